#include "engine/run_summary.h"

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/embedded_run.h"
#include "engine/invariants.h"
#include "engine/number_rule.h"
#include "engine/number_text.h"
#include "engine/paper_coordinates.h"
#include "engine/simulation.h"

namespace spinfold {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The field table: the index is the field's place in a Values array.
enum Field {
  f_r,
  f_phi,
  f_lambda,
  f_mu,
  f_det_L,
  f_energy,
  f_energy_error,
  f_spin,
  f_speed,
  f_X0,
  f_X1,
  f_X2,
  f_K
};
constexpr int kFieldCount = f_K + 1;
constexpr std::array<std::string_view, kFieldCount> kFieldNames = {
    "r", "phi", "lambda", "mu", "det_L", "energy", "energy_error", "spin", "speed", "X.0", "X.1", "X.2", "K"};

bool profile(const Scene& scene) {
  return chart_free(scene.surface);
}
// A surface with no chart (a formula surface): no r, u or φ.
bool chartless(const Scene& scene) {
  return chart_free(scene.surface) && !offers(scene.surface, Offer::profile_chart);
}

// The field's index for this scene, or -1 (u stands for r where the curvature varies, K exists only there).
int field_index(const Scene& scene, std::string_view name) {
  if (chartless(scene) && (name == "r" || name == "u" || name == "phi")) return -1;
  if (name == (profile(scene) ? "u" : "r")) return f_r;
  if (name == "r" || name == "u") return -1;
  if (name == "K") return profile(scene) ? f_K : -1;
  for (int i = 0; i < kFieldCount; ++i)
    if (kFieldNames[i] == name) return i;
  return -1;
}

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

std::vector<std::string> split_on(std::string_view text, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i)
    if (i == text.size() || text[i] == sep) {
      parts.emplace_back(text.substr(start, i - start));
      start = i + 1;
    }
  return parts;
}

// One number of an event's text by the one number reader and rule (engine/number_rule.h).
double event_number(const std::string& event, std::string_view what, const std::string& text,
                    const NumberRule& rule) {
  const std::optional<double> x = number_from_text(text);
  if (!x || !allows(rule, *x))
    throw MonitorRefusal("event '" + event + "': " + refused(what, must_be(rule), "'" + text + "'"), true);
  return *x;
}

std::string level_text(double v) {
  return shortest(v);
}

}  // namespace

RunMonitor::Crossed RunMonitor::crossings(const EventSpec& spec, double ga, double gb) {
  Crossed c;
  if (std::isnan(ga) || std::isnan(gb) || ga == gb) return c;
  c.up = gb > ga;
  if ((c.up && spec.direction == Direction::down) || (!c.up && spec.direction == Direction::up)) return c;
  c.base = spec.level;
  c.period = spec.period;
  // Levels L with ga < L <= gb (up) or gb <= L < ga (down).
  const auto is_crossed = [&](double level) {
    return c.up ? (ga < level && gb >= level) : (ga > level && gb <= level);
  };
  if (spec.period <= 0.0) {
    c.n = is_crossed(spec.level) ? 1.0 : 0.0;
    return c;
  }
  const double P = spec.period, L = spec.level;
  if (P < kMinRelativePeriod * std::max({std::abs(ga), std::abs(gb), std::abs(L)})) {
    c.unresolved = true;
    return c;
  }
  const double lo = std::min(ga, gb), hi = std::max(ga, gb);
  double k_lo = c.up ? std::floor((lo - L) / P) + 1.0 : std::ceil((lo - L) / P);
  double k_hi = c.up ? std::floor((hi - L) / P) : std::ceil((hi - L) / P) - 1.0;
  // The quotients' rounding can move an end by one: each end is checked against the crossing itself.
  for (int i = 0; i < 2 && k_lo <= k_hi && !is_crossed(L + k_lo * P); ++i) k_lo += 1.0;
  for (int i = 0; i < 2 && k_lo <= k_hi && !is_crossed(L + k_hi * P); ++i) k_hi -= 1.0;
  if (is_crossed(L + (k_lo - 1.0) * P)) k_lo -= 1.0;
  if (is_crossed(L + (k_hi + 1.0) * P)) k_hi += 1.0;
  c.n = std::max(0.0, k_hi - k_lo + 1.0);
  // In time order: up the lowest level first, down the highest.
  c.k_first = c.up ? k_lo : k_hi;
  return c;
}

