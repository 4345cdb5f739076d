// Anisotropic inertia J^{AB} (physics.md §13): the worked example W7, isotropic matrix = number bit for
// bit, spin conserved while the vorticity is not, the exact solution's reach, initial spin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/exact_solution.h"
#include "engine/inertia.h"
#include "engine/initial_rates.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "engine/validation.h"
#include "engine/worked_examples.h"
#include "test_support.h"

namespace spinfold {
namespace {

// W5's sphere, radial and abc potentials and start (physics.md §10), with J = [[0.3, 0.08], [0.08, 0.15]].
Scene anisotropic_scene() {
  Scene s = w5_scene();
  s.body.inertia_matrix = InertiaMatrix{0.3, 0.08, 0.08, 0.15};
  return s;
}

using test::matrix;

// W7 (physics.md §13, docs/physics_inertia_check.py): sphere R = 1, m = 2, no potential,
// J = [[0.3, 0.05], [0.05, 0.1]], r = 1, φ = 0.5, ṙ = 0.2, φ̇ = −0.3, L = [[1.5, 0.2], [−0.1, 0.5]],
// M = L̇ + Cφ̇εL = [[0.1, 0.3], [−0.4, 0.2]].
TEST(AnisotropicInertia, WorkedExampleW7) {
  Scene scene;
  scene.surface = {SurfaceKind::sphere, 1.0};
  scene.body = {2.0, 0.1, BodyModel::affine};
  scene.body.inertia_matrix = InertiaMatrix{0.3, 0.05, 0.05, 0.1};
  const Mat2 L = matrix(1.5, 0.2, -0.1, 0.5);
  // P = MJ with M = [[0.1, 0.3], [−0.4, 0.2]], by hand: P_BA = M_B1 J_1A + M_B2 J_2A.
  const Mat2 P = matrix(0.1 * 0.3 + 0.3 * 0.05, 0.1 * 0.05 + 0.3 * 0.1, -0.4 * 0.3 + 0.2 * 0.05,
                        -0.4 * 0.05 + 0.2 * 0.1);
  Coords y(coord::affine_size);
  y << 1.0, 0.5, 2.0 * 0.2, -0.52101786140867159, L(0, 0), L(0, 1), L(1, 0), L(1, 1), P(0, 0), P(0, 1),
      P(1, 0), P(1, 1);
  const Chart chart;
  EXPECT_NEAR(hamiltonian(scene, chart, y), 0.13322660764462141, 1e-15);
  EXPECT_NEAR(spin_of(scene, y), -0.178, 1e-15);
  State state;
  state.y = y;
  EXPECT_NEAR(vorticity(scene, state), 0.0985, 1e-15);
  Coords f;
  vector_field(scene, chart, y, f);
  const double L_dot[4] = {0.11620906917604419, 0.21895465411977904, -0.15686396235933713,
                           0.23241813835208838};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(f[coord::L + i], L_dot[i], 1e-15) << i;
  // dp_β/dt = {p_β, H} = 0.012: the vorticity is not conserved (p_β = −tr((Lε)ᵀP)).
  const Mat2 Ld = matrix(f[4], f[5], f[6], f[7]), Pd = matrix(f[8], f[9], f[10], f[11]);
  const Mat2 eps = epsilon();
  const double p_beta_dot = -(Ld * eps).cwiseProduct(P).sum() - (L * eps).cwiseProduct(Pd).sum();
  EXPECT_NEAR(p_beta_dot, 0.012, 1e-15);
}

TEST(AnisotropicInertia, IsotropicMatrixIsBitIdenticalToTheNumber) {
  Scene number = anisotropic_scene();
  number.body.inertia_matrix.reset();
  Scene iso = number;
  iso.body.inertia_matrix = InertiaMatrix{0.4, 0.0, 0.0, 0.4};
  iso.body.inertia = 7.0;  // unused when the matrix is set
  for (const CatalogEntry& e : integrator_catalog()) {
    number.integrator = iso.integrator = {std::string(e.info.name), 0.05, 1e-10};
    const Simulation a = test::run_to(number, 3.0), b = test::run_to(iso, 3.0);
    EXPECT_TRUE(test::same_bits(a.state, b.state)) << e.info.name;
    EXPECT_EQ(energy(number, a.state), energy(iso, b.state)) << e.info.name;
  }
}

TEST(AnisotropicInertia, SpinConservedVorticityOscillates) {
  Scene scene = anisotropic_scene();
  scene.integrator = {"gauss6", 0.02, 1e-12};
  Simulation run = start_simulation(scene);
  const double s0 = spin(scene, run.state), b0 = vorticity(scene, run.state), H0 = energy(scene, run.state);
  double b_min = b0, b_max = b0, ds = 0.0, dH = 0.0;
  for (int k = 1; k <= 100; ++k) {
    advance_to(run, 0.1 * k);
    ASSERT_EQ(run.state.status, Status::ok);
    ds = std::max(ds, std::abs(spin(scene, run.state) - s0));
    dH = std::max(dH, std::abs(energy(scene, run.state) - H0));
    b_min = std::min(b_min, vorticity(scene, run.state));
    b_max = std::max(b_max, vorticity(scene, run.state));
  }
  EXPECT_LT(ds, 1e-13 * std::max(1.0, std::abs(s0)));
  EXPECT_LT(dH, 1e-9 * std::abs(H0));
  EXPECT_GT(b_max - b_min, 0.05 * std::abs(s0)) << "p_beta " << b_min << " .. " << b_max;
  // The same scene with isotropic J keeps the vorticity too (to the integrator's round-off).
  Scene iso = scene;
  iso.body.inertia_matrix.reset();
  Simulation r2 = start_simulation(iso);
  const double c0 = vorticity(iso, r2.state);
  advance_to(r2, 10.0);
  EXPECT_NEAR(vorticity(iso, r2.state), c0, 1e-12);
}

TEST(AnisotropicInertia, EverySteppingIntegratorAgreesWithTheReference) {
  Scene scene = anisotropic_scene();
  scene.integrator = {"dop853", 0.01, 1e-14};
  const State reference = test::run_to(scene, 3.0).state;
  const EmbeddedBody ref = global_embedding(scene, reference);
  for (const CatalogEntry& e : integrator_catalog()) {
    if (!e.make) continue;
    Scene s = scene;
    s.integrator = {std::string(e.info.name), e.info.order >= 4 ? 0.01 : 0.001, 1e-12};
    const State end = test::run_to(s, 3.0).state;
    ASSERT_EQ(end.status, Status::ok) << e.info.name;
    const EmbeddedBody b = global_embedding(s, end);
    const double error =
        std::max({(b.X - ref.X).norm(), (b.e[0] - ref.e[0]).norm(), (b.e[1] - ref.e[1]).norm(),
                  (b.W[0] - ref.W[0]).norm(), (b.W[1] - ref.W[1]).norm()});
    EXPECT_LT(error, e.info.order >= 4 ? 1e-5 : 1e-3) << e.info.name;  // split4: 1.7e-6
  }
}

TEST(AnisotropicInertia, ExactSolutionCoversTheFreeBodyAndRefusesAbc) {
  Scene scene = anisotropic_scene();
  ASSERT_TRUE(exact_unsupported_reason(scene).has_value());
  EXPECT_NE(exact_unsupported_reason(scene)->find("anisotropic"), std::string::npos);
  EXPECT_NE(resolve_integrator(scene), exact_info.name);
  scene.integrator.name = "exact";
  bool named = false;
  for (const FieldError& e : validate_scene(scene)) named |= e.field == "integrator.name";
  EXPECT_TRUE(named);
  // Without a deformation potential the internal motion L + tM is J-independent: the closed form
  // holds, with and without the radial barrier, on both curved surfaces.
  for (const bool radial : {true, false})
    for (const SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere}) {
      Scene free = anisotropic_scene();
      free.surface.kind = kind;
      free.potential.deformation = std::monostate{};
      if (!radial) free.potential.radial.reset();
      ASSERT_FALSE(exact_unsupported_reason(free).has_value());
      EXPECT_EQ(resolve_integrator(free), exact_info.name);
      Scene stepped = free;
      stepped.integrator = {"dop853", 0.01, 1e-14};
      free.integrator.name = "exact";
      const EmbeddedBody a = global_embedding(free, test::run_to(free, 4.0).state);
      const EmbeddedBody b = global_embedding(stepped, test::run_to(stepped, 4.0).state);
      EXPECT_LT((a.X - b.X).norm() + (a.e[0] - b.e[0]).norm() + (a.W[1] - b.W[1]).norm(), 1e-10)
          << "radial " << radial << " surface " << static_cast<int>(kind);
    }
}

TEST(AnisotropicInertia, GivenSpinIsTheRunsSpin) {
  Scene scene = anisotropic_scene();
  scene.initial.spin = 0.37;
  ASSERT_TRUE(resolve_initial_rates(scene).empty());
  const State start = initial_state(scene);
  EXPECT_NEAR(spin(scene, start), 0.37, 1e-15);
  EXPECT_NEAR(spin_of(scene), 0.37, 1e-15);  // initial_rates.h: the writer's spin from the rates
}

TEST(AnisotropicInertia, RigidBodyMovesAsTheIsotropicOneWithHalfTheTrace) {
  Scene a = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.25, 1.2);
  test::set_rigid_motion(a, 0.5, 0.7, 0.8);
  Scene b = a;
  b.body.inertia_matrix = InertiaMatrix{0.35, 0.1, 0.1, 0.15};  // tr/2 = 0.25
  const State x = test::run_to(a, 5.0).state, y = test::run_to(b, 5.0).state;
  EXPECT_LT((global_embedding(a, x).e[0] - global_embedding(b, y).e[0]).norm(), 1e-13);
  EXPECT_NEAR(energy(a, x), energy(b, y), 1e-14);
}

TEST(AnisotropicInertia, ValidationNamesTheMatrix) {
  struct Bad {
    InertiaMatrix J;
    const char* reason;
  };
  for (const Bad& bad :
       {Bad{{0.3, 0.1, 0.2, 0.2}, "symmetric"}, Bad{{0.1, 0.3, 0.3, 0.1}, "positive definite"},
        Bad{{-0.1, 0.0, 0.0, -0.2}, "positive definite"}, Bad{{0.1, NAN, NAN, 0.1}, "finite"}}) {
    Scene scene = anisotropic_scene();
    scene.body.inertia_matrix = bad.J;
    const std::vector<FieldError> errors = validate_scene(scene);
    ASSERT_FALSE(errors.empty()) << bad.reason;
    EXPECT_EQ(errors.front().field, "body.inertia");
    EXPECT_NE(errors.front().reason.find(bad.reason), std::string::npos) << errors.front().reason;
    EXPECT_EQ(errors.front().value.front(), '[');
  }
  EXPECT_TRUE(validate_scene(anisotropic_scene()).empty());
}

}  // namespace
}  // namespace spinfold
