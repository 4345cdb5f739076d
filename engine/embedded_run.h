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
#include "engine/formula_surface.h"
#include "engine/implicit_start.h"
#include "engine/integrator.h"
#include "engine/paper_coordinates.h"
#include "engine/scene.h"
#include "engine/surface_model.h"

namespace spinfold {

// What the equations need of the scene, kept together because EmbeddedModel holds the surface by
// reference: the surface's model (its implicit F, its profile chart or formula where it has one), the
// body and its forces.
struct EmbeddedScene {
  explicit EmbeddedScene(const Scene& scene);
  std::shared_ptr<const SurfaceModel> surface;  // surface_model_of(scene.surface): implicit set
  SurfaceBody body;
  bool rigid = false;
  bool orbit_only = false;  // steps_orbit_only(scene)
  bool project = false;     // projects_onto_constraints(scene)
  AbcPotential internal;    // the internal potential of the closed form (zero: none)
  EmbeddedModel model() const { return {*surface->implicit, body}; }
};

// Whether the run steps only the orbit (the header's comment says when).
bool steps_orbit_only(const Scene& scene);

// Whether the run brings its state back onto the constraints after each accepted step
// (engine/constraint_projection.h): integrator.projection, whose auto is on wherever the run is
// chart-free (physics-anysurface.md §8; docs/performance.md measures what it buys).
bool projects_onto_constraints(const Scene& scene);

// The state `y` carried onto the model's surface from off it (after a change of the formula): X to
// its foot by Newton along ∇F (as far as max(1, |X|)), then project_state. Where there is no foot,
// project_state alone (the run's checks stop it if that is not enough).
void carry_onto_surface(const EmbeddedScene& model, Coords& y);

// The state `y` brought back onto the constraints: X onto F = 0, then V, e_A, W_A (the orbit-only
// layout's V and E) onto the tangent plane there; the rigid body's e₁ keeps its length.
void project_state(const EmbeddedScene& model, Coords& y);

// The scene's model (shared by the run's field and its read-outs). The scene's kind must vary.
std::shared_ptr<const EmbeddedScene> make_embedded_scene(const Scene& scene);

// The chart-free state of the scene's initial values: on a surface of revolution u, φ,
// L = U(α)diag(λ, μ)U(β)ᵀ in E₁ = X_u/f, E₂ = X_φ/ρ, and their rates (physics-surfaces.md §7
// "Conversions"); on a formula surface X brought onto F = 0, the frame of physics-anysurface.md §5
// there, speed, heading, L and its rates relative to parallel transport. std::invalid_argument
// naming initial.X when the start has no foot on the surface (the validator says so first).
Coords embedded_start(const EmbeddedScene& model, const InitialState& initial);

// The foot on a formula surface of initial.X (physics-anysurface.md §6), or why there is none: Newton
// along ∇F on an implicit surface (a move of at most max(1, |X|)), z = f(x, y) on a graph.
SurfaceFoot start_foot(const FormulaSurface& surface, const std::array<double, 3>& X);

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

// The run's state on a surface with no chart (a formula surface): the body in ℝ³, the normal, K at
// the body and how far the state is off its constraints; the paper's internal coordinates of L in
// the convention's frame at X (physics-anysurface.md §5: E₁ along the world x-axis's tangential
// part), with rates relative to parallel transport, so that at t = 0 they read back as the scene
// gave them. PaperCoordinates::r, r_dot, p_r, phi and phi_dot are not defined (no chart).
struct FreeReadout {
  PaperCoordinates coordinates;
  EmbeddedBody body;
  Vec3 normal = Vec3::UnitZ();
  double K = 0.0;         // Gaussian curvature at the body [1/length²], from F (§1)
  double speed = 0.0;     // |V| [length/time]
  double distance = 0.0;  // |F|/|∇F| at X [length]: the drift off the surface
  double tangency = 0.0;  // the largest normal part of V, e_A, W_A [their units]
};
FreeReadout free_readout(const EmbeddedScene& model, const Coords& y);

// The curvature at a point of the surface [1/length²] (the profile's closed form).
double profile_curvature(const Surface& surface, double u);

}  // namespace spinfold