std::vector<std::string> monitor_field_names(const Scene& scene) {
  std::vector<std::string> names;
  for (int i = 0; i < kFieldCount; ++i) {
    if (i == f_K && !profile(scene)) continue;
    if ((i == f_r || i == f_phi) && chartless(scene)) continue;
    names.emplace_back(i == f_r && profile(scene) ? "u" : kFieldNames[i]);
  }
  return names;
}

SummarySpec parse_summary(std::string_view text) {
  SummarySpec s;
  const std::size_t dot = text.rfind('.');
  if (dot != std::string_view::npos) {
    const std::string_view tail = text.substr(dot + 1);
    const auto r = std::find(kReductionNames.begin(), kReductionNames.end(), tail);
    if (r != kReductionNames.end()) {
      s.field = std::string(text.substr(0, dot));
      s.reductions = {static_cast<Reduction>(r - kReductionNames.begin())};
    }
  }
  if (s.field.empty()) {
    s.field = std::string(text);
    for (std::size_t i = 0; i < kReductionNames.size(); ++i)
      s.reductions.push_back(static_cast<Reduction>(i));
  }
  if (s.field.empty())
    throw MonitorRefusal("summary '" + std::string(text) +
                             "': name a field, or FIELD.REDUCTION (min, max, mean, final, t_min, t_max)",
                         false);
  return s;
}

EventSpec parse_event(std::string_view text) {
  const std::vector<std::string> parts = split_on(text, ':');
  const std::string t(text);
  if (parts.size() < 3 || parts[0].empty())
    throw MonitorRefusal(
        "event '" + t +
            "': write FIELD:DIRECTION:LEVEL[:period=P][:stop=N][:record[=N]][:name=NAME], e.g. "
            "r:up:1.2",
        true);
  EventSpec e;
  e.field = parts[0];
  if (parts[1] == "up")
    e.direction = Direction::up;
  else if (parts[1] == "down")
    e.direction = Direction::down;
  else if (parts[1] == "any")
    e.direction = Direction::any;
  else
    throw MonitorRefusal("event '" + t + "': the direction must be up, down or any (got '" + parts[1] + "')",
                         true);
  e.level = event_number(t, "the level", parts[2], NumberRule{});
  std::vector<std::string> given;  // each key once, as a JSON object's
  for (std::size_t i = 3; i < parts.size(); ++i) {
    const std::size_t eq = parts[i].find('=');
    const std::string key = parts[i].substr(0, eq),
                      value = eq == std::string::npos ? "" : parts[i].substr(eq + 1);
    const bool known = key == "period" || key == "stop" || key == "name" || key == "record";
    if (known && std::find(given.begin(), given.end(), key) != given.end())
      throw MonitorRefusal("event '" + t + "': " + key + "= is given twice (give it once)", true);
    given.push_back(key);
    if (key == "period") {
      e.period = event_number(t, "period", value, NumberRule{.range = kPositive});
      if (e.period < kMinRelativePeriod * std::abs(e.level))
        throw MonitorRefusal("event '" + t + "': period must be at least 1e-12 of |level| (" +
                                 shortest(kMinRelativePeriod * std::abs(e.level)) +
                                 ") so that the levels are "
                                 "distinct in double (got '" +
                                 value + "')",
                             true);
    } else if (key == "stop") {
      e.stop = static_cast<std::uint64_t>(event_number(
          t, "stop", value, NumberRule{.whole = true, .range = {.min = 1.0, .max = kMaxWholeNumber}}));
    } else if (key == "record") {
      e.record =
          eq == std::string::npos
              ? kMaxRecordedCrossings
              : static_cast<std::uint64_t>(event_number(
                    t, "record", value,
                    NumberRule{.whole = true,
                               .range = {.min = 1.0, .max = static_cast<double>(kMaxRecordedCrossings)}}));
    } else if (key == "name" && !value.empty()) {
      e.name = value;
    } else {
      throw MonitorRefusal("event '" + t + "': unknown part '" + parts[i] +
                               "' (period=P, stop=N, record, record=N or name=NAME)",
                           true);
    }
  }
  if (e.name.empty()) e.name = e.field + "_" + parts[1] + "_" + level_text(e.level);
  return e;
}

MonitorSpec parse_monitor(const std::vector<std::string>& summaries, const std::vector<std::string>& events) {
  MonitorSpec spec;
  for (const std::string& text : summaries) spec.summaries.push_back(parse_summary(text));
  for (const std::string& text : events) spec.events.push_back(parse_event(text));
  return spec;
}

