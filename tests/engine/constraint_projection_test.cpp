// Projection onto the constraints after each step (engine/constraint_projection.h), measured as
// physics-anysurface.md §8 measured it: an affine body (abc, gravity) on WF1's triaxial ellipsoid and
// a spinning rigid body on WF3's genus-2 surface, dop853 at 1e-10 to T = 20, with and without
// projection, against Boost.Odeint's RKF78 at 1e-14 (an independent integrator).
#include "engine/constraint_projection.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/field_stepping.h"
#include "engine/formula_surface.h"
#include "engine/implicit_start.h"
#include "engine/integrator.h"
#include "tests/engine/formula_examples.h"
#include "tests/engine/revolution_examples.h"

namespace spinfold {
namespace {

FormulaSurface surface(std::string_view text, const FormulaParameters& p) {
  FormulaSurfaceParse parsed = parse_formula_surface(FormulaSurfaceForm::implicit, text, p);
  EXPECT_TRUE(parsed.surface) << parsed.error.reason;
  return std::move(*parsed.surface);
}

template <int N, class Field>
Eigen::Matrix<double, N, 1> reference(const Field& field, const Eigen::Matrix<double, N, 1>& Y0, double T) {
  return test::rkf78<N>(field, Y0, T, 1e-14);
}

struct Measured {
  ConstraintResidual worst;  // over the run, after each step (and its projection)
  double error = 0.0;        // max-norm of the state's difference from the reference at T
};

// dop853 at 1e-10 to T, each accepted step's residual measured after `project` (if any) ran.
template <int N, class Field, class Project>
Measured run(const ImplicitSurface& s, const Field& field, const Eigen::Matrix<double, N, 1>& Y0, double T,
             const Eigen::Matrix<double, N, 1>& ref, const Project& project, bool projecting) {
  const VectorField f = [&](const Coords& y, Coords& dy) {
    Eigen::Matrix<double, N, 1> d;
    field(Eigen::Matrix<double, N, 1>(y), d);
    dy = d;
  };
  const Scene unused_scene;
  const Chart unused_chart;
  const StepProblem problem{unused_scene, unused_chart, &f};
  Measured m;
  const auto after = [&](Coords& y) {
    Eigen::Matrix<double, N, 1> Y = y;
    if (projecting) project(Y);
    const ConstraintResidual r = constraint_residual(s, Y);
    m.worst.distance = std::max(m.worst.distance, r.distance);
    m.worst.tangency = std::max(m.worst.tangency, r.tangency);
    y = Y;
  };
  std::unique_ptr<Integrator> dop853 = find_integrator("dop853")->make();
  const FieldRun end = step_field(*dop853, problem, Coords(Y0), T, 1e-3, 1e-10, after);
  EXPECT_TRUE(end.ok);
  m.error = (Eigen::Matrix<double, N, 1>(end.y) - ref).template lpNorm<Eigen::Infinity>();
  return m;
}

TEST(ConstraintProjection, AnAffineBodyOnATriaxialEllipsoidStaysOnItsConstraintsToRoundOff) {
  const FormulaSurface ellipsoid =
      surface("x^2/a^2 + y^2/b^2 + z^2/c^2 - 1", {{"a", 2}, {"b", 1.5}, {"c", 1}});
  const SurfaceFoot foot = project_onto_surface(ellipsoid, Vec3(1.0, 0.8, 0.5), 1.0, 1.0);
  ASSERT_TRUE(foot.X);
  const StartFrame frame = start_frame(ellipsoid, *foot.X);
  const Mat2 L = rotation2(0.3) * Eigen::Vector2d(1.1, 0.7).asDiagonal() * rotation2(-0.2).transpose();
  Mat2 L_dot;
  L_dot << 0.05, 0.3, -0.2, 0.1;
  const Embedded Y0 = affine_start_in_frame(frame, *foot.X, 0.8, 0.4, L, L_dot);
  SurfaceBody body;
  body.mass = 1.5;
  body.inertia = test::inertia_matrix(0.5, 0.1, 0.35);
  body.height = GravityPotential{0.8};
  body.deformation = AbcPotential{0.01, 0.2, 0.3};
  const EmbeddedModel model{ellipsoid, body};
  const auto field = [&](const Embedded& y, Embedded& d) { embedded_vector_field(model, y, d); };
  const double T = 20.0;
  const Embedded ref = reference<18>(field, Y0, T);
  const auto project = [&](Embedded& y) { project_onto_constraints(ellipsoid, y); };
  const Measured free = run<18>(ellipsoid, field, Y0, T, ref, project, false);
  const Measured projected = run<18>(ellipsoid, field, Y0, T, ref, project, true);
  std::printf("ellipsoid, affine: distance %.2g → %.2g, tangency %.2g → %.2g, state error %.2g → %.2g\n",
              free.worst.distance, projected.worst.distance, free.worst.tangency, projected.worst.tangency,
              free.error, projected.error);
  EXPECT_GT(free.worst.distance, 1e-13);  // the drift a step's tolerance leaves
  EXPECT_LT(projected.worst.distance, 1e-15);
  EXPECT_LT(projected.worst.tangency, 1e-15);
  EXPECT_LT(projected.error, free.error);  // closed surfaces: the reference measured 2–11× smaller
}

TEST(ConstraintProjection, ARigidBodyOnAGenusTwoSurfaceKeepsItsLength) {
  const FormulaSurface genus2 =
      surface("((x^2 + y^2)^2 - 2*a^2*(x^2 - y^2))^2 + (z/c)^2 - r^2", {{"a", 1.0}, {"c", 0.5}, {"r", 0.7}});
  const SurfaceFoot foot = project_onto_surface(genus2, Vec3(1.2, 0.3, 0.2), 1.0, 1.0);
  ASSERT_TRUE(foot.X);
  const double lambda0 = 0.8;
  const EmbeddedRigid Y0 =
      rigid_start_in_frame(start_frame(genus2, *foot.X), *foot.X, 0.5, 1.0, lambda0 * rotation2(0.4), 0.6);
  SurfaceBody body;
  body.inertia = test::inertia_matrix(0.25, 0.0, 0.25);
  const EmbeddedModel model{genus2, body};
  const auto field = [&](const EmbeddedRigid& y, EmbeddedRigid& d) {
    embedded_rigid_vector_field(model, y, d);
  };
  const double T = 10.0;
  const EmbeddedRigid ref = reference<10>(field, Y0, T);
  double worst_length = 0.0;
  const auto project = [&](EmbeddedRigid& y) {
    project_onto_constraints(genus2, y, lambda0);
    worst_length = std::max(worst_length, std::abs(y.segment<3>(embedded::e1).norm() - lambda0));
  };
  const Measured free = run<10>(genus2, field, Y0, T, ref, project, false);
  const Measured projected = run<10>(genus2, field, Y0, T, ref, project, true);
  std::printf("genus 2, rigid: distance %.2g → %.2g, tangency %.2g → %.2g, state error %.2g → %.2g\n",
              free.worst.distance, projected.worst.distance, free.worst.tangency, projected.worst.tangency,
              free.error, projected.error);
  EXPECT_LT(projected.worst.distance, 1e-15);
  EXPECT_LT(projected.worst.tangency, 1e-15);
  EXPECT_LT(worst_length, 1e-15);
  EXPECT_LT(projected.worst.distance, free.worst.distance);
  EXPECT_LT(projected.error, 2.0 * free.error);
}

}  // namespace
}  // namespace spinfold
