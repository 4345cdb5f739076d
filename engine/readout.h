// The read-out of a run: every number a person or a client is shown about the current state,
// computed once. The JSON sample (codec/sample_json.h) and the HUD (render/snapshot.h) are both
// made from it, so they cannot disagree.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/actions.h"
#include "engine/invariants.h"
#include "engine/paper_coordinates.h"
#include "engine/simulation.h"

namespace spinfold {

struct Readout {
  double t = 0.0;                   // [time]
  PaperCoordinates coordinates;     // r, φ, α, β, θ, λ, μ, their rates and momenta, X, L (paper's)
  double energy = 0.0;              // H [energy]
  double energy_error = 0.0;        // (H − H₀)/max(|H₀|, 1e-300), H₀ = run.initial_energy [1]
  double energy_reference_t = 0.0;  // when H₀ was measured: the start or the last change [time]
  double energy_orbital = 0.0;      // E_orb = m⟨V,V⟩/2 + V_r [energy]
  double energy_deformation = 0.0;  // E_def = H − E_orb [energy]
  double spin = 0.0;                // s = p_α [mass·length²/time]
  std::optional<double> speed;  // v = √(ṙ² + S(r)²φ̇²) [length/time]; none where ṙ is undefined
  std::optional<double> heading;  // h = atan2(S(r)φ̇, ṙ), from E₁ = ∂/∂r towards E₂ [rad]; none at a pole
  double vorticity = 0.0;                      // p_β = −tr((Lε)ᵀP) [mass·length²/time]
  double det_L = 0.0;                          // det L, frame-independent [1]
  std::optional<SeparatedEnergies> separated;  // C_x, C_y [energy] (abc or no deformation, affine)
  std::optional<Vec3> momentum_map;            // M (physics.md §6), when defined
  std::optional<double> casimir;               // MᵀηM, on S² and H² without a radial potential
  // Values computed but not shown because they lost their digits (M far out on H²), with the reason.
  std::vector<UndefinedValue> undefined;
  // Where the curvature varies: the Gaussian curvature K at the body [1/length²], and
  // coordinates.r, r_dot, p_r hold u, u̇, p_u (the sample names them so); none elsewhere.
  std::optional<double> curvature;
  // On a surface with no chart (a formula surface): the body in ℝ³ and the constraints' drift
  // (engine/embedded_run.h FreeReadout); coordinates.r, r_dot, p_r are then not defined.
  struct Embedded {
    Vec3 V, e1, e2, n;      // [length/time], [length], [length], [1]
    double drift = 0.0;     // |F|/|∇F| at X [length]
    double tangency = 0.0;  // largest normal part of V, e_A, W_A
  };
  std::optional<Embedded> embedded;
  // Action variables and frequencies of the separable scenes (engine/actions.h); none with the
  // reason in actions_unsupported otherwise.
  std::optional<ActionVariables> actions;
  std::string actions_unsupported;
  Status status = Status::ok;
  std::string_view status_name;    // status_name(status), e.g. "ok"
  std::string_view status_detail;  // status_description(status): one sentence
  std::string_view integrator;     // catalog name of the integrator that runs (auto resolved)
  std::uint64_t steps = 0;         // accepted steps of the run's step sequence
};

// The read-out of the run's current state (run.state).
Readout readout(const Simulation& run);

// The read-out as the HUD's lines of text: time, energy error, integrator (and whether it stopped),
// the surface and body of `scene` (the run's), spin and det L.
std::vector<std::string> readout_lines(const Scene& scene, const Readout& readout);
// Which of readout_lines names the surface (and K at the body where it varies): what a view adds
// about the surface there goes on it.
inline constexpr std::size_t kSurfaceReadoutLine = 3;

// The read-out in plain words for a class: the time, the surface line of readout_lines (K at the
// body where it varies) and the spin; nothing a class has not met (energy error, integrator,
// inertia, det L).
std::vector<std::string> plain_readout_lines(const Scene& scene, const Readout& readout);
inline constexpr std::size_t kPlainSurfaceLine = 1;

// The action variables and frequencies as HUD lines ("J_r = …", "nu_r = …"; "-" where undefined),
// or one line saying why the scene has none.
std::vector<std::string> action_lines(const Readout& readout);

// A companion's read-out as one compact HUD line: "label: spin = …  energy error = …", with
// "[stopped: status]" when it stopped.
std::string companion_readout_line(std::string_view label, const Readout& readout);

}  // namespace spinfold
