// The maximal Lyapunov exponent and MEGNO (engine/chaos_indicators.h) against known answers: the
// geodesic flow of H² separates at exactly v/R; integrable scenes have λ → 0 and MEGNO → 2; a
// chaotic anisotropic body gives the same exponent with two integrators and two tolerances; the
// closed form and a stepper agree; the restart interval does not change the growth.
#include "engine/chaos_indicators.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/initial_rates.h"
#include "engine/validation.h"
#include "test_support.h"

namespace spinfold {
namespace {

ChaosIndicators indicators(const Scene& scene, double T, double interval = 1.0) {
  ChaosMonitor monitor(scene, interval);
  monitor.advance_to(T);
  return monitor.indicators();
}

// A free affine body with anisotropic inertia in the abc potential on the pseudosphere: its internal
// motion is chaotic (the researcher's scene of issue 35; examples/chaotic_anisotropic_pseudosphere.json).
Scene chaotic(const char* integrator, double tolerance) {
  Scene s;
  s.surface = {SurfaceKind::pseudosphere, 1.0};
  s.body = {1.0, 0.1, BodyModel::affine, InertiaMatrix{0.3, 0.1, 0.1, 0.1}};
  s.potential.deformation = AbcPotential{0.1, 0.4, 0.5};
  s.initial = {.r = 0.8,
               .lambda = 1.3,
               .mu = 0.7,
               .phi_dot = 0.3,
               .alpha_dot = 0.9,
               .beta_dot = 0.2,
               .lambda_dot = 0.3};
  s.integrator = {integrator, 0.01, tolerance};
  return s;
}

// Geodesics of H² (curvature −1/R²) separate like sinh(vt/R): λ = v/R, less ln 2/t at a finite t.
// The body goes out to 5.5 R, where the indicators hold.
TEST(ChaosIndicators, GeodesicsOfThePseudosphereSeparateAtVOverR) {
  for (const char* integrator : {"dop853", "exact"}) {
    Scene s = test::rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.2, 0.5);
    s.integrator.name = integrator;
    s.initial.r = 0.5;
    test::set_rigid_motion(s, 0.25, 1.3, 0.0);
    const ChaosIndicators c = indicators(s, 19.0);
    EXPECT_EQ(c.intervals, 19u) << integrator << ": " << c.stopped;
    EXPECT_NEAR(c.lyapunov, 0.25, 0.03) << integrator;
    EXPECT_GT(c.megno, 4.0) << integrator << ": exponential separation";
    EXPECT_NEAR(c.lyapunov_time, 1.0 / c.lyapunov, 1e-12);
  }
}

// Integrable scenes: the separation grows linearly (the frequencies depend on the actions), so
// λ ~ ln t / t → 0 and MEGNO → 2.
TEST(ChaosIndicators, IntegrableScenesTendToZeroAndTwo) {
  Scene w5 = w5_scene();
  w5.integrator = {"dop853", 0.01, 1e-12};
  Scene rigid = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.2, 0.5);
  rigid.initial.r = 1.0;
  test::set_rigid_motion(rigid, 0.5, 0.3, 0.2);
  for (const Scene& s : {w5, rigid}) {
    const ChaosIndicators c = indicators(s, 400.0);
    ASSERT_EQ(c.intervals, 400u) << c.stopped;
    EXPECT_LT(c.lyapunov, 0.02);
    EXPECT_NEAR(c.megno, 2.0, 0.2);
    EXPECT_NEAR(c.megno_mean, 2.0, 0.3);
  }
  // The closed form and dop853: two formulations of W5, the same indicators.
  Scene exact = w5;
  exact.integrator.name = "exact";
  const ChaosIndicators a = indicators(w5, 200.0), b = indicators(exact, 200.0);
  EXPECT_NEAR(a.lyapunov, b.lyapunov, 1e-4 * a.lyapunov);
  EXPECT_NEAR(a.megno, b.megno, 1e-3);
}

