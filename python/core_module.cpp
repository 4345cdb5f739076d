// spinfold._core: the engine, the codec and the renderer for Python (pybind11). The public API is
// python/spinfold/__init__.py, which turns what this module returns into NumPy arrays, mappings and
// frames. Runs release the GIL; each run takes the one sampling loop (engine/sampling.h), so its
// numbers are `spinfold simulate`'s to the bit.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "codec/json_text.h"
#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "engine/chaos_indicators.h"
#include "engine/integrator.h"
#include "engine/number_rule.h"
#include "engine/readout.h"
#include "engine/run_limits.h"
#include "engine/sampling.h"
#include "engine/simulation.h"
#include "engine/sliced_advance.h"
#include "engine/timeline.h"
#include "render/png_encoder.h"
#include "render/renderer.h"
#include "render/scene_builder.h"
#include "render/snapshot.h"
#include "render/view.h"
#include "render/view_parameters.h"

namespace py = pybind11;
using namespace spinfold;

namespace spinfold::python {
void add_sweep(py::module_& m);  // python/sweep_module.cpp
}

namespace {

// A scene from JSON text, or ValueError naming every field that is wrong.
Scene scene_of(const std::string& text) {
  const SceneParse parsed = parse_scene_text(text);
  if (!parsed.errors.empty()) throw py::value_error("scene: " + describe_errors(parsed.errors));
  return *parsed.scene;
}

// A run limit (engine/run_limits.h): ValueError in its row's words, as the CLI's --NAME refusal.
void check_limit(std::string_view name, double value) {
  const RunLimit& limit = run_limit(name);
  if (!allows(limit.rule, value)) throw py::value_error(refused(name, must_be(limit.rule), shortest(value)));
}

void check_times(double t_end, double every) {
  check_limit("t_end", t_end);
  check_limit("every", every);
  if (const auto why = samples_refusal(t_end, every)) throw py::value_error("every: " + *why);
}

std::optional<std::uint64_t> max_steps_of(std::optional<double> max_steps) {
  if (!max_steps) return std::nullopt;
  check_limit("max_steps", *max_steps);
  return static_cast<std::uint64_t>(*max_steps);
}

// A Python value as JSON, for a scene override or patch: numbers as numbers (NaN and infinities
// kept, for the scene's validation to refuse in its words, as the CLI's --dt nan is), text, None,
// True/False, lists (a NumPy array or scalar as its list or number) and mappings; TypeError naming
// `path` otherwise.
nlohmann::json json_of(const py::handle& value, const std::string& path) {
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    int overflow = 0;
    const long long n = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow == 0) return n;
    double x = PyLong_AsDouble(value.ptr());  // beyond 64 bits: as a double (1e300; inf beyond)
    if (x == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      x = overflow > 0 ? HUGE_VAL : -HUGE_VAL;
    }
    return x;
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  const py::module_ numpy = py::module_::import("numpy");
  if (py::isinstance(value, numpy.attr("ndarray")) || py::isinstance(value, numpy.attr("generic")))
    return json_of(value.attr("tolist")(), path);
  if (py::isinstance<py::dict>(value) || py::hasattr(value, "keys")) {
    nlohmann::json object = nlohmann::json::object();
    for (const py::handle key : value.attr("keys")()) {
      if (!py::isinstance<py::str>(key))
        throw py::type_error((path.empty() ? std::string("changes") : path) + ": keys must be text (got " +
                             py::repr(key).cast<std::string>() + ")");
      const std::string k = key.cast<std::string>();
      object[k] = json_of(value[key], path.empty() ? k : path + "." + k);
    }
    return object;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    nlohmann::json array = nlohmann::json::array();
    for (const py::handle item : value) array.push_back(json_of(item, path));
    return array;
  }
  throw py::type_error((path.empty() ? std::string("value") : path) +
                       ": must be a number, text, a list or a mapping (got " +
                       value.get_type().attr("__name__").cast<std::string>() + ")");
}

