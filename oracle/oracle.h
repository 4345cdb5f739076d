// An independent reference for the engine (issue 22, item 5): the chart-free embedding equations of
// physics.md §7 (with §13's anisotropic inertia, §15's det L constraint and §8.8's rigid body)
// integrated in extended precision by Gragg–Bulirsch–Stoer extrapolation. It shares no code with
// engine/: its own scene structs and JSON reading, its own conversion of the scene's initial values
// into the embedding, its own potentials (derivatives by dual numbers) and its own stepper.
//
// The start is moved to the origin of the embedding by an exact isometry (a rotation on S², a Lorentz
// boost on H², a Euclidean motion on the plane) built in 50-digit arithmetic: in those coordinates
// the body's frame at the start is (1,0,0), (0,1,0) whatever r₀ is, so a start at r₀ = 30R has
// components of size 1, not e^30, and the integration is as well-conditioned as one at the pole.
//
// Where the curvature varies (torus, spheroid, bump, catenoid; physics-surfaces.md) it integrates
// §7's implicit-surface equations from F, ∇F and Hess F alone (its own formulas for them), with the
// spin–curvature force written the other way round from the engine's (K s n × V with K from the
// bordered Hessian for the affine body, §7's shape-operator bracket for the rigid one), §5's height
// potentials and §13's friction; the start frame is the scene's own (no isometry: these surfaces have
// only the rotations about the z-axis). Along the run it also integrates the energy friction took,
// ∫2R dt, so E(T) + ∫2R dt = E(0) checks §13's balance dE/dt = −2R.
#pragma once

#include <array>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace spinfold::oracle {

// 50 significant digits: the comparison's transforms (the engine's chart matrices far out on H²
// have entries of e^30 ≈ 1e13; their products cancel to O(1)).
using Big = boost::multiprecision::cpp_bin_float_50;

enum class Kind { sphere, pseudosphere, plane, torus, spheroid, bump, catenoid, formula };
// The surfaces whose curvature varies, given by an implicit F(X) = 0: the surfaces of revolution
// (their F written out here) and a formula's (read by oracle/formula.h: F, or z − f for a graph).
inline bool implicit_kind(Kind k) {
  return k == Kind::torus || k == Kind::spheroid || k == Kind::bump || k == Kind::catenoid ||
         k == Kind::formula;
}
class OracleFormula;
enum class Model { affine, rigid, incompressible };
enum class DefKind { none, abc, polar };
enum class HeightKind { none, gravity, spring };

// What the oracle reads of a scene (the main body only; companions are not compared).
struct OracleScene {
  Kind kind = Kind::sphere;
  double R = 1.0;  // radius (the plane: unused)
  // the varying surfaces' parameters (physics-surfaces.md §1; the scene format's defaults)
  double tube_radius = 1.0, center_radius = 2.5;       // torus a, c
  double equatorial_radius = 1.0, polar_radius = 0.6;  // spheroid a, b
  double bump_height = 1.0, bump_width = 1.0;          // bump h, w
  double neck_radius = 1.0;                            // catenoid c
  HeightKind height = HeightKind::none;
  double height_coefficient = 0;          // gravity g or spring k
  double friction_t = 0, friction_i = 0;  // γ_t, γ_i (§13)
  double mass = 1.0;
  std::array<double, 4> J{0.1, 0.0, 0.0, 0.1};  // J^{AB} row-major
  Model model = Model::affine;
  bool radial = false;
  double g = 0.0;  // radial gamma
  DefKind def = DefKind::none;
  double A = 0, B = 0, C = 0;   // abc
  double ghat = 0, gtilde = 0;  // polar
  bool literal = false;         // polar form
  // a formula surface: F (or a graph's f, with F = z − f) and the start's guess initial.X
  std::shared_ptr<const OracleFormula> formula;
  bool graph = false;
  std::array<double, 3> X{1.0, 0.0, 0.0};
  double u = 0, u_dot = 0;  // the position along the profile where the curvature varies
  double r = 1, phi = 0, alpha = 0, beta = 0, lambda = 1, mu = 1;
  double r_dot = 0, phi_dot = 0, alpha_dot = 0, beta_dot = 0, lambda_dot = 0, mu_dot = 0;
  std::optional<double> spin, speed, heading;
};

