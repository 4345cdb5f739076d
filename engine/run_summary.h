// What a run did, not only where it ended: reductions of scalar fields over the run's own step
// sequence, and level crossings ("events") located inside its steps as the det L = 0 events are.
// Neither depends on where the run is sampled (--every). `spinfold simulate`, `spinfold sweep` and
// Python's sweep name them in this file's words (parse_summary, parse_event), so every front door
// accepts and refuses alike.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

struct Simulation;

// The fields a summary or an event watches (monitor_field_names): r (u where the curvature varies),
// phi (continuous: it counts turns instead of wrapping at ±π; so is u on the torus, whose profile is
// a circle), lambda, mu, det_L, energy,
// energy_error, spin, speed, X.0, X.1, X.2, and K where the curvature varies. Each is the number of
// the same name in a sample, read off the same state.
std::vector<std::string> monitor_field_names(const Scene& scene);

// Reductions over the run, in the run's time [the field's unit; t_min, t_max in time]:
//   min, max   over the whole run, between steps too (a step's interior extremum is refined by
//              Brent's method on the step's own sub-steps);
//   mean       (1/T)∫ f dt over the step sequence, each step's integral that of the parabola through
//              it and the point before (error O(h³) in the step h);
//   final      the value at the run's last state;
//   t_min, t_max  when the min and the max were reached.
enum class Reduction { min, max, mean, final, t_min, t_max };
inline constexpr std::array<std::string_view, 6> kReductionNames = {"min",   "max",   "mean",
                                                                    "final", "t_min", "t_max"};

struct SummarySpec {
  std::string field;                  // a monitor_field_names() entry
  std::vector<Reduction> reductions;  // all six when the text names only the field
};

enum class Direction { up, down, any };

// A field crossing a level: up (from below to at or above), down, or either. With a period, every
// level + k·period counts (phi through multiples of 2π: level 0, period 6.283185307179586). On an
// angle (φ; u on the torus) a level is a level on the circle: the period is the angle's own (2π)
// unless the text gives one, and the wrap from π to −π is no crossing (the angle is continuous). A period
// is at least kMinRelativePeriod of |level| (parse_event refuses less) and of the field's size
// wherever the run takes it (the run stops there as event_unresolved): closer levels are not told
// apart in double. A step's crossings are counted, not visited, so any number of them costs two or
// three root finds; a run counts at most kMaxEventCount (2⁵³, exact in a double column).
struct EventSpec {
  std::string name;  // the columns' prefix; default FIELD_DIRECTION_LEVEL (r_up_1.2)
  std::string field;
  Direction direction = Direction::any;
  double level = 0.0;
  double period = 0.0;     // 0: the level only
  std::uint64_t stop = 0;  // stop the run at this occurrence (scipy's `terminal`); 0: never
  // Keep the state of each of the first `record` occurrences (a Poincaré section; 0: none), at most
  // kMaxRecordedCrossings: `record` alone in the text asks for that many.
  std::uint64_t record = 0;
};

inline constexpr std::uint64_t kMaxRecordedCrossings = 100'000;  // ~40 MB of states per event

inline constexpr double kMinRelativePeriod = 1e-12;
inline constexpr double kMaxEventCount = 9007199254740992.0;  // 2⁵³

struct MonitorSpec {
  std::vector<SummarySpec> summaries;
  std::vector<EventSpec> events;
  bool empty() const { return summaries.empty() && events.empty(); }
};

// A refusal of a summary's or an event's text, or of a field the scene has not: the message names the
// text and the reason; `event` says which option a front door names (its --event or --summary).
struct MonitorRefusal : std::invalid_argument {
  MonitorRefusal(const std::string& what, bool about_event)
      : std::invalid_argument(what), event(about_event) {}
  bool event;
};