// The scene text with overrides (dotted path -> value) merged in and checked as the CLI's --dt,
// --integrator and sweep's --set are: the scene's validation names each refused field.
std::string apply_overrides(const std::string& text,
                            const std::vector<std::pair<std::string, py::object>>& overrides) {
  nlohmann::json document = parse_json_text(text);
  nlohmann::json patch = nlohmann::json::object();
  for (const auto& [path, value] : overrides) {
    nlohmann::json* node = &patch;
    std::string_view rest = path;
    for (std::size_t dot; (dot = rest.find('.')) != std::string_view::npos; rest.remove_prefix(dot + 1)) {
      nlohmann::json& next = (*node)[std::string(rest.substr(0, dot))];
      if (!next.is_object()) next = nlohmann::json::object();
      node = &next;
    }
    (*node)[std::string(rest)] = json_of(value, path);
  }
  merge_scene_patch(document, patch);
  const SceneParse parsed = parse_scene(document);
  if (!parsed.errors.empty()) throw py::value_error(describe_errors(parsed.errors));
  return document.dump();
}

// A value as a refusal shows it: a number as the shortest decimal, a text quoted.
std::string shown(const render::GivenValue& value) {
  return std::holds_alternative<double>(value) ? shortest(std::get<double>(value))
                                               : "'" + std::get<std::string>(value) + "'";
}

// Sets the view parameter `name` in `request`: nullopt, or why the value is refused (the table's
// words: render::set_parameter); an unknown name is refused too.
std::optional<std::string> view_refusal_of(const std::string& name, const render::GivenValue& value,
                                           render::ViewRequest& request) {
  for (const render::ViewParameter& p : render::view_parameters())
    if (p.name == name) return render::set_parameter(request, p, value);
  return "is not a view parameter";
}

// One body's samples as columns, filled without the GIL (reserved up front: no regrowth).
struct BodyColumns {
  std::string label;                 // companions: their label
  std::vector<double> values;        // rows × sample_value_names().size(), row-major
  std::vector<std::uint8_t> status;  // index into status_names
  std::vector<std::string> status_names;
  std::vector<std::uint64_t> steps;
  std::vector<double> event_t;
  std::vector<std::int64_t> event_row;
  // The distinct sets of undefined values and each row's set (most rows share one).
  std::vector<std::vector<std::pair<std::string, std::string>>> undefined_sets;
  std::vector<std::int32_t> undefined_row;
  std::string integrator, status_detail;

  void reserve(std::size_t rows) {
    values.reserve(rows * sample_value_names().size());
    status.reserve(rows);
    steps.reserve(rows);
    undefined_row.reserve(rows);
  }

  void append(const Simulation& run, double events_since) {
    const Readout r = readout(run);
    const std::size_t width = sample_value_names().size();
    const std::size_t row = status.size();
    values.resize(values.size() + width);
    sample_values(r, std::span<double>(values.data() + row * width, width));
    const auto code = static_cast<std::size_t>(
        std::find(status_names.begin(), status_names.end(), r.status_name) - status_names.begin());
    if (code == status_names.size()) status_names.emplace_back(r.status_name);
    status.push_back(static_cast<std::uint8_t>(code));
    steps.push_back(r.steps);
    for (const DegenerateEvent& e : events_after(run, events_since)) {
      event_t.push_back(e.t);
      event_row.push_back(static_cast<std::int64_t>(row));
    }
    if (!same_as_last_undefined(r)) undefined_sets.push_back(undefined_values(r));
    undefined_row.push_back(static_cast<std::int32_t>(undefined_sets.size() - 1));
    integrator = r.integrator;
    status_detail = r.status_detail;
  }

 private:
  // Whether the read-out's undefined values are the last set's, compared without building strings.
  bool same_as_last_undefined(const Readout& r) const {
    if (undefined_sets.empty()) return false;
    const auto& last = undefined_sets.back();
    std::size_t i = 0;
    bool same = true;
    for_each_undefined(r, [&](std::string_view prefix, std::string_view field, std::string_view reason) {
      if (!same || i >= last.size()) {
        same = false;
        return;
      }
      const std::string& name = last[i].first;
      same = name.size() == prefix.size() + field.size() && name.starts_with(prefix) &&
             std::string_view(name).substr(prefix.size()) == field && last[i].second == reason;
      ++i;
    });
    return same && i == last.size();
  }
};