// A chaotic scene: a positive exponent that two integrators and two tolerances agree on (to 15 %, a
// finite-time estimate), and a MEGNO far above 2.
TEST(ChaosIndicators, AChaoticBodyHasOneExponentWhateverTheIntegrator) {
  std::vector<double> exponents;
  for (const auto& [integrator, tolerance] :
       std::vector<std::pair<const char*, double>>{{"dop853", 1e-10}, {"dop853", 1e-12}, {"gauss6", 1e-12}}) {
    const ChaosIndicators c = indicators(chaotic(integrator, tolerance), 200.0);
    ASSERT_EQ(c.intervals, 200u) << integrator << ": " << c.stopped;
    EXPECT_GT(c.lyapunov, 0.3) << integrator;
    EXPECT_GT(c.megno_mean, 20.0) << integrator;
    exponents.push_back(c.lyapunov);
  }
  const auto [lo, hi] = std::minmax_element(exponents.begin(), exponents.end());
  EXPECT_LT(*hi / *lo, 1.15);
}

// The restart interval is a numerical choice: in the linear regime the summed growth is the same.
TEST(ChaosIndicators, TheIntervalDoesNotChangeTheGrowth) {
  Scene s = w5_scene();
  s.integrator = {"dop853", 0.01, 1e-12};
  const ChaosIndicators one = indicators(s, 400.0, 1.0), five = indicators(s, 400.0, 5.0),
                        many = indicators(s, 400.0, 25.0);
  EXPECT_NEAR(one.lyapunov, five.lyapunov, 1e-3 * one.lyapunov);
  EXPECT_NEAR(one.lyapunov, many.lyapunov, 1e-3 * one.lyapunov);
}

// Integrable scenes as a generator draws them, on every surface where the motion is integrable (S²,
// the plane, H² with the body circling, the torus, oblate and prolate spheroids; rigid bodies and
// isotropic affine ones in the abc potential), at the scene's default integrator and tolerance
// (`auto`, 1e-10: the path users take): ⟨Y⟩ within 5 % of 2 at T = 800. A shadow run whose step
// sequence was not the reference's counted the integrator's error per interval (~1 % of d₀ at 1e-10)
// as growth: ⟨Y⟩ 4.7, 9.9, 20.7 at T = 200, 400, 800 on the torus (issue 51).
Scene integrable_scene(unsigned seed) {
  std::mt19937_64 rng(seed);
  const auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  Scene s;
  const SurfaceKind kinds[] = {SurfaceKind::sphere, SurfaceKind::plane,    SurfaceKind::pseudosphere,
                               SurfaceKind::torus,  SurfaceKind::spheroid, SurfaceKind::spheroid};
  const SurfaceKind kind = kinds[seed % 6];
  s.surface = {kind, uniform(0.8, 1.5)};
  const bool rigid = (seed / 6) % 2 == 0;
  s.body = {uniform(0.5, 2.0), uniform(0.05, 0.3), rigid ? BodyModel::rigid : BodyModel::affine};
  if (!rigid)
    s.potential.deformation = AbcPotential{uniform(0.05, 0.15), uniform(0.3, 0.5), uniform(0.4, 0.6)};
  s.initial.lambda = uniform(0.9, 1.3);
  // An affine body's λ and μ apart: the abc potential's A/(λ − μ)² is a barrier at λ = μ (the
  // validator refuses a start on it).
  s.initial.mu = rigid ? s.initial.lambda : s.initial.lambda * uniform(0.6, 0.8);
  double speed = uniform(0.3, 1.0), spin = uniform(-1.0, 1.0);
  switch (kind) {
    case SurfaceKind::pseudosphere:  // circling: s > m v R (a geodesic of H² separates at v/R)
      speed = uniform(0.2, 0.4);
      spin = uniform(1.5, 2.5) * s.body.mass * speed * s.surface.radius;
      s.initial.r = uniform(0.2, 0.8);
      break;
    case SurfaceKind::torus:
      s.surface.tube_radius = uniform(0.6, 1.0);
      s.surface.center_radius = uniform(2.0, 3.0);
      s.initial.u = uniform(-3.0, 3.0);
      break;
    case SurfaceKind::spheroid:
      s.surface.equatorial_radius = 1.0;
      s.surface.polar_radius = seed % 12 < 6 ? uniform(0.5, 0.8) : uniform(1.3, 1.6);
      s.initial.u = uniform(0.5, 2.5);
      break;
    default: s.initial.r = uniform(0.3, 1.2);
  }
  s.initial.speed = speed;
  s.initial.heading = uniform(-3.0, 3.0);
  s.initial.spin = spin;
  // As a front door reads it: the rates from speed, heading and spin, and valid.
  EXPECT_TRUE(resolve_initial_rates(s).empty()) << "seed " << seed;
  EXPECT_TRUE(validate_scene(s).empty()) << "seed " << seed;
  return s;
}

