// spinfold._core's sweep and scene names: Python's door to the sweep library (sweep/), the one
// `spinfold sweep` calls, so that one definition gives the CLI's rows to the bit (
// python/spinfold/__init__.py turns the rows into NumPy columns), and to the one scene rule of the
// CLI (codec/scene_source.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "codec/json_text.h"
#include "codec/scene_source.h"
#include "sweep/grid.h"
#include "sweep/plan.h"
#include "sweep/rows.h"
#include "sweep/run.h"

namespace py = pybind11;

namespace spinfold::python {

namespace {

py::object cell(const nlohmann::ordered_json& value) {
  if (value.is_null()) return py::none();
  if (value.is_number_unsigned()) return py::int_(value.get<std::uint64_t>());
  if (value.is_number_integer()) return py::int_(value.get<std::int64_t>());
  if (value.is_number()) return py::float_(value.get<double>());
  if (value.is_boolean()) return py::bool_(value.get<bool>());
  return py::str(value.get<std::string>());
}

// axes: (path, spec, values): `spec` an "a:b:n" or "v1,v2,…" text as --set takes it, or else
// `values` a JSON array. Returns the column names and the rows (lists of None, int, float, str).
py::tuple sweep(
    const std::string& base_text,
    const std::vector<std::tuple<std::string, std::optional<std::string>, std::optional<std::string>>>& axes,
    bool zip, double t_end, double every, const std::string& fields,
    const std::vector<std::string>& summaries, const std::vector<std::string>& events, bool chaos,
    double chaos_interval, std::optional<std::uint64_t> max_steps, int threads, const std::string& command) {
  if (threads < 0) throw py::value_error("threads: must be >= 1 or None (one per core)");
  sweep::Definition def{.base_text = base_text,
                        .axes = {},
                        .zip = zip,
                        .t_end = t_end,
                        .every = every,
                        .max_steps = max_steps,
                        .fields = fields,
                        .summaries = summaries,
                        .events = events,
                        .chaos = chaos,
                        .chaos_interval = chaos_interval,
                        .trajectories = "",
                        .trajectory_fields = "",
                        .trajectory_format = "jsonl",
                        .command = command,
                        .door = sweep::Door::python};
  std::vector<sweep::Row> rows;
  std::vector<std::string> names;
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    for (const auto& [path, spec, values] : axes) {
      const std::string label = "vary['" + path + "']";
      def.axes.push_back(spec ? sweep::axis_from_spec(path, *spec, label)
                              : sweep::axis_from_values(path, parse_json_text(values.value_or("[]")), label));
    }
    const sweep::Plan plan = sweep::make_plan(std::move(def));
    names = sweep::column_names(plan);
    const std::vector<std::size_t> runs = sweep::shard_runs(plan.total, {});
    rows.reserve(runs.size());
    // The sweep on a thread of its own; this one looks at Python's signals every 20 ms (its handler
    // only sets a flag, which only a thread holding the GIL can read), so that Ctrl-C stops the
    // sweep after the runs in progress and raises KeyboardInterrupt here.
    std::atomic<bool> cancel{false}, done{false};
    std::exception_ptr failure;
    std::thread worker([&] {
      try {
        sweep::run_all(
            plan, runs, static_cast<unsigned>(threads),
            [&](sweep::Row&& row) { rows.push_back(std::move(row)); }, {}, [&] { return cancel.load(); });
      } catch (...) {
        failure = std::current_exception();
      }
      done = true;
    });
    while (!done) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        cancel = true;
        interrupted = true;
        break;
      }
    }
    worker.join();
    if (failure) std::rethrow_exception(failure);
  }
  if (interrupted) throw py::error_already_set();
  py::list out;
  for (const sweep::Row& row : rows) {
    py::list r;
    r.append(py::int_(row.index));
    for (const auto& [name, value] : row.cells) r.append(cell(value));
    out.append(std::move(r));
  }
  return py::make_tuple(names, out);
}

}  // namespace

void add_sweep(py::module_& m) {
  m.def("sweep", &sweep, py::arg("base"), py::arg("axes"), py::arg("zip"), py::arg("t_end"), py::arg("every"),
        py::arg("fields"), py::arg("summaries"), py::arg("events"), py::arg("chaos"),
        py::arg("chaos_interval"), py::arg("max_steps"), py::arg("threads"), py::arg("command"));
  m.def("sweep_fields", [] { return sweep::field_names(); });
  m.def("default_sweep_fields", [] { return std::string(sweep::kDefaultFields); });
  // The one scene rule (codec/scene_source.h): a file if one has that name, else a preset.
  m.def("scene_text", [](const std::string& name, const std::string& option) {
    if (name.empty()) throw py::value_error(option + ": give a preset's name, a path, JSON text or a dict");
    return find_scene(name, option).text;
  });
  m.def("grid", [](double a, double b, std::size_t n) {
    if (n < 1 || n > sweep::kMaxRuns)
      throw py::value_error("n: must be 1.." + std::to_string(sweep::kMaxRuns) + " (got " +
                            std::to_string(n) + ")");
    return sweep::grid_values(a, b, n);
  });
}

}  // namespace spinfold::python