struct RunColumns {
  BodyColumns main;
  std::vector<BodyColumns> companions;
  bool budget_left = true;                              // false: max_steps ran out before t_end
  std::vector<std::pair<std::string, double>> summary;  // the summaries' and events' values (run_summary.h)
  std::vector<BodyColumns> crossings;  // each recording event's crossings (EventSpec::record), label its name

  void append(const Simulation& run, double events_since) {
    main.append(run, events_since);
    companions.resize(run.companions.size());
    for (std::size_t i = 0; i < run.companions.size(); ++i) {
      companions[i].label = companion_label(run.scene, i);
      companions[i].append(run.companions[i], events_since);
    }
  }
};

// Python's Ctrl-C while a run goes on with the GIL released: the signal handler only sets a flag,
// which a thread holding the GIL reads. check() takes the GIL for that moment at most every 50 ms and
// raises KeyboardInterrupt (py::error_already_set) when it was pressed. The main thread's only: other
// threads never see a signal.
class Interrupts {
 public:
  void check() {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(50)) return;
    last_ = now;
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// `spinfold simulate`'s run: samples at 0, every, 2·every, … and t_end (engine/sampling.h), in slices
// of step attempts with `interrupts` looked at between them (the numbers do not depend on where a
// run was stopped).
RunColumns run_columns(const Scene& scene, double t_end, double every, std::optional<std::uint64_t> max_steps,
                       const MonitorSpec& monitor = {}, Interrupts* interrupts = nullptr,
                       std::optional<double> chaos_interval = std::nullopt) {
  RunColumns out;
  out.main.reserve(static_cast<std::size_t>(std::ceil(t_end / every)) + 2);
  Simulation run = start_simulation(scene);
  if (!monitor.empty()) watch(run, monitor);
  double since = -1.0;
  std::uint64_t attempts = max_steps.value_or(kNoStepLimit);
  constexpr std::uint64_t kSlice = 4096;
  sample_run(
      run, t_end, every,
      [&](double t) {
        if (!interrupts)
          return out.budget_left = max_steps ? advance_within(run, t, attempts) : advance_to(run, t);
        const Advanced got = advance_in_slices(
            run, t, attempts,
            [&] {
              interrupts->check();
              return true;
            },
            kSlice);
        return out.budget_left = got == Advanced::reached;
      },
      [&] {
        out.append(run, since);
        since = run.state.t;
      });
  const std::vector<std::string> names = monitor_columns(monitor);
  const std::vector<double> values = monitor_values(run);
  for (std::size_t i = 0; i < names.size(); ++i) out.summary.emplace_back(names[i], values[i]);
  if (run.monitor) {  // the crossings recorded, each read as a sample is (the main body's columns)
    const State end = run.state;
    for (std::size_t e = 0; e < monitor.events.size(); ++e) {
      if (monitor.events[e].record == 0) continue;
      BodyColumns& c = out.crossings.emplace_back();
      c.label = monitor.events[e].name;
      for (const State& at : run.monitor->recorded(e)) {
        run.state = at;
        c.append(run, std::numeric_limits<double>::infinity());
      }
    }
    run.state = end;
  }
  if (chaos_interval) {  // `spinfold simulate --chaos`: its own two runs, to where this one ended
    // Within what is left of max_steps, Ctrl-C looked at between slices of step attempts.
    ChaosMonitor indicators(scene, *chaos_interval, run.start_time);
    indicators.advance_to(run.state.t, attempts, [&] {
      if (interrupts) interrupts->check();
      return true;
    });
    const ChaosIndicators got = indicators.indicators();
    if (got.out_of_steps) out.budget_left = false;
    const std::array<double, 5> c = chaos_values(got);
    for (std::size_t i = 0; i < c.size(); ++i)
      out.summary.emplace_back(std::string(kChaosColumns[i]), std::isfinite(c[i]) ? c[i] : NAN);
  }
  return out;
}

// chaos_interval (Python's chaos=True): the CLI's --chaos-interval rule, ValueError naming it.
std::optional<double> chaos_of(std::optional<double> interval, double t_end) {
  if (!interval) return std::nullopt;
  if (const auto why = chaos_interval_refusal(*interval, t_end))
    throw py::value_error("chaos_interval: " + *why);
  return interval;
}

// The summaries and events as Python names them (ValueError "summaries: …" / "events: …"), checked
// against each scene ("scenes[i]: " before it where there are several).
MonitorSpec monitor_spec(const std::vector<std::string>& summaries, const std::vector<std::string>& events,
                         const std::vector<const Scene*>& scenes) {
  const auto named = [](const MonitorRefusal& e) {
    return std::string(e.event ? "events: " : "summaries: ") + e.what();
  };
  MonitorSpec spec;
  try {
    spec = parse_monitor(summaries, events);
  } catch (const MonitorRefusal& e) {
    throw py::value_error(named(e));
  }
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    try {
      check_monitor(spec, *scenes[i]);
    } catch (const MonitorRefusal& e) {
      throw py::value_error((scenes.size() > 1 ? "scenes[" + std::to_string(i) + "]: " : std::string()) +
                            named(e));
    }
  }
  return spec;
}