void check_monitor(const MonitorSpec& spec, const Scene& scene) {
  const auto known = [&](const std::string& field, const std::string& what, bool event) {
    if (field_index(scene, field) < 0)
      throw MonitorRefusal(what + ": unknown field '" + field + "' for this scene (one of " +
                               join(monitor_field_names(scene)) +
                               "; or FIELD.REDUCTION, REDUCTION one of min, max, mean, final, t_min, t_max)",
                           event);
  };
  for (const SummarySpec& s : spec.summaries) known(s.field, "summary '" + s.field + "'", false);
  std::vector<std::string> names;
  for (const EventSpec& e : spec.events) {
    known(e.field, "event '" + e.name + "'", true);
    if (std::find(names.begin(), names.end(), e.name) != names.end())
      throw MonitorRefusal("event '" + e.name + "': two events have this name (give one name=OTHER)", true);
    names.push_back(e.name);
  }
}

std::vector<std::string> monitor_columns(const MonitorSpec& spec) {
  std::vector<std::string> columns;
  for (const SummarySpec& s : spec.summaries)
    for (const Reduction r : s.reductions)
      columns.push_back(s.field + "." + std::string(kReductionNames[static_cast<int>(r)]));
  for (const EventSpec& e : spec.events) {
    for (const char* c : {".count", ".t_first", ".t_last"}) columns.push_back(e.name + c);
    for (const SummarySpec& s : spec.summaries) columns.push_back(e.name + ".at." + s.field);
  }
  return columns;
}

RunMonitor::RunMonitor(MonitorSpec spec, const Simulation& run) : spec_(std::move(spec)) {
  check_monitor(spec_, run.scene);
  const auto watch = [&](const std::string& name) {
    const int f = field_index(run.scene, name);
    const auto at = std::find(fields_.begin(), fields_.end(), f);
    if (at != fields_.end()) return static_cast<int>(at - fields_.begin());
    fields_.push_back(f);
    return static_cast<int>(fields_.size() - 1);
  };
  for (const SummarySpec& s : spec_.summaries) summary_index_.push_back(watch(s.field));
  for (const EventSpec& e : spec_.events) event_index_.push_back(watch(e.field));
  // The angles: φ, and u where the profile's domain is a circle (the torus's tube angle). Their
  // values are continuous (turns counted, not wrapped), and an event's level on one is a level on
  // the circle: level + k·period for every k, the period the angle's own unless the text gave one.
  angle_period_.fill(0.0);
  angle_period_[f_phi] = 2.0 * std::numbers::pi;
  if (run.surface->profile) {
    const ProfileDomain d = revolution_entry(run.surface->profile->kind).domain(*run.surface->profile);
    if (d.periodic) angle_period_[f_r] = d.u_max - d.u_min;
  }
  for (std::size_t e = 0; e < spec_.events.size(); ++e)
    if (spec_.events[e].period == 0.0) spec_.events[e].period = angle_period_[fields_[event_index_[e]]];
  // What evaluate() must compute, decided once: the energy, the body, or only its position.
  for (const int f : fields_) {
    const bool energy = f == f_energy || f == f_energy_error, x = f == f_X0 || f == f_X1 || f == f_X2;
    (energy ? reads_.energy : reads_.body) = true;
    reads_.x = reads_.x || x;
    reads_.position_only = reads_.position_only && (energy || x || f == f_r || f == f_phi);
  }
  last_ = run.state;
  t_start_ = run.state.t;
  last_values_ = evaluate(run, last_, nullptr);
  for (std::size_t k = 0; k < fields_.size(); ++k) {
    const double v = last_values_[k];
    tracks_.push_back({v, v, t_start_, t_start_, 0.0, v});
  }
  events_.resize(spec_.events.size());
  recorded_ = std::make_shared<std::vector<std::vector<State>>>(spec_.events.size());
}

