#include "engine/embedded_run.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/chart.h"
#include "engine/constraint_projection.h"
#include "engine/exact_solution.h"
#include "engine/formula_surface.h"
#include "engine/implicit_start.h"
#include "engine/inertia.h"
#include "engine/number_text.h"

namespace spinfold {

namespace {

SurfaceBody surface_body(const Scene& scene) {
  SurfaceBody body;
  body.mass = scene.body.mass;
  body.inertia = inertia_of(scene.body);
  body.height = scene.potential.height;
  body.deformation = scene.potential.deformation;
  body.friction = scene.friction.value_or(Friction{});
  return body;
}

Embedded affine_of(const Coords& y) {
  return Embedded(y.head<18>());
}
EmbeddedRigid rigid_of(const Coords& y) {
  return EmbeddedRigid(y.head<10>());
}

}  // namespace

bool steps_orbit_only(const Scene& scene) {
  const DeformationPotential& d = scene.potential.deformation;
  return chart_free(scene.surface) && scene.integrator.stepping == Stepping::automatic &&
         scene.body.model == BodyModel::affine && inertia_of(scene.body).isotropic &&
         (std::holds_alternative<std::monostate>(d) || std::holds_alternative<AbcPotential>(d)) &&
         scene.friction.value_or(Friction{}).internal == 0.0;
}

SurfaceFoot start_foot(const FormulaSurface& surface, const std::array<double, 3>& X) {
  const Vec3 guess(X[0], X[1], X[2]);
  if (surface.form() == FormulaSurfaceForm::graph) {  // §6: keep (x₀, y₀), z₀ = f(x₀, y₀)
    SurfaceFoot foot;
    const Vec3 on(guess.x(), guess.y(), surface.height(guess.x(), guess.y()));
    const ImplicitPoint p = surface.at(on);
    if (on.allFinite() && p.gradient.allFinite() && p.hessian.allFinite())
      foot.X = on;
    else
      foot.refusal = "the formula z = f(x, y) is not defined at (x, y) = (" + shortest(guess.x()) + ", " +
                     shortest(guess.y()) + ") (its value or a derivative is not a finite number)";
    return foot;
  }
  const double scale = std::max(1.0, guess.norm());
  return project_onto_surface(surface, guess, scale, scale);
}

bool projects_onto_constraints(const Scene& scene) {
  switch (scene.integrator.projection) {
    case Projection::on:
    case Projection::automatic: return chart_free(scene.surface);
    case Projection::off: return false;
  }
  return false;
}

EmbeddedScene::EmbeddedScene(const Scene& scene)
    : surface(surface_model_of(scene.surface)),
      body(surface_body(scene)),
      rigid(scene.body.model == BodyModel::rigid),
      orbit_only(steps_orbit_only(scene)),
      project(projects_onto_constraints(scene)) {
  if (!surface->implicit) throw std::logic_error("EmbeddedScene: the surface has its polar chart, not an F");
  if (const AbcPotential* abc = std::get_if<AbcPotential>(&scene.potential.deformation)) internal = *abc;
}

namespace {

// The orbit-only state's parts: [X, V, E, τ] (EmbeddedOrbit), then L₀ and M₀ (row-major) in the frame
// (E, n × E) at τ = 0.
constexpr int kL0 = 10, kM0 = 14;

Mat2 matrix_at(const Coords& y, int i) {
  Mat2 m;
  m << y(i), y(i + 1), y(i + 2), y(i + 3);
  return m;
}

// s = J Σ_A ω(e_A, W_A) of the frame components (isotropic J; constant along the orbit, §6).
double orbit_spin(const EmbeddedScene& model, const Coords& y) {
  const Mat2 L = matrix_at(y, kL0), M = matrix_at(y, kM0);
  return model.body.inertia.J *
         (L(0, 0) * M(1, 0) - L(1, 0) * M(0, 0) + L(0, 1) * M(1, 1) - L(1, 1) * M(0, 1));
}

// The orbit-only state of a body whose frame components in (E, n × E) are L, M.
Coords orbit_state(const Vec3& X, const Vec3& V, const Vec3& E, const Mat2& L, const Mat2& M) {
  Coords y(18);
  y.segment<3>(embedded_orbit::X) = X;
  y.segment<3>(embedded_orbit::V) = V;
  y.segment<3>(embedded_orbit::E) = E;
  y(embedded_orbit::tau) = 0.0;
  y.segment<4>(kL0) << L(0, 0), L(0, 1), L(1, 0), L(1, 1);
  y.segment<4>(kM0) << M(0, 0), M(0, 1), M(1, 0), M(1, 1);
  return y;
}

}  // namespace

Embedded embedded_full_state(const EmbeddedScene& model, const Coords& y) {
  if (!model.orbit_only) return affine_of(y);
  // §4: the internal motion is the flat one in the parallel-transported frame (E, n × E).
  const Vec3 X = y.segment<3>(embedded_orbit::X);
  const Vec3 n = embedded_normal(*model.surface->implicit, X);
  const Vec3 F1 = y.segment<3>(embedded_orbit::E).normalized(), F2 = n.cross(F1);
  const auto [L, M] = flat_internal_motion(model.body.inertia.J, model.internal, matrix_at(y, kL0),
                                           matrix_at(y, kM0), y(embedded_orbit::tau));
  Embedded Y;
  Y.segment<3>(embedded::X) = X;
  Y.segment<3>(embedded::V) = y.segment<3>(embedded_orbit::V);
  for (int A = 0; A < 2; ++A) {
    Y.segment<3>(embedded::e1 + 3 * A) = L(0, A) * F1 + L(1, A) * F2;
    Y.segment<3>(embedded::W1 + 3 * A) = M(0, A) * F1 + M(1, A) * F2;
  }
  return Y;
}

Coords embedded_layout(const EmbeddedScene& model, const EmbeddedScene& from, const Coords& y) {
  if (model.rigid || (!model.orbit_only && !from.orbit_only)) return y;
  const Embedded Y = embedded_full_state(from, y);
  if (!model.orbit_only) return Coords(Y);
  const Vec3 X = Y.segment<3>(embedded::X);
  const Vec3 n = embedded_normal(*model.surface->implicit, X);
  // E: the one carried so far, or the profile's E₁ there (any unit tangent would do)
  Vec3 E = from.orbit_only ? Vec3(y.segment<3>(embedded_orbit::E).normalized()) : Vec3::Zero();
  if (!from.orbit_only) {
    const Vec3 e1 = Y.segment<3>(embedded::e1);
    E = (e1 - e1.dot(n) * n).normalized();
  }
  const Vec3 F2 = n.cross(E);
  Mat2 L, M;
  for (int A = 0; A < 2; ++A) {
    const Vec3 e = Y.segment<3>(embedded::e1 + 3 * A), W = Y.segment<3>(embedded::W1 + 3 * A);
    L(0, A) = E.dot(e), L(1, A) = F2.dot(e);
    M(0, A) = E.dot(W), M(1, A) = F2.dot(W);
  }
  return orbit_state(X, Y.segment<3>(embedded::V), E, L, M);
}

std::shared_ptr<const EmbeddedScene> make_embedded_scene(const Scene& scene) {
  return std::make_shared<const EmbeddedScene>(scene);
}

namespace {

// A formula surface's start (physics-anysurface.md §5, §6): the foot of initial.X, the convention's
// frame there, V, e_A, W_A from speed, heading, L and L̇ (relative to parallel transport: M = L̇).
Coords formula_start(const EmbeddedScene& model, const InitialState& q, const Mat2& L, const Mat2& L_dot) {
  const SurfaceFoot foot = start_foot(*model.surface->formula, q.X);
  if (!foot.X) throw std::invalid_argument("initial.X: " + foot.refusal);
  const StartFrame frame = start_frame(*model.surface->implicit, *foot.X);
  const double v = q.speed.value_or(0.0), heading = q.heading.value_or(0.0);
  if (model.rigid)
    return Coords(
        rigid_start_in_frame(frame, *foot.X, v, heading, L, spin_from_rate(model.body.inertia, L, L_dot)));
  const Embedded Y = affine_start_in_frame(frame, *foot.X, v, heading, L, L_dot);
  if (!model.orbit_only) return Coords(Y);
  return orbit_state(*foot.X, Y.segment<3>(embedded::V), frame.E1, L, L_dot);
}

}  // namespace

Coords embedded_start(const EmbeddedScene& model, const InitialState& q) {
  // §7 "Conversions", with no division by ρ (regular at an axis point): V = f u̇ E₁ + ρ φ̇ E₂,
  // e_A = E_B L_BA, W_A = E_B M_BA with M = L̇ + Cφ̇εL and L̇ = α̇εL − β̇Lε + U(α)diag(λ̇, μ̇)U(β)ᵀ.
  const Mat2 Ua = rotation2(q.alpha), Ub = rotation2(q.beta), eps = epsilon();
  const Mat2 L = Ua * Eigen::Vector2d(q.lambda, q.mu).asDiagonal() * Ub.transpose();
  const Mat2 L_dot = q.alpha_dot * eps * L - q.beta_dot * L * eps +
                     Ua * Eigen::Vector2d(q.lambda_dot, q.mu_dot).asDiagonal() * Ub.transpose();
  if (!model.surface->profile) return formula_start(model, q, L, L_dot);
  const ProfilePoint p = revolution_entry(model.surface->profile->kind).profile(*model.surface->profile, q.u);
  const ProfileMetric metric = profile_metric(p);
  const RevolutionFrame frame = revolution_frame(*model.surface->profile, q.u, q.phi);
  const Mat2 M = L_dot + metric.C * q.phi_dot * eps * L;
  const Vec3 V = metric.f * q.u_dot * frame.E1 + p.rho * q.phi_dot * frame.E2;
  if (model.rigid) {
    EmbeddedRigid Y;
    Y << frame.X, V, L(0, 0) * frame.E1 + L(1, 0) * frame.E2, spin_from_rate(model.body.inertia, L, M);
    return Coords(Y);
  }
  if (model.orbit_only) return orbit_state(frame.X, V, frame.E1, L, M);
  Embedded Y;
  Y.segment<3>(embedded::X) = frame.X;
  Y.segment<3>(embedded::V) = V;
  for (int A = 0; A < 2; ++A) {
    Y.segment<3>(embedded::e1 + 3 * A) = L(0, A) * frame.E1 + L(1, A) * frame.E2;
    Y.segment<3>(embedded::W1 + 3 * A) = M(0, A) * frame.E1 + M(1, A) * frame.E2;
  }
  return Coords(Y);
}

void project_state(const EmbeddedScene& model, Coords& y) {
  if (model.rigid) {
    EmbeddedRigid Y = rigid_of(y);
    project_onto_constraints(*model.surface->implicit, Y, Y.segment<3>(embedded::e1).norm());
    y.head<10>() = Y;
    return;
  }
  if (!model.orbit_only) {
    Embedded Y = affine_of(y);
    project_onto_constraints(*model.surface->implicit, Y);
    y.head<18>() = Y;
    return;
  }
  // [X, V, E, τ, L₀, M₀]: the affine layout's projection of X, V and E (e₁'s place), τ and the rest kept.
  Embedded Y = Embedded::Zero();
  Y.segment<9>(embedded::X) = y.segment<9>(embedded_orbit::X);
  project_onto_constraints(*model.surface->implicit, Y);
  y.segment<9>(embedded_orbit::X) = Y.segment<9>(embedded::X);
}

void carry_onto_surface(const EmbeddedScene& model, Coords& y) {
  const Vec3 X = y.segment<3>(embedded::X);
  const double scale = std::max(1.0, X.norm());
  const SurfaceFoot foot =
      model.surface->formula && model.surface->formula->form() == FormulaSurfaceForm::graph
          ? start_foot(*model.surface->formula, {X.x(), X.y(), X.z()})
          : project_onto_surface(*model.surface->implicit, X, scale, scale);
  if (foot.X) y.segment<3>(embedded::X) = *foot.X;
  project_state(model, y);
}

VectorField embedded_field(std::shared_ptr<const EmbeddedScene> model) {
  return [model](const Coords& y, Coords& dydt) {
    if (model->rigid) {
      EmbeddedRigid d;
      embedded_rigid_vector_field(model->model(), rigid_of(y), d);
      dydt = d;
    } else if (model->orbit_only) {
      EmbeddedOrbit d;
      embedded_orbit_vector_field(model->model(), orbit_spin(*model, y), EmbeddedOrbit(y.head<10>()), d);
      dydt.resize(18);
      dydt.head<10>() = d;
      dydt.tail<8>().setZero();  // L₀, M₀: the closed form's start
    } else {
      Embedded d;
      embedded_vector_field(model->model(), affine_of(y), d);
      dydt = d;
    }
  };
}

EnergyParts embedded_energy_parts(const EmbeddedScene& model, const Coords& y) {
  const SurfaceBody& body = model.body;
  const double orbital_kinetic = 0.5 * body.mass * y.segment<3>(embedded::V).squaredNorm();
  if (model.rigid) {
    const double total = embedded_rigid_energy(model.model(), rigid_of(y));
    const double potential = height_energy(body.height, body.mass, y(embedded::X + 2));
    return {total - potential, potential};
  }
  const Embedded Y = embedded_full_state(model, y);
  const Mat2& J = body.inertia.matrix;
  double internal_kinetic = 0.0;
  for (int A = 0; A < 2; ++A)
    for (int B = 0; B < 2; ++B)
      internal_kinetic +=
          J(A, B) * Y.segment<3>(embedded::W1 + 3 * A).dot(Y.segment<3>(embedded::W1 + 3 * B));
  const double kinetic = orbital_kinetic + 0.5 * internal_kinetic;
  return {kinetic, embedded_energy(model.model(), Y).total() - kinetic};
}

EmbeddedEnergy embedded_energy_split(const EmbeddedScene& model, const Coords& y) {
  if (!model.rigid) return embedded_energy(model.model(), embedded_full_state(model, y));
  const SurfaceBody& body = model.body;
  EmbeddedEnergy e;
  e.orbital = 0.5 * body.mass * y.segment<3>(embedded::V).squaredNorm() +
              height_energy(body.height, body.mass, y(embedded::X + 2));
  e.deformation = embedded_rigid_energy(model.model(), rigid_of(y)) - e.orbital;
  return e;
}

double embedded_det(const EmbeddedScene& model, const Coords& y) {
  if (model.rigid) return y.segment<3>(embedded::e1).squaredNorm();
  return embedded_det_L(model.model(), embedded_full_state(model, y));
}

double embedded_spin_of(const EmbeddedScene& model, const Coords& y) {
  if (model.rigid) return y(embedded::spin);
  if (model.orbit_only) return orbit_spin(model, y);
  return embedded_spin(model.model(), affine_of(y));
}

double embedded_p_phi(const EmbeddedScene& model, const Coords& y) {
  const Vec3 X = y.segment<3>(embedded::X), V = y.segment<3>(embedded::V);
  return model.body.mass * X.cross(V).z() +
         embedded_spin_of(model, y) * embedded_normal(*model.surface->implicit, X).z();
}

double embedded_dissipation(const EmbeddedScene& model, const Coords& y) {
  const Friction& f = model.body.friction;
  if (model.rigid) {
    // W_A = (s/I) n × e_A: Σ|W_A|² = 2|e₁|² s²/I², I = |e₁|² tr J.
    const double e2 = y.segment<3>(embedded::e1).squaredNorm(), s = y(embedded::spin);
    const double I = e2 * model.body.inertia.matrix.trace();
    return 0.5 * f.translational * y.segment<3>(embedded::V).squaredNorm() +
           f.internal * e2 * s * s / (I * I);
  }
  return embedded_rayleigh(model.model(), embedded_full_state(model, y));
}

EmbeddedBody embedded_body(const EmbeddedScene& model, const Coords& y) {
  EmbeddedBody b;
  b.X = y.segment<3>(embedded::X);
  b.V = y.segment<3>(embedded::V);
  if (model.rigid) {
    const Vec3 n = embedded_normal(*model.surface->implicit, b.X);
    b.e[0] = y.segment<3>(embedded::e1);
    b.e[1] = n.cross(b.e[0]);
    const double I = b.e[0].squaredNorm() * model.body.inertia.matrix.trace();
    for (int A = 0; A < 2; ++A) b.W[A] = (y(embedded::spin) / I) * n.cross(b.e[A]);
    return b;
  }
  const Embedded Y = embedded_full_state(model, y);
  for (int A = 0; A < 2; ++A) {
    b.e[A] = Y.segment<3>(embedded::e1 + 3 * A);
    b.W[A] = Y.segment<3>(embedded::W1 + 3 * A);
  }
  return b;
}

double profile_curvature(const Surface& surface, double u) {
  const RevolutionSurface s = revolution_surface(surface);
  return revolution_entry(s.kind).profile(s, u).K;
}

ProfileReadout profile_readout(const EmbeddedScene& model, const Coords& y) {
  const RevolutionEntry& entry = revolution_entry(model.surface->profile->kind);
  const Vec3 X = y.segment<3>(embedded::X), V = y.segment<3>(embedded::V);
  const double u = entry.u_of(*model.surface->profile, X);
  const double phi = std::atan2(X.y(), X.x());
  const ProfilePoint p = entry.profile(*model.surface->profile, u);
  const ProfileMetric metric = profile_metric(p);
  const RevolutionFrame frame = revolution_frame(*model.surface->profile, u, phi);
  const bool axis = std::hypot(X.x(), X.y()) == 0.0 || p.rho == 0.0;
  const double m = model.body.mass;

  const EmbeddedBody body = embedded_body(model, y);
  const Vec3(&e)[2] = body.e;
  const Vec3(&W)[2] = body.W;
  const Vec3 E[2] = {frame.E1, frame.E2};
  Mat2 L, M;
  for (int A = 0; A < 2; ++A)
    for (int B = 0; B < 2; ++B) {
      L(B, A) = E[B].dot(e[A]);
      M(B, A) = E[B].dot(W[A]);
    }
  const double v1 = V.dot(frame.E1), v2 = V.dot(frame.E2);

  ProfileReadout out;
  PaperCoordinates& c = out.coordinates;
  c.r = u;
  c.X = X;
  c.det_L = embedded_det(model, y);
  c.p_alpha = embedded_spin_of(model, y);
  c.p_phi = embedded_p_phi(model, y);
  // p_β = −tr((Lε)ᵀP), P = MJ: the frame-independent vorticity (physics.md §3).
  c.p_beta = -(L * epsilon()).cwiseProduct(momentum_from_rate(model.body.inertia, M)).sum();
  out.K = p.K;
  out.speed = V.norm();
  c.r_dot = v1 / metric.f;
  c.p_r = m * metric.f * v1;  // p_u = m f² u̇
  // L̇ = M − Cφ̇εL in (E₁, E₂); at an axis point φ̇ and the frame's angles are undefined.
  Mat2 L_dot = M;
  const double phi_dot = axis ? 0.0 : v2 / p.rho;
  if (!axis) L_dot -= metric.C * phi_dot * epsilon() * L;
  const BodyModel body_model = model.rigid ? BodyModel::rigid : BodyModel::affine;
  set_internal_coordinates(c, L, L_dot, M, model.body.inertia, body_model, !axis);
  if (axis) {
    const std::string why = "the body is on the axis (rho = 0), where phi and E2 = X_phi/rho are undefined";
    for (const char* f : {"phi", "phi_dot", "heading"}) c.undefined.push_back({f, why});
    for (const char* f : {"alpha", "beta", "theta", "alpha_dot", "beta_dot", "theta_dot", "L"})
      c.undefined.push_back({f, why});
    return out;
  }
  c.phi = phi;
  c.phi_dot = phi_dot;
  out.heading = std::atan2(v2, v1);
  return out;
}

FreeReadout free_readout(const EmbeddedScene& model, const Coords& y) {
  FreeReadout out;
  out.body = embedded_body(model, y);
  const Vec3& X = out.body.X;
  const ImplicitPoint p = model.surface->implicit->at(X);
  out.normal = embedded_normal(*model.surface->implicit, X);
  out.K = bordered_hessian_curvature(p);
  out.speed = out.body.V.norm();
  out.distance = std::abs(p.F) / p.gradient.norm();
  double tangency = 0.0;
  for (const Vec3& u : {out.body.V, out.body.e[0], out.body.e[1], out.body.W[0], out.body.W[1]})
    tangency = std::max(tangency, std::abs(u.dot(out.normal)));
  out.tangency = tangency;

  const StartFrame frame = start_frame(*model.surface->implicit, X);
  const Vec3 E[2] = {frame.E1, frame.E2};
  Mat2 L, M;
  for (int A = 0; A < 2; ++A)
    for (int B = 0; B < 2; ++B) {
      L(B, A) = E[B].dot(out.body.e[A]);
      M(B, A) = E[B].dot(out.body.W[A]);
    }
  PaperCoordinates& c = out.coordinates;
  c.X = X;
  c.det_L = embedded_det(model, y);
  c.p_alpha = embedded_spin_of(model, y);
  c.p_phi = embedded_p_phi(model, y);
  c.p_beta = -(L * epsilon()).cwiseProduct(momentum_from_rate(model.body.inertia, M)).sum();
  set_internal_coordinates(c, L, M, M, model.body.inertia, model.rigid ? BodyModel::rigid : BodyModel::affine,
                           true);
  const std::string why = "a formula surface has no chart: the position is X, the velocity V";
  for (const char* f : {"phi", "phi_dot"}) c.undefined.push_back({f, why});
  c.r_dot.reset();
  c.p_r.reset();
  c.phi.reset();
  c.phi_dot.reset();
  return out;
}

}  // namespace spinfold