// A vector handed to NumPy without a copy: the array owns it through a capsule.
template <typename T>
py::array_t<T> owned_array(std::vector<T>&& data, std::vector<py::ssize_t> shape) {
  auto* held = new std::vector<T>(std::move(data));
  py::capsule owner(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, held->data(), owner);
}

py::dict body_dict(BodyColumns&& b) {
  const auto width = static_cast<py::ssize_t>(sample_value_names().size());
  const auto rows = static_cast<py::ssize_t>(b.status.size());
  const auto events = static_cast<py::ssize_t>(b.event_t.size());
  py::list undefined_sets;
  for (const auto& set : b.undefined_sets) {
    py::dict reasons;
    for (const auto& [field, reason] : set) reasons[py::str(field)] = reason;
    undefined_sets.append(reasons);
  }
  py::dict d;
  d["label"] = b.label;
  d["values"] = owned_array(std::move(b.values), {rows, width});
  d["status_codes"] = owned_array(std::move(b.status), {rows});
  d["status_names"] = b.status_names;
  d["steps"] = owned_array(std::move(b.steps), {rows});
  d["event_t"] = owned_array(std::move(b.event_t), {events});
  d["event_row"] = owned_array(std::move(b.event_row), {events});
  d["undefined_sets"] = undefined_sets;
  d["undefined_row"] = owned_array(std::move(b.undefined_row), {rows});
  d["integrator"] = b.integrator;
  d["status_detail"] = b.status_detail;
  return d;
}

py::dict run_dict(RunColumns&& run, const Scene& scene, const std::string& command) {
  py::dict d = body_dict(std::move(run.main));
  py::list companions;
  for (BodyColumns& c : run.companions) companions.append(body_dict(std::move(c)));
  d["companions"] = companions;
  py::list crossings;
  for (BodyColumns& c : run.crossings) crossings.append(body_dict(std::move(c)));
  d["crossings"] = crossings;
  d["budget_left"] = run.budget_left;
  py::dict summary;
  for (const auto& [name, value] : run.summary) summary[py::str(name)] = value;
  d["summary"] = summary;
  d["provenance"] = provenance_json(scene, command).dump();
  return d;
}

py::dict simulate(const std::string& scene_text, double t_end, double every,
                  std::optional<double> max_steps_given, const std::string& command,
                  const std::vector<std::string>& summaries, const std::vector<std::string>& events,
                  std::optional<double> chaos_interval) {
  check_times(t_end, every);
  const std::optional<std::uint64_t> max_steps = max_steps_of(max_steps_given);
  const Scene scene = scene_of(scene_text);
  const MonitorSpec monitor = monitor_spec(summaries, events, {&scene});
  const std::optional<double> chaos = chaos_of(chaos_interval, t_end);
  RunColumns columns;
  {
    py::gil_scoped_release release;
    Interrupts interrupts;
    columns = run_columns(scene, t_end, every, max_steps, monitor, &interrupts, chaos);
  }
  return run_dict(std::move(columns), scene, command);
}