// The watched fields at `s`; phi continues `near` (its turns are counted, not wrapped).
RunMonitor::Values RunMonitor::evaluate(const Simulation& run, const State& s, const Values* near) const {
  Values out;
  out.fill(kNaN);
  const Scene& scene = run.scene;
  const bool energy_needed = reads_.energy, body_needed = reads_.body, position_only = reads_.position_only,
             x_needed = reads_.x;
  std::array<double, kFieldCount> v;
  v.fill(kNaN);
  if (energy_needed) {
    const EnergyParts e =
        run.embedded ? embedded_energy_parts(*run.embedded, s.y) : energy_parts(scene, s.chart, s.y);
    v[f_energy] = e.kinetic + e.potential;
    v[f_energy_error] = (v[f_energy] - run.initial_energy) / std::max(std::abs(run.initial_energy), 1e-300);
  }
  std::optional<double> phi;
  if (body_needed && run.embedded && !run.surface->profile) {
    const FreeReadout p = free_readout(*run.embedded, s.y);
    const PaperCoordinates& c = p.coordinates;
    v[f_lambda] = c.lambda;
    v[f_mu] = c.mu;
    v[f_det_L] = c.det_L;
    v[f_spin] = c.p_alpha;
    v[f_speed] = p.speed;
    for (int i = 0; i < 3; ++i) v[f_X0 + i] = c.X[i];
    v[f_K] = p.K;
  } else if (body_needed && run.embedded) {
    const ProfileReadout p = profile_readout(*run.embedded, s.y);
    const PaperCoordinates& c = p.coordinates;
    v[f_r] = c.r;
    phi = c.phi;
    v[f_lambda] = c.lambda;
    v[f_mu] = c.mu;
    v[f_det_L] = c.det_L;
    v[f_spin] = c.p_alpha;
    v[f_speed] = p.speed;
    for (int i = 0; i < 3; ++i) v[f_X0 + i] = c.X[i];
    v[f_K] = p.K;
  } else if (body_needed && position_only && s.chart.global && !x_needed) {
    // In the scene's own chart r and φ are coordinates of the state (global_body reads them back
    // through X, which can differ in the last bits): the monitor's cheapest read.
    v[f_r] = s.y[coord::r];
    if (!(v[f_r] <= 1e-12 * scene.surface.radius)) phi = s.y[coord::phi];
  } else if (body_needed && position_only) {
    // r, φ and X alone: global_body's own first lines (the same numbers), not its frame.
    const ChartPoint p = chart_point(scene.surface, s.y[coord::r], s.y[coord::phi]);
    const Vec3 X = s.chart.A * p.X + s.chart.b;
    const PolarCoordinates pc = polar_coordinates(scene.surface, X);
    v[f_r] = pc.r;
    if (!(pc.rho <= 1e-12 * scene.surface.radius)) phi = pc.phi;
    for (int i = 0; i < 3; ++i) v[f_X0 + i] = X[i];
  } else if (body_needed) {
    const GlobalBody g = global_body(scene, s);
    v[f_r] = g.r;
    if (!g.at_pole) phi = g.phi;
    const FrameStretches st = frame_stretches(g.L);
    v[f_lambda] = st.lambda;
    v[f_mu] = st.mu;
    v[f_det_L] = g.L.determinant();
    v[f_spin] = g.spin;
    v[f_speed] = g.at_pole ? std::abs(g.r_dot) : std::hypot(g.r_dot, g.S * g.phi_dot);
    for (int i = 0; i < 3; ++i) v[f_X0 + i] = g.X[i];
  }
  for (std::size_t k = 0; k < fields_.size(); ++k) {
    out[k] = v[fields_[k]];
    if (fields_[k] == f_r && angle_period_[f_r] > 0.0) {  // the torus's u: continued like φ
      const double previous = near ? (*near)[k] : kNaN;
      if (!std::isnan(previous)) out[k] = previous + std::remainder(out[k] - previous, angle_period_[f_r]);
    } else if (fields_[k] == f_phi) {
      const double previous = near ? (*near)[k] : kNaN;
      if (!phi)
        out[k] = previous;  // at a pole φ is undefined: it keeps its last value
      else
        out[k] =
            std::isnan(previous) ? *phi : previous + std::remainder(*phi - previous, 2.0 * std::numbers::pi);
    }
  }
  return out;
}

void RunMonitor::refine_extremum(const Simulation& run, std::size_t k, bool maximum) {
  // Brent's method over the two steps around the sequence point `last_`, on their own sub-steps.
  const double sign = maximum ? -1.0 : 1.0;
  const auto g = [&](double t) {
    const bool first = t <= last_.t;
    const State& from = first ? before_ : last_;
    const Values& near = first ? before_values_ : last_values_;
    if (t == from.t) return sign * near[k];
    return sign * evaluate(run, state_after(run, from, t - from.t), &near)[k];
  };
  const auto [t, value] = boost::math::tools::brent_find_minima(g, before_.t, last_.t + (last_.t - before_.t),
                                                                std::numeric_limits<double>::digits / 2);
  Track& track = tracks_[k];
  const double v = sign * value;
  if (maximum && v > track.max) track.max = v, track.t_max = t;
  if (!maximum && v < track.min) track.min = v, track.t_min = t;
}