// "r" (every reduction of r) or "r.max" (one); MonitorRefusal naming the text and the reason.
SummarySpec parse_summary(std::string_view text);
// "FIELD:DIRECTION:LEVEL[:period=P][:stop=N][:record[=N]][:name=NAME]", DIRECTION up, down or any,
// e.g. "r:up:1.2", "phi:any:0:period=6.283185307179586", "r:up:1.2:stop=3", "phi:up:0:record".
EventSpec parse_event(std::string_view text);
// Each text parsed (parse_summary, parse_event).
MonitorSpec parse_monitor(const std::vector<std::string>& summaries, const std::vector<std::string>& events);
// The fields named exist for this scene and the event names are distinct; MonitorRefusal naming the
// field, the value and the reason otherwise.
void check_monitor(const MonitorSpec& spec, const Scene& scene);

// The columns the spec adds to a row, in order: FIELD.REDUCTION for each summary, then for each
// event NAME.count, NAME.t_first, NAME.t_last and NAME.at.FIELD (the summaries' fields at the first
// occurrence).
std::vector<std::string> monitor_columns(const MonitorSpec& spec);

// The run's monitor: fed each step of the run's own sequence by engine/simulation.cpp, never the
// cut steps that reach a sample time (those are recomputed, not kept).
class RunMonitor {
 public:
  RunMonitor(MonitorSpec spec, const Simulation& run);  // the start: run.state

  // A step of the sequence from the monitor's last state to `b`. Returns the state of a terminal
  // event inside it (status event_stop) when one occurred; the monitor then ends there.
  std::optional<State> step(const Simulation& run, const State& b);

  // The columns' values (monitor_columns order); NaN where there is none (no occurrence).
  std::vector<double> values() const;
  // Event e's recorded occurrences (EventSpec::record), in time order: each the run's state at the
  // crossing, located as t_first is. Only those up to the monitor's last state: a run rewound to its
  // last good state (engine/simulation.h) drops what it recorded after it.
  std::vector<State> recorded(std::size_t e) const;
  const State& last() const { return last_; }
  bool stopped() const { return stopped_; }
  const MonitorSpec& spec() const { return spec_; }
  std::uint64_t closed_form_points = 0;  // the closed form's virtual steps fed so far

 private:
  struct Track {  // one watched field
    double min = 0, max = 0, t_min = 0, t_max = 0, integral = 0, final = 0;
  };
  struct Occurrences {
    std::uint64_t count = 0;
    double t_first = 0, t_last = 0;
    std::vector<double> at_first;  // the watched fields at the first occurrence
  };
  // The levels one step crosses: n of them, the j-th in time order level(j) (0 ≤ j < n).
  struct Crossed {
    double n = 0.0, k_first = 0.0, base = 0.0, period = 0.0;
    bool up = true, unresolved = false;
    double level(double j) const { return period > 0.0 ? base + (k_first + (up ? j : -j)) * period : base; }
    Crossed first(double count) const {  // the first `count` of them
      Crossed c = *this;
      c.n = count;
      return c;
    }
  };
  static Crossed crossings(const EventSpec& spec, double ga, double gb);
  static constexpr std::size_t kMaxFields = 13;   // monitor_field_names() at most
  using Values = std::array<double, kMaxFields>;  // the watched fields' values, in fields_ order
  Values evaluate(const Simulation& run, const State& s, const Values* near) const;
  void refine_extremum(const Simulation& run, std::size_t k, bool maximum);

  MonitorSpec spec_;
  struct Reads {  // what evaluate() computes for the watched fields
    bool energy = false, body = false, x = false, position_only = true;
  } reads_;
  std::vector<int> fields_;                        // the watched fields (indices into the field table)
  std::array<double, kMaxFields> angle_period_{};  // by field-table index: the angles' period, 0 else
  std::vector<int> summary_index_;                 // spec_.summaries[i]'s field in fields_
  std::vector<int> event_index_;                   // spec_.events[i]'s field in fields_
  std::vector<Track> tracks_;                      // per watched field
  std::vector<Occurrences> events_;                // per event
  // Per event, the recorded states: shared by the copies the run keeps to rewind to (copying them
  // every check would cost the whole record), read up to last_.t.
  std::shared_ptr<std::vector<std::vector<State>>> recorded_;
  State before_, last_;  // the last two points of the sequence (before_ valid when has_before_)
  Values before_values_{}, last_values_{};
  bool has_before_ = false, stopped_ = false;
  double t_start_ = 0.0;
};

}  // namespace spinfold