// The seconds simulate() spends in C++ for the scene (the run, its read-outs and columns), without
// making Python objects: bench/python_bench.py's yardstick of the binding's overhead.
double engine_seconds(const std::string& scene_text, double t_end, double every,
                      const std::string& integrator) {
  check_times(t_end, every);
  nlohmann::json document = parse_json_text(scene_text);
  if (!integrator.empty()) document["integrator"]["name"] = integrator;
  const Scene scene = scene_of(document.dump());
  py::gil_scoped_release release;
  const auto start = std::chrono::steady_clock::now();
  const RunColumns columns = run_columns(scene, t_end, every, std::nullopt);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Many runs on `threads` C++ threads (0: one per core), the GIL released; results in input order.
py::list run_many(const std::vector<std::string>& scene_texts, double t_end, double every,
                  std::optional<double> threads_given, const std::string& command,
                  const std::vector<std::string>& summaries, const std::vector<std::string>& events,
                  std::optional<double> chaos_interval) {
  check_times(t_end, every);
  if (threads_given) check_limit("threads", *threads_given);
  const std::optional<double> chaos = chaos_of(chaos_interval, t_end);
  const unsigned threads = threads_given ? static_cast<unsigned>(*threads_given) : 0u;
  std::vector<Scene> scenes;
  for (std::size_t i = 0; i < scene_texts.size(); ++i) {
    const SceneParse parsed = parse_scene_text(scene_texts[i]);
    if (!parsed.errors.empty())
      throw py::value_error("scenes[" + std::to_string(i) + "]: " + describe_errors(parsed.errors));
    scenes.push_back(*parsed.scene);
  }
  std::vector<const Scene*> each;
  for (const Scene& scene : scenes) each.push_back(&scene);
  const MonitorSpec monitor = monitor_spec(summaries, events, each);
  std::vector<RunColumns> results(scenes.size());
  {
    py::gil_scoped_release release;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t workers = std::min<std::size_t>(scenes.size(), threads == 0 ? cores : threads);
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t i; (i = next++) < scenes.size();)
        results[i] = run_columns(scenes[i], t_end, every, std::nullopt, monitor, nullptr, chaos);
    };
    std::vector<std::thread> pool;
    for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
  }
  py::list out;
  for (std::size_t i = 0; i < results.size(); ++i)
    out.append(run_dict(std::move(results[i]), scenes[i], command));
  return out;
}

// A run steered step by step: the parameters at t = 0 and the changes since, as a server session
// keeps them, so that its trajectory can be replayed.
class PySimulation {
 public:
  explicit PySimulation(const std::string& scene_text) : base_(scene_of(scene_text)) {
    run_ = start_simulation(base_);
  }

  bool advance(double until, std::optional<double> max_steps_given) {
    if (!std::isfinite(until) || until < run_.state.t)
      throw py::value_error("until: must be a finite time not before the run's t = " +
                            shortest(run_.state.t) + " (got " + shortest(until) + ")");
    const std::optional<std::uint64_t> max_steps = max_steps_of(max_steps_given);
    py::gil_scoped_release release;
    return advance_to(run_, until, max_steps.value_or(kNoStepLimit));
  }

  // The sample now, with the events since the previous sample() (JSON text: sample_to_json).
  std::string sample() {
    const std::string text = sample_to_json(run_, since_).dump();
    since_ = run_.state.t;
    return text;
  }
  std::string state() const { return sample_to_json(run_, run_.state.t).dump(); }
  std::string scene() const { return scene_to_json(run_.scene).dump(); }
  std::string initial_scene() const { return scene_to_json(base_).dump(); }
  double t() const { return run_.state.t; }

