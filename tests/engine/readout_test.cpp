// The read-out: computed once from a run, equal to the engine's own queries, and the HUD's lines
// are made of its values.
#include "engine/readout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/initial_rates.h"
#include "engine/invariants.h"
#include "engine/scene_fields.h"

namespace spinfold {
namespace {

Scene deforming(SurfaceKind kind) {
  Scene s;
  s.surface = {kind, 1.5};
  s.body = {2.0, 0.3, BodyModel::affine};
  s.potential.radial = RadialPotential{0.05};
  s.potential.deformation = AbcPotential{0.02, 0.0, 0.4};
  s.initial.r = 0.9;
  s.initial.mu = 0.6;
  s.initial.phi_dot = 0.7;
  s.initial.alpha_dot = 0.3;
  s.initial.lambda_dot = 0.1;
  s.integrator.name = "dop853";
  return s;
}

std::string format(const char* pattern, double v) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, v);
  return text;
}

// The speed and heading read off the state at t = 0 are the scene's start, given as rates or in the
// physical form; and a speed is conserved by a free geodesic motion (no potentials, no spin).
TEST(Readout, SpeedAndHeadingAreTheScenesPhysicalStart) {
  for (const SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere, SurfaceKind::plane}) {
    const Scene rates = deforming(kind);
    const Readout r = readout(start_simulation(rates));
    ASSERT_TRUE(r.speed && r.heading);
    EXPECT_NEAR(*r.speed, speed_of(rates), 1e-12);
    EXPECT_NEAR(*r.heading, heading_of(rates), 1e-12);
    EXPECT_GT(*r.speed, 0.5);

    Scene physical = rates;
    physical.initial.r_dot = physical.initial.phi_dot = 0.0;
    physical.initial.speed = 0.8;
    physical.initial.heading = -2.0;
    ASSERT_TRUE(resolve_initial_rates(physical).empty());
    const Readout p = readout(start_simulation(physical));
    ASSERT_TRUE(p.speed && p.heading);
    EXPECT_NEAR(*p.speed, 0.8, 1e-12);
    EXPECT_NEAR(*p.heading, -2.0, 1e-12);
  }
}

TEST(Readout, EqualsTheEngineQueriesOfTheCurrentState) {
  for (const SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere, SurfaceKind::plane}) {
    Simulation run = start_simulation(deforming(kind));
    advance_to(run, 1.3);
    const Readout r = readout(run);
    const Scene& scene = run.scene;
    const State& state = run.state;
    EXPECT_EQ(r.t, state.t);
    EXPECT_EQ(r.energy, energy(scene, state));
    EXPECT_EQ(r.energy_error,
              (energy(scene, state) - run.initial_energy) / std::max(std::abs(run.initial_energy), 1e-300));
    EXPECT_LT(std::abs(r.energy_error), 1e-8);
    EXPECT_EQ(r.energy_orbital, orbital_energy(scene, state));
    EXPECT_EQ(r.energy_deformation, deformation_energy(scene, state));
    EXPECT_NEAR(r.energy_orbital + r.energy_deformation, r.energy, 1e-12 * std::abs(r.energy));
    // One spin, vorticity and det L for everyone: the paper coordinates' own.
    EXPECT_EQ(r.spin, r.coordinates.p_alpha);
    EXPECT_EQ(r.vorticity, r.coordinates.p_beta);
    EXPECT_EQ(r.det_L, r.coordinates.det_L);
    EXPECT_NEAR(r.spin, spin(scene, state), 1e-12 * (1 + std::abs(r.spin)));
    EXPECT_NEAR(r.vorticity, vorticity(scene, state), 1e-12 * (1 + std::abs(r.vorticity)));
    EXPECT_NEAR(r.det_L, det_L(scene, state), 1e-12 * (1 + std::abs(r.det_L)));
    EXPECT_EQ(r.separated.has_value(), separated_energies(scene, state).has_value());
    EXPECT_EQ(r.momentum_map.has_value(), momentum_map(scene, state).has_value());
    EXPECT_EQ(r.casimir.has_value(), r.momentum_map.has_value() && !offers(kind, Offer::zero_curvature));
    EXPECT_EQ(r.status, state.status);
    EXPECT_EQ(r.status_name, status_name(state.status));
    EXPECT_EQ(r.status_detail, status_description(state.status));
    EXPECT_EQ(r.integrator, "dop853");
    EXPECT_EQ(r.steps, run.steps);
    EXPECT_GT(r.steps, 0u);
  }
}

TEST(Readout, HudLinesAreMadeOfTheReadoutValues) {
  Simulation run = start_simulation(deforming(SurfaceKind::pseudosphere));
  advance_to(run, 0.77);
  const Readout r = readout(run);
  const std::vector<std::string> lines = readout_lines(run.scene, r);
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(lines[0], format("t = %.3f", r.t));
  EXPECT_EQ(lines[0], "t = 0.770");
  EXPECT_EQ(lines[1], format("energy error = %.2e", r.energy_error));
  EXPECT_EQ(lines[2], "integrator: " + std::string(r.integrator));
  EXPECT_EQ(lines[3], std::string(enum_name(SurfaceKind::pseudosphere)) + "  R = 1.5");
  EXPECT_EQ(lines[4], "m = 2  J = 0.3  affine");
  EXPECT_EQ(lines[5], format("spin = %.4f", r.spin) + format("  det L = %.4f", r.det_L));

  // A change in the read-out is a change in the lines, and a stopped run says so.
  Readout stopped = r;
  stopped.status = Status::diverged;
  stopped.spin = r.spin + 1.0;
  const std::vector<std::string> changed = readout_lines(run.scene, stopped);
  EXPECT_EQ(changed[2], "integrator: " + std::string(r.integrator) + "  [stopped]");
  EXPECT_EQ(changed[5], format("spin = %.4f", r.spin + 1.0) + format("  det L = %.4f", r.det_L));
}

TEST(Readout, ANumberThatRoundsToZeroIsShownWithoutASign) {
  Simulation run = start_simulation(deforming(SurfaceKind::sphere));
  Readout r = readout(run);
  r.t = -0.0;
  r.spin = -1e-17;  // a spin that cancelled to round-off
  r.det_L = -0.00004;
  r.energy_error = -0.0;
  std::vector<std::string> lines = readout_lines(run.scene, r);
  EXPECT_EQ(lines[0], "t = 0.000");
  EXPECT_EQ(lines[1], "energy error = 0.00e+00");
  EXPECT_EQ(lines[5], "spin = 0.0000  det L = 0.0000");
  // What is not zero keeps its sign: −0.5, −1e-17 in the exponent form, −0.0001.
  r.spin = -0.5;
  r.det_L = -0.0001;
  r.energy_error = -1e-17;
  lines = readout_lines(run.scene, r);
  EXPECT_EQ(lines[1], "energy error = -1.00e-17");
  EXPECT_EQ(lines[5], "spin = -0.5000  det L = -0.0001");
  EXPECT_EQ(companion_readout_line("b", r), "b: spin = -0.5000  energy error = -1.00e-17");
  // A fan's label names the spin already: said once (it read "spin = 0.25: spin = 0.2500").
  EXPECT_EQ(companion_readout_line("spin = -0.5", r), "spin = -0.5: energy error = -1.00e-17");
}

}  // namespace
}  // namespace spinfold
