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
#include "engine/integrator.h"
#include "engine/number_text.h"
#include "engine/readout.h"
#include "engine/sampling.h"
#include "engine/simulation.h"
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

constexpr double kMaxSamples = 1e7;  // as `spinfold simulate`

// A scene from JSON text, or ValueError naming every field that is wrong.
Scene scene_of(const std::string& text) {
  const SceneParse parsed = parse_scene_text(text);
  if (!parsed.errors.empty()) throw py::value_error("scene: " + describe_errors(parsed.errors));
  return *parsed.scene;
}

void check_times(double t_end, double every) {
  if (!std::isfinite(t_end) || t_end < 0.0)
    throw py::value_error("t_end: must be a finite number >= 0 (got " + shortest(t_end) + ")");
  if (!std::isfinite(every) || !(every > 0.0))
    throw py::value_error("every: must be a finite number > 0 (got " + shortest(every) + ")");
  if (t_end / every > kMaxSamples) throw py::value_error("every: more than 1e7 samples requested");
}

// One body's samples as columns, filled without the GIL (reserved up front: no regrowth).
struct BodyColumns {
  std::string label;           // companions: their label
  std::vector<double> values;  // rows × sample_value_names().size(), row-major
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
  bool budget_left = true;  // false: max_steps ran out before t_end

  void append(const Simulation& run, double events_since) {
    main.append(run, events_since);
    companions.resize(run.companions.size());
    for (std::size_t i = 0; i < run.companions.size(); ++i) {
      companions[i].label = companion_label(run.scene, i);
      companions[i].append(run.companions[i], events_since);
    }
  }
};

// `spinfold simulate`'s run: samples at 0, every, 2·every, … and t_end (engine/sampling.h).
RunColumns run_columns(const Scene& scene, double t_end, double every,
                       std::optional<std::uint64_t> max_steps) {
  RunColumns out;
  out.main.reserve(static_cast<std::size_t>(std::ceil(t_end / every)) + 2);
  Simulation run = start_simulation(scene);
  double since = -1.0;
  std::uint64_t attempts = max_steps.value_or(kNoStepLimit);
  sample_run(
      run, t_end, every,
      [&](double t) {
        return out.budget_left = max_steps ? advance_within(run, t, attempts) : advance_to(run, t);
      },
      [&] {
        out.append(run, since);
        since = run.state.t;
      });
  return out;
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
  d["budget_left"] = run.budget_left;
  d["provenance"] = provenance_json(scene, command).dump();
  return d;
}

py::dict simulate(const std::string& scene_text, double t_end, double every,
                  std::optional<std::uint64_t> max_steps, const std::string& command) {
  check_times(t_end, every);
  if (max_steps && *max_steps == 0) throw py::value_error("max_steps: must be at least 1");
  const Scene scene = scene_of(scene_text);
  RunColumns columns;
  {
    py::gil_scoped_release release;
    columns = run_columns(scene, t_end, every, max_steps);
  }
  return run_dict(std::move(columns), scene, command);
}

