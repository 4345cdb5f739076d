// Work-precision measurement (issue 24): run time per unit simulated time against the error at T,
// for any scene. Shared by `spinfold work-precision` (any scene) and `spinfold-bench work-precision`
// (the bench scenes, with Boost.Odeint beside ours): the reference, the sweeps, the cost at a target
// error, the recommendation and the plot (cairo, render/curves_plot.h; a gnuplot script as an export).
//
// The error is chart-free: the engine's state at T and the reference's are compared by the oracle's
// `compare` (oracle/oracle.h) in the oracle's start frame, whatever chart each run ended in.
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/chaos_indicators.h"
#include "engine/scene.h"
#include "engine/state.h"
#include "render/figure_page.h"

namespace spinfold::work_precision {

inline constexpr double kNotReached = std::numeric_limits<double>::infinity();

// What CSV headers and summaries say "state_error" and "energy_error" mean.
inline constexpr const char* kErrorMeaning =
    "state_error = max(geodesic distance of the positions [length], |dV| tangential [length/time], "
    "max_A |de_A| / max_A |e_A|) at T against the reference; energy_error = |H(T) - H(0)| / "
    "(kinetic + |potential| energy at the start)";

// One measured run.
struct Point {
  std::string method;
  std::string parameter;  // "dt", "tol" or "-" (exact)
  double value = 0.0;
  double seconds_per_unit_time = 0.0;  // best wall time of repeated runs / T
  double state_error = kNotReached;    // see kErrorMeaning; infinity when the run stopped
  double energy_error = kNotReached;
  long steps = 0;  // accepted steps (ours) or right-hand-side evaluations (Odeint)
  // The parts of state_error (its largest): the position, velocity and frame errors (kErrorParts).
  double position_error = kNotReached, velocity_error = kNotReached, frame_error = kNotReached;
};

struct Errors {
  double state = kNotReached;
  double energy = kNotReached;
  double position = kNotReached, velocity = kNotReached, frame = kNotReached;  // state = their max
};

// What the CSV's and the API's position, velocity and frame errors are.
inline constexpr const char* kErrorParts =
    "position_error, velocity_error, frame_error: the three parts of state_error (where the oracle runs: "
    "the geodesic distance [length], |dV| tangential [length/time], max_A |de_A| / max_A |e_A|; elsewhere "
    "the largest component difference of X, of V and of e_A, each relative to max(1, |v|))";

// The most accurate solution at T available for the scene: the extended-precision oracle where it
// runs, else the closed form where the engine has one, else gauss6 at period/4096 cross-checked by
// dop853 at 1e-15. Its `errors` measure any engine state at T (in any chart) against it.
struct Reference {
  std::string kind;         // "oracle", "closed form" or "gauss6"
  std::string description;  // what was run, and its own agreement check
  std::function<Errors(const State&)> errors;
};
Reference make_reference(const Scene& scene, double t_end);

// The characteristic (orbital) period of a scene's motion [time]: 2πmR²/√|MᵀηM| without a radial
// potential; 2π/√Λ, Λ = 2KE/m + K²s²/m², with one (physics.md §8.2). Infinity where the motion
// has none (a body at rest, a free body on the plane).
double characteristic_period(const Scene& scene);

// The horizon when none is given: this many characteristic periods (time units where the motion
// has none), long enough for the errors to build up but short enough to sweep in seconds.
inline constexpr double kDefaultPeriods = 20.0;
double default_t_end(const Scene& scene);

// The horizon the sweep measures errors over, and why (issue 35): on a chaotic scene an error grows
// like e^{λt}, so past the predictable horizon ln(target / kRoundingFloor)/λ every method's error at T
// is the chaos's, not the integrator's, and a recommendation from it would name noise. The scene is
// chaotic when, over max(T, kChaosProbe), its MEGNO mean exceeds kChaoticMegno (2 for quasi-periodic
// motion, 2k for growth like t^k, λt/2 for chaos; engine/chaos_indicators.h). The note says the
// verdict in every case; where T is beyond the horizon (`beyond`) nothing is worth measuring.
inline constexpr double kChaosProbe = 200.0;  // [time]
inline constexpr double kChaoticMegno = 8.0;  // [1]
// The error the tightest double runs make over the first unit of time (dop853 at 1e-15 against the
// oracle), from which the chaos grows it [1].
inline constexpr double kRoundingFloor = 1e-13;
struct Horizon {
  double t_end = 0.0;      // what the sweep uses [time]
  bool shortened = false;  // t_end is the predictable horizon, shorter than asked or the default
  bool beyond = false;     // T was given (--t-end) and lies beyond the predictable horizon
  ChaosIndicators chaos;   // over the probe
  bool chaotic = false;
  double predictable = kNotReached;  // ln(target / kRoundingFloor)/λ where chaotic [time]
  std::string note;                  // the verdict, one sentence for the summary
};
// `asked`: --t-end, or nullopt for default_t_end. The probe spends at most `max_attempts` steps.
Horizon choose_horizon(const Scene& scene, std::optional<double> asked, double target_error,
                       std::uint64_t max_attempts = 20'000'000);

struct SweepOptions {
  double t_end = 1.0;
  std::vector<std::string> integrators;  // catalog names and/or "auto"; empty: every catalog entry
  bool include_auto = true;              // with an empty list: also `auto` at the scene's tolerance
  double max_seconds_per_run = 1.0;      // stop refining a method once one run takes longer
  std::uint64_t max_attempts_per_run = 20'000'000;  // a run past this is "not reached"
  // Asked before each run with the methods finished so far and the methods to sweep (progress);
  // false stops the sweep there, and it returns the curves measured until then (a cancel).
  std::function<bool(std::size_t methods_done, std::size_t methods)> proceed{};
};

// Times `run` (repeated, best of up to 5 within 0.2 s) and measures its final state.
Point measure(const Reference& reference, double t_end, const std::string& method,
              const std::string& parameter, double value, const std::function<State(long& steps)>& run);

// Sweeps each integrator: adaptive ones over tol = 1e-3 … 1e-15, fixed-step ones over
// dt = period/8 … period/65536 (until the error is below 1e-13 or a run exceeds the time limit),
// `exact` once where the scene has a closed form, `auto` once. `on_point` sees each point as it is
// measured. Returns the curves by method, each from coarse to fine.
using Curves = std::map<std::string, std::vector<Point>>;
Curves sweep(const Scene& scene, const Reference& reference, const SweepOptions& options,
             const std::function<void(const Point&)>& on_point = {});

// Integrators of the catalog that a scene cannot run here, with the reason (exact without a
// closed form); the sweep leaves them out.
std::map<std::string, std::string> skipped_integrators(const Scene& scene, const SweepOptions& options);

// Cost at the target error, interpolated log-log along the curve; kNotReached when it never gets there.
double cost_at(const std::vector<Point>& curve, double target_error);
// Microseconds with 3 significant digits, or "not reached".
std::string format_cost(double seconds_per_unit_time);
// A number as written in the CSV and summaries (6 significant digits).
std::string format_number(double value);

// The setting `recommendation` names first: auto at the scene's tolerance when it reaches the target
// at no more than 1.25× the cost of the cheapest stepping setting that does (auto keeps choosing
// well after later changes), else that stepping setting (a catalog integrator with its tol or dt).
// nullopt when neither reached it. Never `exact` alone: auto picks it where it holds.
std::optional<Point> recommended_setting(const Curves& curves, double target_error);

// "picks <integrator>": what `auto` resolves to on the scene, for `recommendation`.
std::string auto_picks(const Scene& scene);

// One line: the recommended setting (recommended_setting) with its cost and error, and how the
// others compare (the cheapest stepping setting, exact, auto), or that none reached it and which came
// closest.
std::string recommendation(const Curves& curves, double target_error, double t_end,
                           const std::string& auto_picks);

// recommendation() over the horizon chosen: none where T lies beyond a chaotic scene's predictable
// horizon (every error there is the chaos's), with the reason.
std::string recommendation(const Curves& curves, double target_error, const Horizon& horizon,
                           const std::string& auto_picks);

// The CSV of the curves: `comments` ("# ..." lines, each ending in a newline) then kCsvColumns and
// one row per point (numbers as format_number writes them).
inline constexpr const char* kCsvColumns =
    "method,parameter,value,seconds_per_unit_time,state_error,energy_error,steps,position_error,velocity_"
    "error,"
    "frame_error";
std::string csv(const std::string& comments, const Curves& curves);

// The markdown table of the curves' points (method, setting, cost, errors, steps).
std::string points_table(const Curves& curves);

// The picture's size: the default is a page of its own (the CLI's files); a plot shown scaled down
// in a narrow column (the browser UI's) wants a narrower page, so larger letters, the legend below.
struct PlotLayout {
  double width = 540, plot_height = 330;  // of the page and of its plotting area [pt]
  double pixels_per_point = 2.0;          // the PNG's resolution (144 dpi)
  bool key_below = false;                 // the legend under the plot rather than to its right
};

// The plot (state error against wall time per unit simulated time, both logarithmic; one line per
// method, the runs that stopped left out; methods outside the catalog dashed) as a figure page whose
// metadata is `provenance` (codec/provenance.h's JSON: the PNG's Source chunk, the SVG's <metadata>);
// std::invalid_argument("no run finished: nothing to plot") when no run has a point to draw.
render::FigurePage plot_page(const std::string& title, const std::string& provenance, const Curves& curves,
                             double t_end, const PlotLayout& layout = {});

// Writes <stem>.svg and <stem>.png (plot_page, drawn by cairo in-process) and <stem>.gp in `dir`: a
// gnuplot script with the data inline and the provenance as comment lines, an export for whoever
// re-plots in gnuplot (never run here). Returns "" or why no image was drawn (no run finished, a file
// that cannot be written).
std::string write_plot(const std::filesystem::path& dir, const std::string& stem, const std::string& title,
                       const std::string& provenance, const Curves& curves, double t_end,
                       const PlotLayout& layout = {});

}  // namespace spinfold::work_precision