  // A JSON merge patch of the scene in force: continues the run (retune) where the server's session
  // would, else starts over at t = 0. Returns (kind, reason); kind is continued, restarted or
  // unchanged. A refused patch raises ValueError and changes nothing.
  std::pair<std::string, std::string> patch(const py::object& changes) {
    nlohmann::json patch;
    if (py::isinstance<py::str>(changes)) {  // JSON text
      try {
        patch = parse_json_text(changes.cast<std::string>());
      } catch (const JsonTextError& e) {
        throw py::value_error("changes" + (e.field.empty() ? std::string() : "." + e.field) + ": " +
                              e.what());
      }
    } else {
      patch = json_of(changes, "");  // NaN kept for the validation to name the field
    }
    if (!patch.is_object())
      throw py::type_error("changes: must be a mapping (a JSON merge patch of the scene)");
    nlohmann::json document = scene_to_json(run_.scene);
    nlohmann::json merged = document;
    merge_scene_patch(merged, patch);
    const SceneParse parsed = parse_scene(merged);
    if (!parsed.errors.empty()) throw py::value_error("changes: " + describe_errors(parsed.errors));
    if (scene_to_json(*parsed.scene) == document) return {"unchanged", "the patch changes nothing"};
    if (std::string why = restart_reason(patch, run_.scene, *parsed.scene); !why.empty()) {
      start_over(*parsed.scene);
      return {"restarted", why};
    }
    if (run_.state.t == 0.0 && changes_.empty()) {
      start_over(*parsed.scene);
      return {"continued", continued_reason(0.0)};
    }
    retune(run_, *parsed.scene);
    changes_.push_back({run_.state.t, *parsed.scene});
    return {"continued", continued_reason(run_.state.t)};
  }

  // Back to t = 0 with the parameters in force (as the server's reset).
  void reset() { start_over(run_.scene); }

  // The samples at 0, every, … up to the run's time, replayed from the changes (engine/timeline.h).
  py::dict trajectory(double every) {
    check_times(run_.state.t, every);
    RunColumns columns;
    {
      py::gil_scoped_release release;
      double since = -1.0;
      replay_sampled(base_, changes_, run_.state.t, every, [&](const Simulation& run) {
        columns.append(run, since);
        since = run.state.t;
      });
    }
    return run_dict(std::move(columns), run_.scene, "");
  }

 private:
  void start_over(const Scene& scene) {
    base_ = scene;
    changes_.clear();
    run_ = start_simulation(base_);
    since_ = -1.0;
  }
  Scene base_;
  std::vector<ParameterChange> changes_;
  Simulation run_;
  double since_ = -1.0;
};

// The still `spinfold render` draws, as RGBA rows top-down, on this thread's GL context. `given`:
// the view parameters given (name -> a number or a text), each checked by its row of the view
// table (render/view_parameters.h) in the CLI's words; the request resolved by the one resolver.
py::dict render_still(const std::string& scene_text, double t,
                      const std::vector<std::pair<std::string, render::GivenValue>>& given,
                      const std::string& command) {
  check_limit("t", t);
  render::ViewRequest request;
  for (const auto& [name, value] : given) {
    if (const auto why = view_refusal_of(name, value, request))
      throw py::value_error(refused(name, *why, shown(value)));
  }
  const Scene scene = scene_of(scene_text);
  render::ViewOptions view;
  try {
    view = render::view_options(request, scene.surface);
  } catch (const render::ViewRefused& e) {
    throw py::value_error(refused(e.parameter, e.what(), "'" + e.value + "'"));
  }
  render::Image image;
  std::string status;
  {
    py::gil_scoped_release release;
    Simulation run;
    const render::Snapshot snapshot =
        render::snapshot_at(scene, t, request.layers & render::kTrail, request.trail, run);
    render::place_camera(view, request, snapshot);
    thread_local render::Renderer renderer;  // one GL context per thread, made at its first frame
    image = renderer.render_image(snapshot, view);
    status = status_name(run.state.status);
  }
  py::dict d;
  d["rgba"] = py::bytes(reinterpret_cast<const char*>(image.rgba.data()), image.rgba.size());
  d["width"] = image.width;
  d["height"] = image.height;
  d["status"] = status;
  py::list texts;
  for (const auto& [key, text] : picture_texts(scene, command, t, render::view_name(view.kind)))
    texts.append(py::make_tuple(key, text));
  d["texts"] = texts;
  return d;
}

py::bytes png_bytes(const py::bytes& rgba, int width, int height,
                    const std::vector<std::pair<std::string, std::string>>& texts) {
  const std::string_view pixels = rgba;
  if (width <= 0 || height <= 0 || pixels.size() != static_cast<std::size_t>(width) * height * 4)
    throw py::value_error("rgba: must hold width × height × 4 bytes");
  const auto png =
      render::encode_png(reinterpret_cast<const std::uint8_t*>(pixels.data()), width, height, texts);
  return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
}