// The seconds simulate() spends in C++ for the scene (the run, its read-outs and columns), without
// making Python objects: bench/python_bench.py's yardstick of the binding's overhead.
double engine_seconds(const std::string& scene_text, double t_end, double every, const std::string& integrator) {
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
py::list run_many(const std::vector<std::string>& scene_texts, double t_end, double every, int threads,
                  const std::string& command) {
  check_times(t_end, every);
  if (threads < 0) throw py::value_error("threads: must be >= 0 (0: one per core)");
  std::vector<Scene> scenes;
  for (std::size_t i = 0; i < scene_texts.size(); ++i) {
    const SceneParse parsed = parse_scene_text(scene_texts[i]);
    if (!parsed.errors.empty())
      throw py::value_error("scenes[" + std::to_string(i) + "]: " + describe_errors(parsed.errors));
    scenes.push_back(*parsed.scene);
  }
  std::vector<RunColumns> results(scenes.size());
  {
    py::gil_scoped_release release;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t workers =
        std::min<std::size_t>(scenes.size(), threads == 0 ? cores : static_cast<unsigned>(threads));
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t i; (i = next++) < scenes.size();)
        results[i] = run_columns(scenes[i], t_end, every, std::nullopt);
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

  bool advance(double until, std::optional<std::uint64_t> max_steps) {
    if (!std::isfinite(until) || until < run_.state.t)
      throw py::value_error("until: must be a finite time not before the run's t = " +
                            shortest(run_.state.t) + " (got " + shortest(until) + ")");
    if (max_steps && *max_steps == 0) throw py::value_error("max_steps: must be at least 1");
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
  std::pair<std::string, std::string> patch(const std::string& patch_text) {
    nlohmann::json patch;
    try {
      patch = parse_json_text(patch_text);
    } catch (const JsonTextError& e) {
      throw py::value_error(std::string("changes: ") + e.what());
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
      return {"continued", "new parameters from t = 0"};
    }
    retune(run_, *parsed.scene);
    changes_.push_back({run_.state.t, *parsed.scene});
    return {"continued", "new parameters from t = " + shortest(run_.state.t) + " on"};
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

// The still `spinfold render` draws, as RGBA rows top-down, on this thread's GL context.
py::dict render_still(const std::string& scene_text, double t, const std::string& view_name, int width,
                      int height, const std::string& layers_text,
                      std::optional<std::tuple<double, double, double>> camera, double scale,
                      std::optional<double> trail, const std::string& command) {
  if (!std::isfinite(t) || t < 0.0)
    throw py::value_error("t: must be a finite number >= 0 (got " + shortest(t) + ")");
  if (trail && (!std::isfinite(*trail) || *trail < 0.0)) throw py::value_error("trail: must be >= 0");
  if (width < 16 || width > 4096 || height < 16 || height > 4096)
    throw py::value_error("width/height: must be between 16 and 4096 pixels");
  if (!std::isfinite(scale) || !(scale > 0.0)) throw py::value_error("scale: must be a finite number > 0");
  const Scene scene = scene_of(scene_text);
  render::ViewOptions view;
  view.kind = render::default_view(scene.surface.kind);
  if (!view_name.empty()) {
    const auto kind = render::parse_view(view_name);
    if (!kind)
      throw py::value_error("view: must be one of " + render::joined_view_names(", ") + " (got '" +
                            view_name + "')");
    view.kind = *kind;
  }
  if (const auto why = render::view_unsupported_reason(view.kind, scene.surface.kind))
    throw py::value_error("view: " + *why);
  view.width = width;
  view.height = height;
  std::string unknown;
  const auto layers = render::parse_layers(layers_text, &unknown);
  if (!layers) throw py::value_error("layers: unknown layer '" + unknown + "'");
  view.layers = *layers;
  view.scale = scale * render::body_scale_length(view.kind, scene.surface);
  if (camera) {
    const auto [yaw, pitch, distance] = *camera;
    if (!std::isfinite(yaw) || !std::isfinite(pitch) || !std::isfinite(distance) || !(distance > 0))
      throw py::value_error("camera: must be (yaw, pitch, distance) in rad, rad, radii > 0");
    view.yaw = yaw;
    view.pitch = pitch;
    view.distance = distance;
  }
  render::Image image;
  std::string status;
  {
    py::gil_scoped_release release;
    Simulation run;
    const render::Snapshot snapshot = render::snapshot_at(scene, t, view.layers & render::kTrail, trail, run);
    if (!camera) render::aim_camera_at_body(view, snapshot);
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
        py::arg("command"));
  m.def("run_many", &run_many, py::arg("scenes"), py::arg("t_end"), py::arg("every"), py::arg("threads"),
        py::arg("command"));
  m.def("render", &render_still, py::arg("scene"), py::arg("t"), py::arg("view"), py::arg("width"),
        py::arg("height"), py::arg("layers"), py::arg("camera"), py::arg("scale"), py::arg("trail"),
        py::arg("command"));
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