std::optional<State> RunMonitor::step(const Simulation& run, const State& b_in) {
  if (stopped_) return std::nullopt;
  const double h = b_in.t - last_.t;
  if (!(h > 0.0)) return std::nullopt;
  State b = b_in;
  Values vb = evaluate(run, b, &last_values_);

  // Events: the levels a step crosses are counted, never visited one by one (a period far below the
  // field's change over a step would take a root find per level); the first and the last crossing in
  // time and a terminal one are located by TOMS 748 on the step's own sub-steps.
  const auto locate = [&](int k, double ga, double gb, double level) {
    const auto f = [&](double tau) {
      if (tau <= 0.0) return ga - level;
      if (tau >= h) return gb - level;
      return evaluate(run, state_after(run, last_, tau), &last_values_)[k] - level;
    };
    std::uintmax_t iterations = 100;
    const auto tol = [h](double a, double c) { return std::abs(c - a) <= 1e-14 * h; };
    const auto [a, c] = boost::math::tools::toms748_solve(f, 0.0, h, ga - level, gb - level, tol, iterations);
    return 0.5 * (a + c);
  };
  std::vector<Crossed> crossed(spec_.events.size());
  double tau_stop = std::numeric_limits<double>::infinity();
  std::size_t stop_event = spec_.events.size();
  for (std::size_t e = 0; e < spec_.events.size(); ++e) {
    const EventSpec& spec = spec_.events[e];
    const int k = event_index_[e];
    crossed[e] = crossings(spec, last_values_[k], vb[k]);
    if (crossed[e].unresolved || static_cast<double>(events_[e].count) + crossed[e].n > kMaxEventCount) {
      // The levels cannot be told apart here: stop at the step's start, the last state whose
      // crossings were counted (engine/state.h, event_unresolved).
      stopped_ = true;
      State at = last_;
      at.status = Status::event_unresolved;
      return at;
    }
    const double wanted = static_cast<double>(spec.stop) - static_cast<double>(events_[e].count);
    if (spec.stop > 0 && wanted >= 1.0 && wanted <= crossed[e].n) {
      const double tau = locate(k, last_values_[k], vb[k], crossed[e].level(wanted - 1.0));
      if (tau < tau_stop) tau_stop = tau, stop_event = e;
    }
  }
  if (stop_event < spec_.events.size()) {
    // A terminal event cuts the step: the others count what they crossed before it.
    b = state_after(run, last_, tau_stop);
    b.status = Status::event_stop;
    vb = evaluate(run, b, &last_values_);
    for (std::size_t e = 0; e < spec_.events.size(); ++e)
      crossed[e] = e == stop_event
                       ? crossed[e].first(static_cast<double>(spec_.events[e].stop - events_[e].count))
                       : crossings(spec_.events[e], last_values_[event_index_[e]], vb[event_index_[e]]);
    stopped_ = true;
  }
  for (std::size_t e = 0; e < spec_.events.size(); ++e) {
    const Crossed& c = crossed[e];
    if (!(c.n >= 1.0) || c.unresolved) continue;
    const int k = event_index_[e];
    const double gb = vb[k];
    Occurrences& o = events_[e];
    const bool last_is_stop = e == stop_event;
    double tau_first = -1.0;
    if (o.count == 0) {
      tau_first = last_is_stop && c.n == 1.0 ? tau_stop : locate(k, last_values_[k], gb, c.level(0.0));
      o.t_first = last_.t + tau_first;
      const Values values = evaluate(run, state_after(run, last_, tau_first), &last_values_);
      for (const int s : summary_index_) o.at_first.push_back(values[s]);
    }
    const double tau_last = last_is_stop ? tau_stop
                            : tau_first >= 0.0 && c.n == 1.0
                                ? tau_first
                                : locate(k, last_values_[k], gb, c.level(c.n - 1.0));
    // Each occurrence's state where the event records them (a root find each, up to its bound).
    if (spec_.events[e].record > 0) {
      std::vector<State>& kept = (*recorded_)[e];
      while (!kept.empty() && kept.back().t > last_.t) kept.pop_back();  // rewound past them
      const double room = static_cast<double>(spec_.events[e].record) - static_cast<double>(o.count);
      for (double j = 0.0; j < std::min(c.n, room); j += 1.0) {
        const bool is_last = j == c.n - 1.0;
        const double tau = j == 0.0 && tau_first >= 0.0 ? tau_first
                           : is_last                    ? tau_last
                                                        : locate(k, last_values_[k], gb, c.level(j));
        kept.push_back(is_last && last_is_stop ? b : state_after(run, last_, tau));
      }
    }
    o.count += static_cast<std::uint64_t>(c.n);
    o.t_last = last_.t + tau_last;
  }

  // Reductions: an interior extremum at last_ is refined where the parabola through the three
  // points says it beats the one so far; then the new point and the step's trapezoid.
  const double hb = b.t - last_.t;
  for (std::size_t k = 0; k < fields_.size(); ++k) {
    Track& track = tracks_[k];
    if (has_before_ && hb > 0.0) {
      const double t0 = before_.t, t1 = last_.t, t2 = b.t;
      const double g0 = before_values_[k], g1 = last_values_[k], g2 = vb[k];
      const double d1 = (g1 - g0) / (t1 - t0), d2 = (g2 - g1) / (t2 - t1), a = (d2 - d1) / (t2 - t0);
      if (a != 0.0 && std::isfinite(a)) {
        const double ts = 0.5 * (t0 + t1) - d1 / (2.0 * a);
        const double peak = g0 + d1 * (ts - t0) + a * (ts - t0) * (ts - t1);
        if (ts > t0 && ts < t2) {
          if (a < 0.0 && g1 >= g0 && g1 >= g2 && peak > track.max) refine_extremum(run, k, true);
          if (a > 0.0 && g1 <= g0 && g1 <= g2 && peak < track.min) refine_extremum(run, k, false);
        }
      }
    }
    const double v = vb[k];
    if (v > track.max) track.max = v, track.t_max = b.t;
    if (v < track.min) track.min = v, track.t_min = b.t;
    // ∫ over the step of the parabola through the last three points: the trapezoid less a·h³/6,
    // a the second divided difference (the trapezoid alone on the first step).
    double curvature = 0.0;
    if (has_before_) {
      const double t0 = before_.t, t1 = last_.t;
      const double a =
          ((v - last_values_[k]) / hb - (last_values_[k] - before_values_[k]) / (t1 - t0)) / (b.t - t0);
      if (std::isfinite(a)) curvature = a;
    }
    track.integral += 0.5 * (last_values_[k] + v) * hb - curvature * hb * hb * hb / 6.0;
    track.final = v;
  }
  before_ = std::move(last_);
  before_values_ = last_values_;
  has_before_ = true;
  last_ = b;
  last_values_ = vb;
  if (stopped_) return b;
  return std::nullopt;
}