TEST(ChaosIndicators, EveryIntegrableSceneHasMegnoTwoAtTheDefaultTolerance) {
  // Seeds 0–11 draw each surface with each body once (24 before: the same spread, twice the time);
  // under the sanitizers, which look for memory errors rather than numbers, three (170 s → 20 s).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  constexpr unsigned kSeeds = 3;
#else
  constexpr unsigned kSeeds = 12;
#endif
  for (unsigned seed = 0; seed < kSeeds; ++seed) {
    const Scene s = integrable_scene(seed);
    ASSERT_EQ(s.integrator.name, "auto");
    ASSERT_EQ(s.integrator.tolerance, 1e-10);
    const std::string what = "seed " + std::to_string(seed) + " (surface kind " +
                             std::to_string(static_cast<int>(s.surface.kind)) +
                             (s.body.model == BodyModel::rigid ? ", rigid)" : ", affine)");
    const ChaosIndicators c = indicators(s, 800.0);
    ASSERT_EQ(c.intervals, 800u) << what << ": " << c.stopped;
    // ⟨Y⟩ → 2 from below with a finite-time bias of order (ln T)²/T, and λ ~ ln T / T: measured
    // 1.83–2.06 and λ ≤ 0.0096 over these scenes (before: 4.7 at T = 200 on the torus).
    EXPECT_NEAR(c.megno_mean, 2.0, 0.2) << what;
    EXPECT_LT(c.lyapunov, 2.0 * std::log(800.0) / 800.0) << what;
    // The tolerance hardly enters: at 1e-13 within 4 % (measured ≤ 1.4 %; the closed form has none).
    if (resolve_integrator(s) == "exact") continue;
    Scene tight = s;
    tight.integrator.tolerance = 1e-13;
    const ChaosIndicators t = indicators(tight, 800.0);
    EXPECT_NEAR(c.megno_mean, t.megno_mean, 0.04 * t.megno_mean) << what;
  }
}

TEST(ChaosIndicators, IntervalsAreBoundedAndRefusedInWords) {
  EXPECT_FALSE(chaos_interval_refusal(1.0, 100.0));
  EXPECT_EQ(*chaos_interval_refusal(0.0, 100.0), "must be a number > 0 [time] (got 0)");
  EXPECT_NE(chaos_interval_refusal(1e-6, 100.0)->find("at most 1e6"), std::string::npos);
  EXPECT_EQ(*chaos_interval_refusal(100.0, 5.0),
            "must be at most the run's length t_end = 5 (got 100): no interval would end");
  // Far out on H² the indicators stop and say why.
  Scene s = test::rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.2, 0.5);
  s.initial.r = 0.5;
  test::set_rigid_motion(s, 1.0, 0.0, 0.0);
  const ChaosIndicators c = indicators(s, 40.0);
  EXPECT_LT(c.t, 6.0);
  EXPECT_NE(c.stopped.find("5.5 R"), std::string::npos) << c.stopped;
}

}  // namespace
}  // namespace spinfold
