// Summaries and events of a run (engine/run_summary.h): checked against a dense trajectory of the
// same run, against the state at the located times, against the closed form, and for independence
// of where the run is sampled.
#include "engine/run_summary.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>

#include "engine/embedded_run.h"
#include "engine/initial_rates.h"
#include "engine/sampling.h"
#include "formula_surfaces.h"
#include "test_support.h"

namespace spinfold {
namespace {

Scene w5_with(const char* integrator, double dt, double tolerance) {
  Scene s = w5_scene();
  s.integrator = {integrator, dt, tolerance};
  return s;
}

MonitorSpec r_and_phi(const std::string& event) {
  return {.summaries = {parse_summary("r"), parse_summary("phi.max"), parse_summary("energy_error.max")},
          .events = {parse_event(event)}};
}

// Runs to t_end sampled every `every`, with the monitor; the monitor's values at the end.
std::vector<double> summarised(const Scene& scene, const MonitorSpec& spec, double t_end, double every,
                               Simulation* out = nullptr) {
  Simulation run = start_simulation(scene);
  watch(run, spec);
  sample_run(
      run, t_end, every, [&](double t) { return advance_to(run, t); }, [] {});
  std::vector<double> values = monitor_values(run);
  if (out) *out = std::move(run);
  return values;
}

double field_r(const Simulation& run) {
  return global_body(run.scene, run.state).r;
}

TEST(RunSummary, ParsesSummariesAndEventsInOneGrammar) {
  const SummarySpec all = parse_summary("X.0");
  EXPECT_EQ(all.field, "X.0");
  EXPECT_EQ(all.reductions.size(), 6u);
  const SummarySpec one = parse_summary("X.0.t_max");
  EXPECT_EQ(one.field, "X.0");
  ASSERT_EQ(one.reductions.size(), 1u);
  EXPECT_EQ(one.reductions[0], Reduction::t_max);

  const EventSpec e = parse_event("phi:any:0:period=6.283185307179586:stop=3");
  EXPECT_EQ(e.field, "phi");
  EXPECT_EQ(e.direction, Direction::any);
  EXPECT_EQ(e.period, 2.0 * std::numbers::pi);
  EXPECT_EQ(e.stop, 3u);
  EXPECT_EQ(e.name, "phi_any_0");
  EXPECT_EQ(parse_event("r:up:1.2:name=out").name, "out");
  EXPECT_EQ(parse_event("r:up:1.2").name, "r_up_1.2");

  for (const char* bad :
       {"r", "r:sideways:1", "r:up:x", "r:up:1:period=0", "r:up:1:stop=0", "r:up:1:colour=red",
        // A key given twice (as a JSON object's is refused), and levels closer than double tells apart.
        "r:up:1:name=a:name=b", "r:up:1:period=1:period=2", "r:up:1e6:period=1e-7"}) {
    try {
      parse_event(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(std::string("'") + bad + "'"), std::string::npos)
          << error.what();
    }
  }
  const Scene scene = w5_scene();
  EXPECT_THROW(check_monitor({.summaries = {parse_summary("u")}, .events = {}}, scene),
               std::invalid_argument);
  EXPECT_THROW(
      check_monitor({.summaries = {}, .events = {parse_event("r:up:1"), parse_event("r:up:1")}}, scene),
      std::invalid_argument);
  // K exists only where the curvature varies.
  EXPECT_THROW(check_monitor({.summaries = {}, .events = {parse_event("K:up:1")}}, scene),
               std::invalid_argument);
}

TEST(RunSummary, ColumnsFollowTheSpec) {
  const std::vector<std::string> columns =
      monitor_columns({.summaries = {parse_summary("r.max"), parse_summary("phi.final")},
                       .events = {parse_event("r:up:1.2")}});
  const std::vector<std::string> expected = {
      "r.max",           "phi.final",     "r_up_1.2.count", "r_up_1.2.t_first",
      "r_up_1.2.t_last", "r_up_1.2.at.r", "r_up_1.2.at.phi"};
  EXPECT_EQ(columns, expected);
}

// The monitor watches; it never changes the run: the same states to the bit with and without it.
TEST(RunSummary, WatchingDoesNotChangeTheRun) {
  for (const char* integrator : {"rk4", "dop853", "exact"}) {
    const Scene scene = w5_with(integrator, 0.01, 1e-10);
    Simulation watched;
    summarised(scene, r_and_phi("r:up:1.3"), 20.0, 0.37, &watched);
    Simulation plain = start_simulation(scene);
    sample_run(
        plain, 20.0, 0.37, [&](double t) { return advance_to(plain, t); }, [] {});
    EXPECT_TRUE(test::same_bits(watched.state, plain.state)) << integrator;
  }
}

// The values come from the run's own steps: the same to the bit however it is sampled.
TEST(RunSummary, IndependentOfTheSampling) {
  for (const char* integrator : {"rk4", "dop853", "exact"}) {
    const Scene scene = w5_with(integrator, 0.01, 1e-10);
    const MonitorSpec spec = r_and_phi("r:up:1.3");
    const std::vector<double> coarse = summarised(scene, spec, 20.0, 0.5);
    const std::vector<double> fine = summarised(scene, spec, 20.0, 0.013);
    const std::vector<double> once = summarised(scene, spec, 20.0, 20.0);
    ASSERT_EQ(coarse.size(), fine.size());
    for (std::size_t i = 0; i < coarse.size(); ++i) {
      EXPECT_EQ(std::memcmp(&coarse[i], &fine[i], sizeof(double)), 0) << integrator << " column " << i;
      EXPECT_EQ(std::memcmp(&coarse[i], &once[i], sizeof(double)), 0) << integrator << " column " << i;
    }
  }
}

// The same on a surface given by a formula, which has no chart: the summaries of X, K and the
// constraint's drift and the events on the height, with projection after each step, to the bit.
TEST(RunSummary, IndependentOfTheSamplingOnAFormulaSurface) {
  Scene scene;
  scene.surface = test::graph_surface("a*sin(x)*sin(y)", {{"a", 0.4}});
  scene.initial.X = {0.3, 0.2, 0.0};
  scene.initial.speed = 0.6;
  scene.initial.heading = 0.4;
  scene.initial.spin = 0.8;
  scene.body.model = BodyModel::rigid;
  scene.integrator = {"dop853", 0.01, 1e-10};
  const MonitorSpec spec{.summaries = {parse_summary("X.0"), parse_summary("K"), parse_summary("X.2.max")},
                         .events = {parse_event("X.2:up:0.05"), parse_event("K:any:0")}};
  const std::vector<double> coarse = summarised(scene, spec, 12.0, 0.5);
  const std::vector<double> fine = summarised(scene, spec, 12.0, 0.017);
  const std::vector<double> once = summarised(scene, spec, 12.0, 12.0);
  ASSERT_EQ(coarse.size(), fine.size());
  ASSERT_EQ(coarse.size(), once.size());
  for (std::size_t i = 0; i < coarse.size(); ++i) {
    EXPECT_EQ(std::memcmp(&coarse[i], &fine[i], sizeof(double)), 0) << "column " << i;
    EXPECT_EQ(std::memcmp(&coarse[i], &once[i], sizeof(double)), 0) << "column " << i;
  }
  EXPECT_GT(coarse[1] - coarse[0], 0.1) << "X.0 varies";
}

// Against a dense trajectory (a sample every 1e-3): the extremes bound every sample's value and
// exceed the largest by no more than the samples' own spacing allows; the mean is its integral.
TEST(RunSummary, ReductionsAgreeWithADenseTrajectory) {
  const Scene scene = w5_with("dop853", 0.01, 1e-12);
  const MonitorSpec spec{.summaries = {parse_summary("r")}, .events = {}};
  const double T = 15.0, every = 1e-3;
  const std::vector<double> v = summarised(scene, spec, T, 0.5);  // min max mean final t_min t_max
  Simulation run = start_simulation(scene);
  double lo = INFINITY, hi = -INFINITY, t_lo = 0, t_hi = 0, integral = 0, previous = field_r(run);
  sample_run(
      run, T, every, [&](double t) { return advance_to(run, t); },
      [&] {
        const double r = field_r(run);
        if (r < lo) lo = r, t_lo = run.state.t;
        if (r > hi) hi = r, t_hi = run.state.t;
        if (run.state.t > 0) integral += 0.5 * (previous + r) * every;
        previous = r;
      });
  EXPECT_LE(v[0], lo + 1e-13);
  EXPECT_GE(v[1], hi - 1e-13);
  EXPECT_LT(lo - v[0], 1e-6);  // a sample every 1e-3 misses the true extreme by ~r''·1e-6/8
  EXPECT_LT(v[1] - hi, 1e-6);
  EXPECT_NEAR(v[2], integral / T, 1e-6);
  EXPECT_NEAR(v[3], field_r(run), 1e-14 * field_r(run));  // read off the chart, not through X
  EXPECT_NEAR(v[4], t_lo, 2e-3);
  EXPECT_NEAR(v[5], t_hi, 2e-3);
  EXPECT_GT(v[1] - v[0], 0.05) << "the scene's r oscillates";
}

// Each located time is where the field meets the level: the run advanced to that time (a cut step
// from its sequence, as any sample) has r = level to 1e-10 of the field's rate; the count is the
// dense trajectory's count of sign changes.
TEST(RunSummary, EventsAreLocatedToTheirLevel) {
  const Scene scene = w5_with("dop853", 0.01, 1e-12);
  const double level = 1.3, T = 30.0;
  std::vector<double> times;
  Simulation probe = start_simulation(scene);
  int dense_count = 0;
  double previous = field_r(probe);
  sample_run(
      probe, T, 1e-3, [&](double t) { return advance_to(probe, t); },
      [&] {
        const double r = field_r(probe);
        if (previous < level && r >= level) ++dense_count;
        previous = r;
      });
  ASSERT_GE(dense_count, 2);
  for (std::uint64_t n = 1; n <= static_cast<std::uint64_t>(dense_count); ++n) {
    MonitorSpec spec{.summaries = {}, .events = {parse_event("r:up:1.3:stop=" + std::to_string(n))}};
    Simulation stopped;
    const std::vector<double> v = summarised(scene, spec, T, 0.5, &stopped);
    ASSERT_EQ(stopped.state.status, Status::event_stop) << n;
    Simulation finer;  // sampled elsewhere: the stop is on the run's own steps, the same to the bit
    summarised(scene, spec, T, 0.07, &finer);
    EXPECT_TRUE(test::same_bits(finer.state, stopped.state)) << n;
    EXPECT_EQ(v[0], static_cast<double>(n));
    EXPECT_EQ(stopped.state.t, v[2]);
    Simulation at = start_simulation(scene);
    advance_to(at, v[2]);
    const GlobalBody g = global_body(scene, at.state);
    EXPECT_LT(std::abs(g.r - level), 1e-10 * std::max(std::abs(g.r_dot), 1e-3)) << n;
    EXPECT_GT(g.r_dot, 0.0) << "an upward crossing";
    times.push_back(v[2]);
  }
  const std::vector<double> all =
      summarised(scene, {.summaries = {}, .events = {parse_event("r:up:1.3")}}, T, 0.5);
  EXPECT_EQ(all[0], dense_count);
  EXPECT_EQ(all[1], times.front());
  EXPECT_EQ(all[2], times.back());
}

// A run that stops on an event ends there, its companions too: their last state is at the stop's
// time, bit-identical however the run was sampled (issue 51 item 9: it was the next sample's time).
TEST(RunSummary, ACompanionEndsWhereAStoppedRunEnds) {
  Scene scene = w5_with("dop853", 0.01, 1e-12);
  Companion slower;
  slower.body = scene.body;
  slower.initial = scene.initial;
  slower.integrator = scene.integrator;
  slower.initial.r_dot *= 0.9;
  slower.initial.phi_dot *= 0.9;
  scene.companions.push_back(slower);
  const MonitorSpec spec{.summaries = {}, .events = {parse_event("r:up:1.3:stop=1")}};
  std::vector<Simulation> runs;
  for (const double every : {0.07, 0.5, 3.3, 40.0}) {
    Simulation run;
    summarised(scene, spec, 30.0, every, &run);
    ASSERT_EQ(run.state.status, Status::event_stop) << every;
    ASSERT_EQ(run.companions.size(), 1u);
    EXPECT_EQ(run.companions[0].state.t, run.state.t) << every;
    if (!runs.empty()) {
      EXPECT_TRUE(test::same_bits(run.companions[0].state, runs.front().companions[0].state)) << every;
    }
    runs.push_back(std::move(run));
  }
  // asked past the stop again, nothing moves
  ASSERT_TRUE(advance_to(runs.front(), 35.0) || runs.front().state.status == Status::event_stop);
  EXPECT_EQ(runs.front().companions[0].state.t, runs.front().state.t);
}

// Every crossing with its state (issue 51 item 3: a Poincaré section took 35 re-runs with stop=k).
// `record` keeps each occurrence's state: as many as counted, each on its level, the first and last at
// t_first and t_last, each the state of a stop=k run at that crossing (the same root find), the same
// whatever the sampling, and bounded by record=N.
TEST(RunSummary, EveryCrossingIsRecordedWithItsState) {
  const Scene scene = w5_with("dop853", 0.01, 1e-12);
  const double T = 30.0;
  const EventSpec spec = parse_event("r:up:1.3:record");
  EXPECT_EQ(spec.record, kMaxRecordedCrossings);
  Simulation run;
  const std::vector<double> v = summarised(scene, {.summaries = {}, .events = {spec}}, T, 0.5, &run);
  const std::vector<State> kept = run.monitor->recorded(0);
  ASSERT_GE(v[0], 2.0);
  ASSERT_EQ(static_cast<double>(kept.size()), v[0]);
  EXPECT_EQ(kept.front().t, v[1]);
  EXPECT_EQ(kept.back().t, v[2]);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const GlobalBody g = global_body(scene, kept[k]);
    EXPECT_LT(std::abs(g.r - 1.3), 1e-10) << k;
    EXPECT_GT(g.r_dot, 0.0) << k;
    if (k > 0) {
      EXPECT_GT(kept[k].t, kept[k - 1].t);
    }
    Simulation stopped;  // the k-th by stop=k: the same crossing
    summarised(scene, {.summaries = {}, .events = {parse_event("r:up:1.3:stop=" + std::to_string(k + 1))}}, T,
               0.5, &stopped);
    EXPECT_NEAR(stopped.state.t, kept[k].t, 1e-12) << k;
  }
  Simulation finer;
  summarised(scene, {.summaries = {}, .events = {spec}}, T, 0.07, &finer);
  const std::vector<State> again = finer.monitor->recorded(0);
  ASSERT_EQ(again.size(), kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k) EXPECT_TRUE(test::same_bits(again[k], kept[k])) << k;
  // Bounded: the first N only, the count still all of them.
  Simulation capped;
  const std::vector<double> c =
      summarised(scene, {.summaries = {}, .events = {parse_event("r:up:1.3:record=1")}}, T, 0.5, &capped);
  EXPECT_EQ(c[0], v[0]);
  ASSERT_EQ(capped.monitor->recorded(0).size(), 1u);
  EXPECT_TRUE(test::same_bits(capped.monitor->recorded(0)[0], kept[0]));
  // With a period every level's crossing is kept: φ through each multiple of 2π, in order.
  Simulation turns;
  const std::vector<double> p =
      summarised(scene, {.summaries = {}, .events = {parse_event("phi:any:0:record")}}, 40.0, 0.5, &turns);
  const std::vector<State> each = turns.monitor->recorded(0);
  ASSERT_EQ(static_cast<double>(each.size()), p[0]);
  for (const State& at : each) {
    const double phi = global_body(scene, at).phi;
    EXPECT_LT(std::abs(std::remainder(phi, 2.0 * std::numbers::pi)), 1e-9) << at.t;
  }
  EXPECT_THROW(parse_event("r:up:1.3:record=0"), MonitorRefusal);
  EXPECT_THROW(parse_event("r:up:1.3:record=100001"), MonitorRefusal);
  EXPECT_THROW(parse_event("r:up:1.3:record=1.5"), MonitorRefusal);
}

// The closed form and a stepper locate the same crossings: two formulations, to their accuracy.
TEST(RunSummary, ClosedFormAndStepperAgree) {
  const MonitorSpec spec{
      .summaries = {parse_summary("r.max"), parse_summary("r.min")},
      .events = {parse_event("r:down:1.25"), parse_event("phi:any:0:period=6.283185307179586")}};
  const std::vector<double> exact = summarised(w5_with("exact", 0.01, 1e-12), spec, 25.0, 0.5);
  const std::vector<double> stepped = summarised(w5_with("dop853", 0.01, 1e-13), spec, 25.0, 0.5);
  ASSERT_EQ(exact.size(), stepped.size());
  EXPECT_NEAR(exact[0], stepped[0], 1e-10);
  EXPECT_NEAR(exact[1], stepped[1], 1e-10);
  for (std::size_t i = 2; i < exact.size(); ++i) EXPECT_NEAR(exact[i], stepped[i], 1e-8) << "column " << i;
  EXPECT_GE(exact[2], 1.0);
}

// phi counts turns: crossings of multiples of 2π equal the dense trajectory's unwrapped turns.
TEST(RunSummary, PhiThroughMultiplesOfTwoPi) {
  const Scene scene = w5_with("dop853", 0.01, 1e-12);
  const double T = 40.0;
  Simulation probe = start_simulation(scene);
  const double p = 2.0 * std::numbers::pi;
  double unwrapped = global_body(scene, probe.state).phi, raw = unwrapped, turns = 0;
  sample_run(
      probe, T, 1e-2, [&](double t) { return advance_to(probe, t); },
      [&] {
        const double now = global_body(scene, probe.state).phi;
        const double next = unwrapped + std::remainder(now - raw, p);
        // Multiples k·2π with unwrapped < k·2π <= next (up) or next <= k·2π < unwrapped (down).
        turns += next > unwrapped ? std::floor(next / p) - std::floor(unwrapped / p)
                                  : std::ceil(unwrapped / p) - std::ceil(next / p);
        unwrapped = next;
        raw = now;
      });
  const std::vector<double> v = summarised(scene,
                                           {.summaries = {parse_summary("phi.final")},
                                            .events = {parse_event("phi:any:0:period=6.283185307179586")}},
                                           T, 0.5);
  EXPECT_NEAR(v[0], unwrapped, 1e-9);
  EXPECT_EQ(v[1], turns);
  EXPECT_GE(turns, 1.0);
}

// The torus's tube angle u is a circle (issue 51): u is read wrapped to (−π, π], and each wrap was
// counted as a crossing (u:up:1.5 gave 12 where there are 6), stop=2 stopped at a wrap, u.max read
// ±π. Now u is continuous and a level on it is a level on the circle; checked against a dense
// trajectory of the same run, unwrapped here.
TEST(RunSummary, TheTorussTubeAngleIsACircle) {
  Scene scene;
  scene.surface.kind = SurfaceKind::torus;
  scene.surface.tube_radius = 1.0;
  scene.surface.center_radius = 2.5;
  scene.body = {1.0, 0.1, BodyModel::rigid};
  scene.initial.u = 0.2;
  scene.initial.speed = 1.2;
  scene.initial.heading = 0.15;  // mostly round the tube
  scene.initial.spin = 0.05;
  ASSERT_TRUE(resolve_initial_rates(scene).empty());
  scene.integrator = {"dop853", 0.01, 1e-12};
  const double T = 40.0, level = 1.5, p = 2.0 * std::numbers::pi;
  Simulation probe = start_simulation(scene);
  const auto wrapped_u = [&] { return profile_readout(*probe.embedded, probe.state.y).coordinates.r; };
  double raw = wrapped_u(), unwrapped = raw, highest = raw;
  int circle_ups = 0, wraps = 0;
  sample_run(
      probe, T, 1e-3, [&](double t) { return advance_to(probe, t); },
      [&] {
        const double now = wrapped_u();
        if (std::abs(now - raw) > std::numbers::pi) ++wraps;
        const double next = unwrapped + std::remainder(now - raw, p);
        if (next > unwrapped)
          circle_ups +=
              static_cast<int>(std::floor((next - level) / p) - std::floor((unwrapped - level) / p));
        unwrapped = next, raw = now, highest = std::max(highest, next);
      });
  ASSERT_GE(circle_ups, 3);
  ASSERT_GE(wraps, 3);  // the wrapped u jumps: each jump was a crossing before
  const std::vector<double> v = summarised(
      scene,
      {.summaries = {parse_summary("u.max"), parse_summary("u.final")}, .events = {parse_event("u:up:1.5")}},
      T, 0.5);
  EXPECT_NEAR(v[0], highest, 1e-6);  // the continuous angle's maximum, not ±π
  EXPECT_GT(v[0], 2.0 * p);
  EXPECT_NEAR(v[1], unwrapped, 1e-8);
  EXPECT_EQ(v[2], circle_ups);
  // stop=2 stops at the second crossing of the circle u = 1.5, not at a wrap.
  Simulation stopped;
  summarised(scene, {.summaries = {}, .events = {parse_event("u:up:1.5:stop=2")}}, T, 0.5, &stopped);
  ASSERT_EQ(stopped.state.status, Status::event_stop);
  EXPECT_NEAR(std::remainder(profile_readout(*stopped.embedded, stopped.state.y).coordinates.r - level, p),
              0.0, 1e-9);
}

// A period far below the field's change over a step: every crossing counted (the levels are counted
// in each step, not visited one by one; 10,000 a step were kept before and the rest dropped without
// a word), the first and last located, in the time a few root finds take.
TEST(RunSummary, CrossingsAreCountedNotVisited) {
  const Scene scene = w5_with("dop853", 0.01, 1e-12);
  const double T = 40.0, P = 1e-6;
  const auto started = std::chrono::steady_clock::now();
  const std::vector<double> v = summarised(
      scene, {.summaries = {parse_summary("phi.final")}, .events = {parse_event("phi:any:0:period=1e-6")}}, T,
      0.5);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 5.0);
  const Simulation start = start_simulation(scene);
  const double phi0 = global_body(scene, start.state).phi, phi_T = v[0];
  // φ increases through the run (w5 circles): the multiples k·P in (φ₀, φ_T].
  ASSERT_GT(phi_T - phi0, 2.0 * std::numbers::pi);
  const double expected = std::floor(phi_T / P) - std::floor(phi0 / P);
  EXPECT_NEAR(v[1], expected, 2.0) << "count";
  EXPECT_GT(v[1], 6e6);
  EXPECT_NEAR(v[2], 0.0, 1e-3) << "t_first: the first level just after the start";
  EXPECT_NEAR(v[3], T, 1e-3) << "t_last: the last level just before the end";
}