std::vector<State> RunMonitor::recorded(std::size_t e) const {
  const std::vector<State>& kept = (*recorded_)[e];
  std::vector<State> out;
  for (const State& s : kept)
    if (s.t <= last_.t) out.push_back(s);
  return out;
}

std::vector<double> RunMonitor::values() const {
  std::vector<double> out;
  const double duration = last_.t - t_start_;
  for (std::size_t i = 0; i < spec_.summaries.size(); ++i) {
    const Track& t = tracks_[summary_index_[i]];
    for (const Reduction r : spec_.summaries[i].reductions) switch (r) {
        case Reduction::min: out.push_back(t.min); break;
        case Reduction::max: out.push_back(t.max); break;
        case Reduction::mean: out.push_back(duration > 0.0 ? t.integral / duration : t.final); break;
        case Reduction::final: out.push_back(t.final); break;
        case Reduction::t_min: out.push_back(t.t_min); break;
        case Reduction::t_max: out.push_back(t.t_max); break;
      }
  }
  for (const Occurrences& o : events_) {
    out.push_back(static_cast<double>(o.count));
    out.push_back(o.count ? o.t_first : kNaN);
    out.push_back(o.count ? o.t_last : kNaN);
    for (std::size_t i = 0; i < spec_.summaries.size(); ++i) out.push_back(o.count ? o.at_first[i] : kNaN);
  }
  return out;
}

}  // namespace spinfold
