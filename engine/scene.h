// The immutable description of a simulation: surface, body, potentials, initial state, integrator.
// Every field has a default; units are "any consistent set", angles in radians.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "engine/surface.h"

namespace spinfold {

enum class BodyModel {
  affine,  // the internal matrix L is free: 4 deformation degrees of freedom (physics.md §2)
  rigid,   // gyroscope: L = λ₀ U(θ), only the angle θ is integrated (physics.md §8.8)
  // det L held at its initial value λμ: 3 internal degrees of freedom, integrated by RATTLE on the
  // level set inside split4/split6 (physics.md §15)
  incompressible,
};

// J^{AB} in the body frame (the e_A indices), row-major as the scene gives it [mass·length²].
// Valid when symmetric (J12 = J21) and positive definite (J11 > 0, J11 J22 − J12² > 0).
struct InertiaMatrix {
  double J11 = 0.1, J12 = 0.0, J21 = 0.0, J22 = 0.1;  // [mass·length²]
};

struct Body {
  double mass = 1.0;     // m [mass]
  double inertia = 0.1;  // J [mass·length²]: isotropic J^{AB} = J δ^{AB} (when inertia_matrix is absent)
  BodyModel model = BodyModel::affine;
  // Anisotropic J^{AB} (physics.md §13); when set it is the inertia and `inertia` is unused. The
  // scene format writes both as body.inertia: a number or [[J11, J12], [J21, J22]].
  std::optional<InertiaMatrix> inertia_matrix = std::nullopt;
};

// V_r = g/sin²(r/R) on S², g/(R² sinh²(r/R)) on H², g/r² on the plane (physics.md §5, paper's
// normalisations kept). A barrier at the chart pole(s) for g > 0.
struct RadialPotential {
  double gamma = 0.0;  // g [energy] on S², [energy·length²] on H² and the plane
};

// V = A/x² + B/y² + C(x² + y²), x² = ‖L‖²/2 − det L, y² = ‖L‖²/2 + det L (physics.md §5).
// A zero coefficient means the term is absent (x = 0 is then regular).
struct AbcPotential {
  double A = 0.0;  // [energy]
  double B = 0.0;  // [energy]
  double C = 0.0;  // [energy]
};

enum class PolarForm {
  cot2,     // W = ĝ cot²(2ε): matches the paper's action variable (default)
  literal,  // W = ĝ cot²(2ε)/sin²ε: the potential as printed
};

// V = g̃/ς + W(ε)/ς² with x = ς sin ε, y = ς cos ε (physics.md §5).
struct PolarPotential {
  double ghat = 0.0;    // ĝ [energy]
  double gtilde = 0.0;  // g̃ [energy]
  PolarForm form = PolarForm::cot2;
};

using DeformationPotential = std::variant<std::monostate, AbcPotential, PolarPotential>;

// V_h = m g z: uniform gravity along −z, z the embedded height (physics-surfaces.md §5).
struct GravityPotential {
  double g = 0.0;  // [length/time²]
};
// V_h = k z²/2: a spring pulling the body towards the plane z = 0.
struct SpringPotential {
  double k = 0.0;  // [energy/length²]
};
using HeightPotential = std::variant<std::monostate, GravityPotential, SpringPotential>;

struct Potentials {
  std::optional<RadialPotential> radial;  // absent: no radial force
  DeformationPotential deformation;       // monostate: no deformation force
  HeightPotential height;                 // monostate: none (the sphere and where the curvature varies)
};

// Rayleigh's dissipation R = γ_t/2 |V|² + γ_i/2 Σ_A |De_A/Dt|² (physics-surfaces.md §13): viscous
// friction in translation and in the internal motion, relative to parallel transport. dE/dt = −2R.
struct Friction {
  double translational = 0.0;  // γ_t [mass/time]
  double internal = 0.0;       // γ_i [mass·length²/time]
  bool any() const { return translational != 0.0 || internal != 0.0; }
};

// Initial state in the paper's coordinates: L = U(α) diag(λ, μ) U(β)ᵀ in the frame
// E₁ = ∂/∂r, E₂ = (1/S)∂/∂φ (physics.md §2). For the rigid model λ is the scale λ₀, μ must equal
// λ, and only α − β (the angle θ) and its rate matter.
//
// spin, speed and heading are the physical alternatives to the rates, as given by the scene: when
// set, the reader has filled alpha_dot (from spin) or r_dot and phi_dot (from speed and heading)
// with engine/initial_rates.h's resolve_initial_rates, and the writer writes them back instead of
// those rates. A scene built in code that sets them calls resolve_initial_rates itself.
//
// On a surface whose curvature varies the position along the profile is u (with u_dot) instead of
// r, and the frame is E₁ = X_u/f, E₂ = X_φ/ρ (physics-surfaces.md §1).
struct InitialState {
  double r = 1.0;           // geodesic distance from the pole [length]
  double phi = 0.0;         // [rad]
  double alpha = 0.0;       // [rad]
  double beta = 0.0;        // [rad]
  double lambda = 1.0;      // [length·(body unit)⁻¹], > 0
  double mu = 1.0;          // > 0
  double r_dot = 0.0;       // [length/time]
  double phi_dot = 0.0;     // [rad/time]
  double alpha_dot = 0.0;   // [rad/time]
  double beta_dot = 0.0;    // [rad/time]
  double lambda_dot = 0.0;  // [1/time]
  double mu_dot = 0.0;      // [1/time]
  // s = p_α = J[(λ² + μ²)(α̇ + Cφ̇) − 2λμβ̇] [mass·length²/time] (physics.md §3): replaces alpha_dot
  std::optional<double> spin = std::nullopt;
  // v = √(ṙ² + S²φ̇²) ≥ 0 [length/time], with heading: replaces r_dot and phi_dot
  std::optional<double> speed = std::nullopt;
  // angle of the velocity from E₁ = ∂/∂r towards E₂ = (1/S)∂/∂φ [rad], with speed
  std::optional<double> heading = std::nullopt;
  // Where the curvature varies, in place of r and r_dot (last, so that positional initialisers of
  // the constant-curvature fields keep their meaning):
  double u = 0.0;      // the profile parameter (physics-surfaces.md §1) [rad or length]
  double u_dot = 0.0;  // [per time]
  // On a formula surface, in place of a chart: the start point (brought onto F = 0 along ∇F by
  // Newton; a graph keeps x, y and takes z = f(x, y)) [length], and the frame there by the
  // convention of physics-anysurface.md §5 (E₁ along the world x-axis's tangential part); the
  // velocity is speed and heading only.
  std::array<double, 3> X = {1.0, 0.0, 0.0};
};

// What the integrator steps where the curvature varies.
enum class Stepping {
  automatic,  // only the orbit where the internal motion has a closed form (physics-surfaces.md §4)
  full,       // every number of the chart-free state (a check of the above, or a benchmark's baseline)
};

// Whether the state is brought back onto the surface after each step where the curvature varies
// (engine/constraint_projection.h, physics-anysurface.md §8).
enum class Projection {
  automatic,  // on wherever the curvature varies (2.6-3x less error for the same evaluations:
              // docs/performance.md); the polar chart needs none
  on,
  off,
};

struct IntegratorSettings {
  std::string name = "auto";  // a catalog name (integrator.h), or "auto": the engine chooses
  double dt = 0.01;           // [time]: the step of fixed-step methods, the first trial step otherwise
  double tolerance = 1e-10;   // relative and absolute error per step of adaptive methods
  Stepping stepping = Stepping::automatic;
  Projection projection = Projection::automatic;
};

enum class OnDegenerate {
  report,  // follow the motion through det L = 0 and record the event (default)
  stop,    // stop with status degenerate_frame and keep the last state with det L > 0
};

// A second body on the same surface under the same radial or height potential and friction, with its own
// body, deformation potential, initial state and integrator (test bodies do not interact: each is its own
// run). The scene format writes it as a JSON merge patch over the main body's blocks (codec/scene_json.h);
// here it is the expanded result.
struct Companion {
  std::string label;                           // legend text ("" → "body N")
  std::optional<std::array<double, 3>> color;  // sRGB in [0, 1]; none: the renderer's palette
  bool geodesic = false;  // the point-particle companion (zero spin, rigid), drawn dashed
  Body body;
  DeformationPotential deformation;
  InitialState initial;
  IntegratorSettings integrator;
};

inline constexpr std::size_t kMaxCompanions = 8;

struct Scene {
  std::string name;         // preset name, informational
  std::string description;  // one line, informational
  Surface surface;
  Body body;
  Potentials potential;
  std::optional<Friction> friction;  // absent: none
  InitialState initial;
  IntegratorSettings integrator;
  OnDegenerate on_degenerate = OnDegenerate::report;
  std::vector<Companion> companions;  // at most kMaxCompanions
  // The scene format's "companions" and "vary" blocks as written (JSON text, "" when absent): the
  // writer gives them back, and a change of the main body's blocks reaches the companions through
  // them (each is a merge patch over those blocks).
  std::string companions_source;
  // The main body's label in legends and tables beside its companions' ("": "body 1"). A fan
  // ("vary") names it by its own value of the varied field, as the fan names the others ("spin = 0").
  std::string main_label;
};

// Companion i as a scene of its own: the main scene's surface, radial and height potentials, friction
// and degenerate policy with the companion's body, deformation potential, initial state and integrator.
Scene companion_scene(const Scene& scene, std::size_t i);

// Companion i's label: its own, else "body i+2" (the main body is body 1).
std::string companion_label(const Scene& scene, std::size_t i);
// The main body's label: scene.main_label, else "body 1".
std::string main_body_label(const Scene& scene);

}  // namespace spinfold