// The closed form looks at its points every dt for a summary: a jump of 10⁸ is 10¹⁰ of them, which
// ran inside one advance whatever --max-steps or --max-seconds said (issue 48's hunt). Each point is
// now one of the advance's step attempts: a budget stops it, and the values do not depend on how
// the run was cut.
TEST(RunSummary, TheClosedFormsPointsAreStepAttempts) {
  const Scene scene = w5_with("exact", 0.01, 1e-12);
  const MonitorSpec spec{.summaries = {parse_summary("r")}, .events = {parse_event("phi:any:0:period=0.1")}};
  Simulation cut = start_simulation(scene);
  watch(cut, spec);
  std::uint64_t attempts = 1000;
  const auto started = std::chrono::steady_clock::now();
  EXPECT_FALSE(advance_within(cut, 1e8, attempts));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 1.0);
  EXPECT_EQ(attempts, 0u);
  EXPECT_NEAR(cut.state.t, 10.0, 1e-9) << "1000 points of dt = 0.01";
  for (int k = 0; k < 5; ++k) {
    std::uint64_t more = 700;
    advance_within(cut, 40.0, more);
  }
  advance_to(cut, 40.0);
  Simulation whole = start_simulation(scene);
  watch(whole, spec);
  advance_to(whole, 40.0);
  EXPECT_EQ(monitor_values(cut), monitor_values(whole));
  EXPECT_EQ(cut.state.y, whole.state.y);
}

// Levels closer than double tells apart where the field is (1e-300 apart at φ ~ 1): the run stops
// at the start of the first step that meets them, with event_unresolved, instead of looping there.
TEST(RunSummary, LevelsDoubleCannotTellApartStopTheRun) {
  const Scene scene = w5_with("dop853", 0.01, 1e-12);
  Simulation run;
  const auto started = std::chrono::steady_clock::now();
  const std::vector<double> v = summarised(
      scene, {.summaries = {}, .events = {parse_event("phi:any:0:period=1e-300")}}, 10.0, 0.5, &run);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 2.0);
  EXPECT_EQ(run.state.status, Status::event_unresolved);
  EXPECT_LT(run.state.t, 10.0);
  EXPECT_TRUE(std::isfinite(run.state.y.norm()));
}

}  // namespace
}  // namespace spinfold
