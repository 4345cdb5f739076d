#include "engine/chaos_indicators.h"

#include <cmath>
#include <numbers>

#include "engine/chart.h"
#include "engine/embedded_run.h"
#include "engine/invariants.h"
#include "engine/number_rule.h"
#include "engine/number_text.h"
#include "engine/sliced_advance.h"

namespace spinfold {

namespace {

// `state`'s coordinates in `chart` (the same body; chart-free states need no move).
Coords in_chart(const Simulation& run, const State& state, const Chart& chart) {
  if (run.embedded) return state.y;
  const Surface& surface = run.scene.surface;
  BodyKinematics body = chart_kinematics(run.scene, state.y);
  const Mat3 back = inverse_linear(surface, chart.A);
  const Mat3 to = back * state.chart.A;
  body.X = back * (state.chart.A * body.X + state.chart.b - chart.b);
  body.V = to * body.V;
  body.F1 = to * body.F1;
  return chart_coords(run.scene, body);
}

// a − b for two states' coordinates in one chart, with the angles' differences wrapped to (−π, π]
// (φ of one may be the other's plus 2π).
Coords difference(const Simulation& run, const Coords& a, const Coords& b) {
  Coords d = a - b;
  if (!run.embedded) {
    d[coord::phi] = std::remainder(d[coord::phi], 2.0 * std::numbers::pi);
    if (run.scene.body.model == BodyModel::rigid)
      d[coord::theta] = std::remainder(d[coord::theta], 2.0 * std::numbers::pi);
  }
  return d;
}

// X, V, e_A, W_A of a state in `chart`'s embedding coordinates (the scene's where the curvature
// varies): moderate numbers even far out on H², where the scene's own coordinates grow like e^{r/R}.
Eigen::Matrix<double, 18, 1> embedded_in(const Simulation& run, const State& state, const Chart& chart) {
  EmbeddedBody b = run.embedded ? embedded_body(*run.embedded, state.y) : global_embedding(run.scene, state);
  if (!run.embedded) {
    const Mat3 back = inverse_linear(run.scene.surface, chart.A);
    b.X = back * (b.X - chart.b);
    for (Vec3* v : {&b.V, &b.e[0], &b.e[1], &b.W[0], &b.W[1]}) *v = back * *v;
  }
  Eigen::Matrix<double, 18, 1> v;
  v << b.X, b.V, b.e[0], b.e[1], b.W[0], b.W[1];
  return v;
}

// Moves every vector of `v` by the isometry that takes `at` (a point of the surface) to its pole O
// (the origin of the plane): a boost on H², a rotation on S², a translation on the plane. Norms
// measured after it are the same wherever the reference body is: the metric is intrinsic.
void to_pole(const Surface& surface, const Vec3& at, Eigen::Matrix<double, 18, 1>& v) {
  if (offers(surface, Offer::zero_curvature)) {
    v.segment<3>(0) -= at;
    return;
  }
  const double rho = std::hypot(at.x(), at.y());
  if (!(rho > 0.0)) return;
  const double nx = at.x() / rho, ny = at.y() / rho, c = at.z() / surface.radius, s = rho / surface.radius;
  const bool hyperbolic = offers(surface, Offer::negative_curvature);
  for (int block = 0; block < 6; ++block) {
    Vec3 w = v.segment<3>(3 * block);
    const double along = nx * w.x() + ny * w.y(), across = -ny * w.x() + nx * w.y();
    const double along_new = c * along - s * w.z();
    const double z_new = hyperbolic ? -s * along + c * w.z() : s * along + c * w.z();
    v.segment<3>(3 * block) = Vec3(nx * along_new - ny * across, ny * along_new + nx * across, z_new);
  }
}

// The scene with its initial values moved by about `size` in a fixed generic direction.
Scene nudged(Scene scene, double size) {
  InitialState& i = scene.initial;
  i.r += 0.9 * size;
  i.phi += 0.7 * size;
  i.lambda += 0.5 * size;
  i.mu += 0.3 * size;
  i.r_dot += 0.6 * size;
  i.phi_dot += 0.4 * size;
  i.lambda_dot += 0.2 * size;
  i.mu_dot += 0.8 * size;
  i.beta_dot += 0.35 * size;
  if (i.spin) *i.spin += 0.45 * size;
  if (i.speed) *i.speed += 0.25 * size;
  if (!i.spin) i.alpha_dot += 0.45 * size;
  return scene;
}

}  // namespace

std::optional<std::string> chaos_interval_refusal(double interval, double t_end) {
  if (const auto why = refusal(NumberRule{.range = kPositive, .unit = "time"}, interval))
    return *why + " (got " + shortest(interval) + ")";
  if (interval > t_end)
    return "must be at most the run's length t_end = " + shortest(t_end) + " (got " + shortest(interval) +
           "): no interval would end";
  if (t_end / interval > 1e6)
    return "t_end / interval must be at most 1e6 (got " + shortest(t_end / interval) +
           "): each interval restarts the shadow run";
  return std::nullopt;
}

std::array<double, 5> chaos_values(const ChaosIndicators& c) {
  return {c.lyapunov, c.megno, c.megno_mean, c.lyapunov_time, c.t};
}

ChaosMonitor::ChaosMonitor(const Scene& scene, double interval, double start_time)
    : scene_(scene), interval_(interval), t0_(start_time) {
  scene_.companions.clear();
  reference_ = start_simulation(scene_, t0_);
  shadow_ =
      start_simulation(nudged(scene_, kChaosSeparation * std::max(reference_.state.y.norm(), 1e-300)), t0_);
  start_reference_ = reference_.state;
  start_shadow_ = shadow_.state;
  stopped_ = !(separation(start_shadow_, start_reference_, reference_.state.chart) > 0.0);
}

// Measured intrinsically: both bodies moved so that the reference sits at the pole (to_pole).
double ChaosMonitor::separation(const State& shadow, const State& reference, const Chart& chart) const {
  Eigen::Matrix<double, 18, 1> a = embedded_in(reference_, shadow, chart),
                               b = embedded_in(reference_, reference, chart);
  if (!reference_.embedded) {
    const Vec3 at = b.segment<3>(0);
    to_pole(reference_.scene.surface, at, a);
    to_pole(reference_.scene.surface, at, b);
  }
  return (a - b).norm();
}

// The shadow restarted at the reference's state plus the separation scaled back to d₀.
void ChaosMonitor::seed_shadow() {
  const Chart& chart = reference_.state.chart;
  const Coords apart = difference(reference_, in_chart(reference_, shadow_.state, chart), reference_.state.y);
  const double scale = kChaosSeparation * reference_.state.y.norm() / apart.norm();
  State seeded = reference_.state;
  seeded.y = reference_.state.y + scale * apart;
  seeded.status = Status::ok;
  // Both runs start a step sequence here with the reference's next step, so an adaptive integrator
  // takes the same steps in both to O(d₀): the separation is then the tangent flow of one map, not
  // the two sequences' difference. (A shadow that began with the scene's first trial step took
  // another sequence, and the integrator's error per interval, ~1 % of d₀ at tolerance 1e-10, was
  // counted as growth: ⟨Y⟩ 20.7 on an integrable torus scene at T = 800.)
  retune(reference_, scene_);
  shadow_ = start_simulation(scene_, seeded.t);
  shadow_.state = seeded;
  retune(shadow_, scene_);
  shadow_.grid.h_next = reference_.grid.h_next;
  shadow_.checked = shadow_.grid;
  start_reference_ = reference_.state;
  start_shadow_ = shadow_.state;
}

void ChaosMonitor::advance_to(double t, std::uint64_t max_attempts,
                              std::optional<std::chrono::steady_clock::time_point> deadline) {
  advance_to(t, max_attempts, [&] { return !deadline || std::chrono::steady_clock::now() <= *deadline; });
}

void ChaosMonitor::advance_to(double t, std::uint64_t max_attempts, const std::function<bool()>& go_on) {
  // Each run in slices of step attempts, `go_on` asked between them.
  const auto reach = [&](Simulation& run, double t_next) {
    const Advanced got = advance_in_slices(run, t_next, max_attempts, go_on, 1024);
    if (got == Advanced::stopped_by_caller) {
      stopped_reason_ = "the time budget ran out";
      out_of_time_ = true;
    } else if (got == Advanced::out_of_attempts) {
      stopped_reason_ = "the step budget ran out";
      out_of_steps_ = true;
    }
    return got == Advanced::reached;
  };
  while (!stopped_) {
    const double t_next = t0_ + static_cast<double>(k_ + 1) * interval_;
    if (t_next > t) return;
    if (!reach(reference_, t_next) || !reach(shadow_, t_next)) {
      stopped_ = true;
      return;
    }
    if (reference_.state.status != Status::ok || shadow_.state.status != Status::ok ||
        reference_.state.t != t_next || shadow_.state.t != t_next) {
      stopped_ = true;
      const Status why =
          reference_.state.status != Status::ok ? reference_.state.status : shadow_.state.status;
      stopped_reason_ = "the runs stopped: " + std::string(status_name(why));
      return;
    }
    if (offers(scene_.surface, Offer::negative_curvature) &&
        global_body(scene_, reference_.state).r > kChaosMaxHyperbolicDistance * scene_.surface.radius) {
      stopped_ = true;
      stopped_reason_ =
          "farther than 5.5 R out on the pseudosphere, where relating two charts rounds to 1/1000 of the "
          "separation";
      return;
    }
    // Both ends in the reference's chart now: a chart move inside the interval is not growth.
    const Chart& chart = reference_.state.chart;
    const double d = separation(shadow_.state, reference_.state, chart);
    const double d_start = separation(start_shadow_, start_reference_, chart);
    if (!(d > 0.0) || !std::isfinite(d) || !(d_start > 0.0) || !std::isfinite(d_start)) {
      stopped_ = true;
      return;
    }
    const double g = std::log(d / d_start);
    const double t_before = t0_ + static_cast<double>(k_) * interval_;
    ++k_;
    const double elapsed = t_next - t0_;
    sum_g_ += g;
    sum_weighted_g_ += g * 0.5 * ((t_before - t0_) + elapsed);
    megno_ = 2.0 * sum_weighted_g_ / elapsed;
    sum_megno_ += megno_;
    seed_shadow();
  }
}

ChaosIndicators ChaosMonitor::indicators() const {
  ChaosIndicators c;
  c.t = t0_ + static_cast<double>(k_) * interval_;
  c.intervals = k_;
  c.stopped = stopped_reason_;
  c.out_of_steps = out_of_steps_;
  c.out_of_time = out_of_time_;
  if (k_ == 0) return c;
  const double elapsed = c.t - t0_;
  c.lyapunov = sum_g_ / elapsed;
  c.megno = megno_;
  c.megno_mean = sum_megno_ / static_cast<double>(k_);
  c.lyapunov_time = c.lyapunov > 0.0 ? 1.0 / c.lyapunov : std::numeric_limits<double>::infinity();
  return c;
}

}  // namespace spinfold