std::string merge_patch(const std::string& document_text, const std::string& patch_text) {
  nlohmann::json document = parse_json_text(document_text);
  merge_scene_patch(document, parse_json_text(patch_text));
  return document.dump();
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "Spinfold's engine, codec and renderer (use the `spinfold` package, not this module)";
  m.def("version", [] { return std::string(build_version()); });
  m.def("commit", [] { return std::string(build_commit()); });
  m.def("value_names", [] {
    const auto names = sample_value_names();
    return std::vector<std::string>(names.begin(), names.end());
  });
  m.def("presets", [] {
    std::vector<std::tuple<std::string, std::string, std::string>> out;
    for (const PresetSource& p : preset_sources()) {
      const SceneParse parsed = parse_scene_text(p.json);
      out.emplace_back(std::string(p.name), parsed.scene ? parsed.scene->description : "",
                       std::string(p.json));
    }
    return out;
  });
  m.def("default_preset", [] { return std::string(kDefaultPreset); });
  m.def("integrators", [] {
    py::list out;
    for (const CatalogEntry& e : integrator_catalog()) {
      py::dict d;
      d["name"] = std::string(e.info.name);
      d["order"] = e.info.order;
      d["symplectic"] = e.info.symplectic;
      d["adaptive"] = e.info.adaptive;
      d["exact"] = e.info.exact;
      d["summary"] = std::string(e.info.summary);
      out.append(d);
    }
    return out;
  });
  m.def("canonical_scene", [](const std::string& text) { return scene_to_json(scene_of(text)).dump(); });
  m.def("scene_hash", [](const std::string& text) { return scene_hash(scene_of(text)); });
  m.def("merge_patch", &merge_patch);
  m.def("simulate", &simulate, py::arg("scene"), py::arg("t_end"), py::arg("every"), py::arg("max_steps"),
        py::arg("command"), py::arg("summaries") = std::vector<std::string>{},
        py::arg("events") = std::vector<std::string>{}, py::arg("chaos_interval") = std::nullopt);
  m.def("run_many", &run_many, py::arg("scenes"), py::arg("t_end"), py::arg("every"), py::arg("threads"),
        py::arg("command"), py::arg("summaries") = std::vector<std::string>{},
        py::arg("events") = std::vector<std::string>{}, py::arg("chaos_interval") = std::nullopt);
  m.def("render", &render_still, py::arg("scene"), py::arg("t"), py::arg("given"), py::arg("command"));
  // The one rule of each value the front doors share, for the Python layer's checks (the reason in
  // the table's words, or None): a view parameter (render/view_parameters.h), a run limit
  // (engine/run_limits.h).
  m.def("view_refusal", [](const std::string& name, const render::GivenValue& value) {
    render::ViewRequest request;
    return view_refusal_of(name, value, request);
  });
  m.def("view_expectation",
        [](const std::string& name) { return render::expectation(render::view_parameter(name)); });
  m.def("view_parameter_names", [] {
    std::vector<std::string> names;
    for (const render::ViewParameter& p : render::view_parameters()) names.emplace_back(p.name);
    return names;
  });
  m.def("run_limit_refusal",
        [](const std::string& name, double value) { return refusal(run_limit(name).rule, value); });
  m.def("run_limit_expectation", [](const std::string& name) { return must_be(run_limit(name).rule); });
  m.def("runs_refusal", [](double runs) { return runs_refusal(runs); });
  m.def("apply_overrides", &apply_overrides);
  m.def("encode_png", &png_bytes);
  // The layers on by default, from the view-parameter table (render/view_parameters.h).
  m.def("default_layers", &render::default_layer_list);
  m.def("engine_seconds", &engine_seconds);
  python::add_sweep(m);
  py::class_<PySimulation>(m, "Simulation")
      .def(py::init<const std::string&>())
      .def("advance", &PySimulation::advance, py::arg("until"), py::arg("max_steps") = std::nullopt)
      .def("sample", &PySimulation::sample)
      .def("state", &PySimulation::state)
      .def("scene", &PySimulation::scene)
      .def("initial_scene", &PySimulation::initial_scene)
      .def("patch", &PySimulation::patch)
      .def("reset", &PySimulation::reset)
      .def("trajectory", &PySimulation::trajectory)
      .def_property_readonly("t", &PySimulation::t);
}
