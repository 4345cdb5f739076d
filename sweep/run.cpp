#include "sweep/run.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "codec/npz_writer.h"
#include "codec/output_file.h"
#include "codec/provenance.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "engine/chaos_indicators.h"
#include "engine/sampling.h"
#include "engine/simulation.h"

namespace spinfold::sweep {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

Row run_one(const Plan& plan, std::size_t index) {
  const auto start = std::chrono::steady_clock::now();
  Row row{.index = index, .cells = {}, .ok = false};
  for (auto& [name, value] : varied_values(plan, index)) row.cells.emplace_back(name, ojson(value));
  std::map<std::string, ojson> first, last;
  std::vector<double> monitored;  // monitor_columns(plan.monitor)'s values
  std::optional<ChaosIndicators> chaos;
  std::string status, detail;
  std::uint64_t steps = 0, events = 0;
  const Definition& def = plan.def;
  try {
    const SceneParse parsed = parse_scene(run_document(plan, index));
    if (!parsed.errors.empty()) {
      status = "invalid_scene";
      detail = describe_errors(parsed.errors);
      while (!detail.empty() && detail.back() == '\n') detail.pop_back();
      std::replace(detail.begin(), detail.end(), '\n', ';');
    } else {
      // `spinfold simulate`'s loop: samples at k·every up to t_end, the same advances.
      Simulation run = start_simulation(*parsed.scene);
      if (!plan.monitor.empty()) watch(run, plan.monitor);
      // The trajectory as `spinfold simulate --fields … --format …` writes it: the provenance, then
      // the samples (the whole sample as JSON Lines without --trajectory-fields).
      const std::string& format = def.trajectory_format;
      std::unique_ptr<OutputFile> trajectory;  // every write checked: a failed one is the row's error
      std::optional<SampleTable> table;
      std::vector<NpzColumn> npz;
      const ojson provenance =
          provenance_json(*parsed.scene, def.command + " # run " + std::to_string(index));
      const std::filesystem::path file =
          std::filesystem::path(def.trajectories) / (std::to_string(index) + "." + format);
      const bool tracing = !def.trajectories.empty();
      if (tracing && (format != "jsonl" || !def.trajectory_fields.empty()))
        table = make_sample_table(def.trajectory_fields, sample_to_json(run, -1.0));
      if (tracing && format == "npz") {
        for (const std::string& name : table->header()) npz.push_back({name, {}});
      } else if (tracing) {
        trajectory = std::make_unique<OutputFile>(file.string());
        if (format == "csv")
          trajectory->write(table->csv_header() + "# spinfold simulate " + version_line() +
                            "\n# provenance: " + provenance.dump() + '\n');
        else
          trajectory->write(ojson{{"provenance", provenance}}.dump() + '\n');
      }
      double reported_until = -1.0;
      const auto sample = [&](std::map<std::string, ojson>* into) {
        if (tracing || into) {
          const ojson s = sample_to_json(run, reported_until);
          events += s["events"].size();
          if (format == "npz" && tracing) {
            const std::vector<ojson> cells = table->row(s);
            for (std::size_t i = 0; i < cells.size(); ++i) npz[i].cells.push_back(cells[i]);
          } else if (trajectory) {
            if (format == "csv")
              trajectory->write(table->csv_row(s));
            else
              trajectory->write((table ? table->json_row(s) : s).dump() + '\n');
          }
          if (into) *into = flatten_sample(s);
        } else {
          events += events_after(run, reported_until).size();
        }
        reported_until = run.state.t;
      };
      std::uint64_t attempts = def.max_steps.value_or(kNoStepLimit);
      bool started = false;
      const bool budget_left = sample_run(
          run, def.t_end, def.every,
          [&](double t) { return def.max_steps ? advance_within(run, t, attempts) : advance_to(run, t); },
          [&] {
            const bool final = run.state.status != Status::ok || run.state.t >= def.t_end;
            sample(!started ? &first : final ? &last : nullptr);
            started = true;
          });
      if (trajectory) trajectory->close();
      if (last.empty()) last = flatten_sample(sample_to_json(run, reported_until));
      status = budget_left ? last["status"].get<std::string>() : "max_steps";
      detail = budget_left ? last["status_detail"].get<std::string>()
                           : "the step budget (" + option_name(def.door, "--max-steps") + ") ran out";
      steps = run.steps;
      if (tracing && format == "npz") {
        npz.push_back({"provenance", {provenance.dump()}});
        write_npz(file.string(), npz);
      }
      monitored = monitor_values(run);
      if (def.chaos) {  // its own two runs, to where this one ended
        ChaosMonitor indicators(*parsed.scene, def.chaos_interval, run.start_time);
        indicators.advance_to(run.state.t, attempts);  // within what is left of the run's --max-steps
        chaos = indicators.indicators();
      }
    }
  } catch (const std::exception& e) {
    status = "error";
    detail = e.what();
  }
  for (const Column& c : plan.columns) {
    ojson value;
    const auto f = last.find(c.key);
    if (f != last.end()) value = f->second;
    if (c.drift) {
      const auto i = first.find(c.key);
      value = (value.is_number() && i != first.end() && i->second.is_number())
                  ? ojson(value.get<double>() - i->second.get<double>())
                  : ojson(nullptr);
    }
    row.cells.emplace_back(c.name, value);
  }
  const std::vector<std::string> monitor_names = monitor_columns(plan.monitor);
  for (std::size_t i = 0; i < monitor_names.size(); ++i) {
    const double v = i < monitored.size() ? monitored[i] : std::numeric_limits<double>::quiet_NaN();
    ojson value = std::isnan(v) ? ojson(nullptr) : ojson(v);
    if (monitor_names[i].ends_with(".count") && !std::isnan(v)) value = static_cast<std::uint64_t>(v);
    row.cells.emplace_back(monitor_names[i], std::move(value));
  }
  if (def.chaos) {
    const std::array<double, 5> values =
        chaos ? chaos_values(*chaos) : std::array<double, 5>{NAN, NAN, NAN, NAN, NAN};
    for (std::size_t i = 0; i < values.size(); ++i)
      row.cells.emplace_back(std::string(kChaosColumns[i]),
                             std::isfinite(values[i]) ? ojson(values[i]) : ojson(nullptr));
  }
  // A run that stopped where it was asked to (an event's stop=N) ended well.
  row.ok = status == "ok" || status == "event_stop";
  row.cells.emplace_back("events", events);
  row.cells.emplace_back("status", status);
  row.cells.emplace_back("detail", detail);
  row.cells.emplace_back("steps", steps);
  row.cells.emplace_back("seconds",
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return row;
}

void run_all(const Plan& plan, std::span<const std::size_t> runs, unsigned jobs,
             const std::function<void(Row&&)>& on_row,
             const std::function<void(const Progress&)>& on_progress,
             const std::function<bool()>& cancelled) {
  // Workers take runs in order; rows go out in run order as soon as all before them are done.
  if (jobs == 0) jobs = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::optional<Row>> rows(runs.size());
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::size_t written = 0;
  Progress progress{.done = 0, .not_ok = 0, .total = runs.size()};
  // The first error of on_row or on_progress (a write that failed) stops the workers taking runs
  // and is thrown here, on the caller's thread, after they have finished.
  std::exception_ptr failure;
  const auto work = [&] {
    for (std::size_t k; (k = next++) < runs.size();) {
      if (cancelled && cancelled()) {
        next = runs.size();
        return;
      }
      Row row = run_one(plan, runs[k]);
      std::lock_guard lock(mutex);
      if (failure) return;
      try {
        ++progress.done;
        progress.not_ok += row.ok ? 0 : 1;
        rows[k] = std::move(row);
        for (; written < rows.size() && rows[written]; ++written) {
          on_row(std::move(*rows[written]));
          rows[written].reset();
        }
        if (on_progress) on_progress(progress);
      } catch (...) {
        failure = std::current_exception();
        next = runs.size();
        return;
      }
    }
  };
  std::vector<std::thread> threads;
  for (unsigned j = 1; j < std::min<std::size_t>(jobs, runs.size()); ++j) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace spinfold::sweep
