// A scene on a surface whose curvature varies (torus, spheroid, bump, catenoid), as a run steps it:
// the chart-free state of physics-surfaces.md §7 in run.state.y, built from the scene's initial values
// in the chart (u, φ) and read back into them. Regular at axis points (the spheroid's poles, the
// bump's top), so a body passes over them like any other point.
//
// The state: affine [X, V, e₁, e₂, W₁, W₂] (18 numbers), rigid [X, V, e₁, s] (10), in the embedding ℝ³.
// Where the internal motion has a closed form (an affine body with isotropic J under abc or no internal
// potential, no internal friction; integrator.stepping auto) only the orbit is stepped (§4,
// decoupling): [X, V, E, τ, L₀, M₀], E a parallel-transported tangent, τ the time since L₀, M₀ (the
// frame's components in (E, n × E)), constant, 18 numbers of which the integrator moves 10; e_A and
// W_A at τ are physics.md §8.3's flat motion from L₀, M₀ in the frame (E, n × E).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/embedded_dynamics.h"
#include "engine/integrator.h"
#include "engine/paper_coordinates.h"
#include "engine/scene.h"

namespace spinfold {

// What the equations need of the scene, kept together because EmbeddedModel holds the surface by
// reference: its profile table row, its implicit F, the body and its forces.
struct EmbeddedScene {
  explicit EmbeddedScene(const Scene& scene);
  RevolutionSurface surface;
  RevolutionImplicit implicit;
  SurfaceBody body;
  bool rigid = false;
  bool orbit_only = false;  // steps_orbit_only(scene)
  AbcPotential internal;    // the internal potential of the closed form (zero: none)
  EmbeddedModel model() const { return {implicit, body}; }
};

// Whether the run steps only the orbit (the header's comment says when).
bool steps_orbit_only(const Scene& scene);

// The scene's model (shared by the run's field and its read-outs). The scene's kind must vary.
std::shared_ptr<const EmbeddedScene> make_embedded_scene(const Scene& scene);

// The chart-free state of the scene's initial values (u, φ, L = U(α)diag(λ, μ)U(β)ᵀ in E₁ = X_u/f,
// E₂ = X_φ/ρ, and their rates; physics-surfaces.md §7 "Conversions").
Coords embedded_start(const EmbeddedScene& model, const InitialState& initial);

// dy/dt of the chart-free equations, as a StepProblem's field (the model is kept alive by it).
VectorField embedded_field(std::shared_ptr<const EmbeddedScene> model);

// H = kinetic + potential (kinetic: m|V|²/2 + ½J^{AB}⟨W_A, W_B⟩, or s²/(2I) for the rigid body).
EnergyParts embedded_energy_parts(const EmbeddedScene& model, const Coords& y);
// E_orb = m|V|²/2 + V_h(z) and E_def = the rest [energy].
EmbeddedEnergy embedded_energy_split(const EmbeddedScene& model, const Coords& y);
// det L = det[e₁, e₂, n]; λ₀² = |e₁|² for the rigid body.
double embedded_det(const EmbeddedScene& model, const Coords& y);
// s [angular momentum].
double embedded_spin_of(const EmbeddedScene& model, const Coords& y);
// p_φ = m(X × V)·ẑ + s n·ẑ [angular momentum], conserved without friction.
double embedded_p_phi(const EmbeddedScene& model, const Coords& y);
// Rayleigh's R [energy/time]: dE/dt = −2R (physics-surfaces.md §13).
double embedded_dissipation(const EmbeddedScene& model, const Coords& y);

// The affine body's [X, V, e₁, e₂, W₁, W₂] of a state (the orbit-only one's through the closed form).
Embedded embedded_full_state(const EmbeddedScene& model, const Coords& y);
// The state `y` of `from` in `model`'s layout (the same body; an orbit-only layout starts its closed
// form here, τ = 0): for a change of parameters that changes what is stepped.
Coords embedded_layout(const EmbeddedScene& model, const EmbeddedScene& from, const Coords& y);

// X, V, e_A and W_A of the state (the rigid body's e₂ = n × e₁, W_A = (s/I) n × e_A, I = |e₁|² tr J).
EmbeddedBody embedded_body(const EmbeddedScene& model, const Coords& y);

// The run's state in the chart: u, φ, the paper's internal coordinates of L in (E₁, E₂), their
// rates, X, the curvature K at the body; `undefined` names what an axis point leaves undefined.
// PaperCoordinates::r holds u here.
struct ProfileReadout {
  PaperCoordinates coordinates;   // r is u, r_dot u̇, p_r p_u = m f² u̇
  double K = 0.0;                 // Gaussian curvature at the body [1/length²]
  double speed = 0.0;             // |V| [length/time]
  std::optional<double> heading;  // from E₁ towards E₂ [rad]; none at an axis point
};
ProfileReadout profile_readout(const EmbeddedScene& model, const Coords& y);

// The curvature at a point of the surface [1/length²] (the profile's closed form).
double profile_curvature(const Surface& surface, double u);

}  // namespace spinfold