// Reads the scene JSON text (nlohmann-json directly, the scene format's fields and defaults).
// Throws std::runtime_error naming the field on what it cannot read.
OracleScene read_scene(std::string_view json_text);

// A body in embedding coordinates (physics.md §7), in the oracle's start frame or in the scene's
// global coordinates.
struct Body3 {
  std::array<Big, 3> X, V, e1, e2, W1, W2;
};

struct OracleRun {
  bool ok = false;
  std::string error;         // why not ok (step size underflow, non-finite, too many steps)
  Body3 start, end;          // in the start frame: the start is at the origin with E₁ = x̂, E₂ = ŷ
  double energy = 0;         // H at the start
  double energy_scale = 0;   // kinetic + |potential| at the start: the yardstick of energy errors
  double end_energy = 0;     // H at the end (the oracle's own drift: ~1e-25)
  Big energy_exact = 0;      // H at the start in full precision
  Big end_energy_exact = 0;  // H at the end in full precision (what the engine's H is compared with)
  double dissipated = 0;     // ∫₀ᵀ 2R dt: the energy friction took (0 without friction)
  double balance = 0;        // |H(T) + ∫2R dt − H(0)| / energy scale: the oracle's own §13 check
  long steps = 0, evaluations = 0;
};

// Integrates the scene from t = 0 to t_end with the per-step tolerance `tolerance` (relative to
// max(1, |y|); 1e-20 is the reference setting), in __float128 (`quad`) or 50-digit Boost (`big`).
enum class Precision { quad, big };
OracleRun run_oracle(const OracleScene& scene, double t_end, double tolerance = 1e-20,
                     Precision precision = Precision::quad, long max_steps = 200000);

// The start isometry: global = S · start_frame (+ translation on the plane).
struct Isometry {
  std::array<std::array<Big, 3>, 3> M;
  std::array<Big, 3> b;
};
Isometry start_isometry(const OracleScene& scene);
// Its inverse applied to a point (translate) or a vector of the global coordinates.
std::array<Big, 3> to_start_point(const OracleScene& scene, const Isometry& iso, const std::array<Big, 3>& x);
std::array<Big, 3> to_start_vector(const OracleScene& scene, const Isometry& iso,
                                   const std::array<Big, 3>& v);

// H of a body given in the start frame (the oracle's own formula: §7's energy).
Big energy_of(const OracleScene& scene, const Body3& body);

// Chart-free distances between the oracle's body at T and the engine's.
struct Difference {
  double position = 0;  // geodesic distance [length]
  double radius =
      0;  // |Δr|, r the geodesic distance from the scene's pole O (varying: from the axis) [length]
  double velocity = 0;  // |ΔV| (tangential part at the oracle's point) [length/time]
  double frame = 0;     // max_A |Δe_A| (tangential part), relative to max_A |e_A|
  double invariants = 0;  // the Gram matrix ⟨u_i, u_j⟩ and ω(u_i, u_j) of u = (V, e₁, e₂, W₁, W₂), relative
  double energy = 0;  // |ΔH| / energy scale
  // What double coordinates can resolve where the body is (the engine's chart matrices and the
  // scene's r, φ have entries of size R cosh(r/R)): ε cosh(r/R) for a position, ε cosh²(r/R) for a
  // vector's components in the local frame. 0 off H².
  double position_floor = 0, vector_floor = 0;
};
// `engine_body`: the engine's body in the start frame; `engine_local`: the same body in the engine's
// own chart coordinates (exact doubles, no large transform): the invariants and the kinetic energy
// come from it, so they do not inherit the chart matrix's round-off far out on H².
Difference compare(const OracleScene& scene, const OracleRun& run, const Body3& engine_body,
                   const Body3& engine_local);

}  // namespace spinfold::oracle
