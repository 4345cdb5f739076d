#include "cli/work_precision_command.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/commands/command.h"
#include "codec/output_file.h"
#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/scene_json.h"
#include "codec/scene_source.h"
#include "engine/integrator.h"
#include "engine/simulation.h"
#include "workprecision/work_precision.h"

namespace spinfold::cli {

namespace {

namespace wp = work_precision;
namespace fs = std::filesystem;

std::string valid_integrator_names() {
  std::string names;
  for (const CatalogEntry& e : integrator_catalog()) names += std::string(e.info.name) + ", ";
  return names + std::string(kAutoIntegrator);
}

std::vector<std::string> parse_integrators(const std::string& list) {
  std::vector<std::string> names, unknown;
  std::istringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    if (name.empty()) continue;
    if (name == kAutoIntegrator || find_integrator(name))
      names.push_back(name);
    else
      unknown.push_back("'" + name + "'");
  }
  if (!unknown.empty()) {
    std::string joined;
    for (const std::string& u : unknown) joined += (joined.empty() ? "" : ", ") + u;
    throw BadInput{"--integrators: unknown " + joined + " (valid: " + valid_integrator_names() + ")"};
  }
  if (!list.empty() && names.empty()) throw BadInput{"--integrators: no integrator named"};
  return names;
}

// The scene and the name it goes by in the outputs (the one scene rule, codec/scene_source.h).
std::pair<Scene, std::string> load_scene(const WorkPrecisionOptions& opt) {
  SceneSource source;
  try {
    source = scene_source(opt.scene_file, opt.preset, /*required=*/true);
  } catch (const SceneSourceError& e) {
    throw BadInput{e.what()};
  }
  try {
    return {spinfold::load_scene(source), source.label};
  } catch (const SceneSourceError& e) {
    throw BadInput{"the scene " + source.label + ": " + e.what()};
  }
}

int work_precision(const WorkPrecisionOptions& opt, int argc, char** argv) {
  // Everything is checked before anything is written.
  if (opt.out.empty()) throw BadInput{"--out: the folder to write is required"};
  if (opt.t_end && !(std::isfinite(*opt.t_end) && *opt.t_end > 0.0))
    throw BadInput{"--t-end: must be a finite number > 0"};
  if (!(std::isfinite(opt.target_error) && opt.target_error > 0.0))
    throw BadInput{"--target-error: must be a finite number > 0"};
  if (!(std::isfinite(opt.max_seconds_per_run) && opt.max_seconds_per_run > 0.0))
    throw BadInput{"--max-seconds-per-run: must be a finite number > 0"};
  const auto [scene, label] = load_scene(opt);
  wp::SweepOptions sweep;
  sweep.integrators = parse_integrators(opt.integrators);
  sweep.max_seconds_per_run = opt.max_seconds_per_run;
  const double period = wp::characteristic_period(scene);
  std::cerr << "work-precision: " << label << ": is the motion chaotic? (Lyapunov exponent and MEGNO)\n";
  const wp::Horizon chosen = wp::choose_horizon(scene, opt.t_end, opt.target_error);
  std::cerr << "  " << chosen.note << "\n";
  sweep.t_end = chosen.t_end;
  if (const fs::path out(opt.out); fs::exists(out) && !fs::is_directory(out))
    throw BadInput{"--out: '" + opt.out + "' exists and is not a folder"};
  std::error_code error;
  fs::create_directories(opt.out, error);
  if (error) throw BadInput{"--out: cannot create '" + opt.out + "': " + error.message()};

  const double t_end = sweep.t_end;
  // Past a chaotic scene's predictable horizon every error measured would be the chaos's: nothing is
  // run (it cost 54 s on the chaotic example at --t-end 100 to recommend nothing).
  wp::Reference reference{"none", "not computed: T lies beyond the predictable horizon", {}};
  wp::Curves curves;
  if (chosen.beyond) {
    std::cerr << "work-precision: " << label << ", T = " << t_end
              << ": nothing measured (beyond the horizon)\n";
  } else {
    std::cerr << "work-precision: " << label << ", T = " << t_end << ": computing the reference\n";
    reference = wp::make_reference(scene, t_end);
    std::cerr << "  reference: " << reference.kind << ": " << reference.description << "\n";
    curves = wp::sweep(scene, reference, sweep, [](const wp::Point& p) {
      std::cerr << "  " << p.method << " " << p.parameter << " " << p.value << ": error " << p.state_error
                << ", " << wp::format_cost(p.seconds_per_unit_time) << " µs per unit time\n";
    });
  }

  const std::string line = wp::recommendation(curves, opt.target_error, chosen, wp::auto_picks(scene));
  std::ostringstream t_text, period_text;
  t_text << t_end;
  period_text << period;
  const std::string horizon =
      "T = " + t_text.str() +
      (chosen.shortened        ? " (the predictable horizon: " + chosen.note + ")"
       : opt.t_end             ? " (--t-end)"
       : std::isfinite(period) ? " (" + std::to_string(static_cast<int>(wp::kDefaultPeriods)) +
                                     " characteristic periods of " + period_text.str() + ")"
                               : " (" + std::to_string(static_cast<int>(wp::kDefaultPeriods)) +
                                     " time units: the motion has no characteristic period)");
  const std::string command = provenance_command(argc, argv);
  const std::string provenance = provenance_json(scene, command).dump();
  const std::string header = "# spinfold work-precision " + version_line() + "\n# command: " + command +
                             "\n# provenance: " + provenance + "\n# scene: " + label + "; " + horizon +
                             "\n# reference: " + reference.kind + ": " + reference.description + "\n# " +
                             wp::kErrorMeaning + "\n# " + wp::kErrorParts + "\n";
  write_whole_file((fs::path(opt.out) / "work_precision.csv").string(), wp::csv(header, curves));
  const std::string plot =
      chosen.beyond
          ? ""
          : wp::write_plot(opt.out, "work_precision", "work-precision: " + label, provenance, curves, t_end);

  std::ostringstream md;
  md << "# Work-precision: " << label << "\n\n"
     << "**Recommendation.** " << line << "\n\n"
     << "- " << horizon << "; target error " << opt.target_error << "\n"
     << "- Reference: " << reference.kind << ": " << reference.description << "\n"
     << "- Error: " << wp::kErrorMeaning << "; " << wp::kErrorParts << "\n";
  if (!chosen.shortened) md << "- Chaos: " << chosen.note << "\n";
  if (!scene.companions.empty()) md << "- The main body only: its companions are separate runs.\n";
  if (chosen.beyond) {
    md << "- Nothing measured: T lies beyond the predictable horizon\n";
    write_whole_file((fs::path(opt.out) / "summary.md").string(), "<!--\n" + header + "-->\n" + md.str());
    std::cout << md.str();
    return 0;
  }
  for (const auto& [name, why] : wp::skipped_integrators(scene, sweep))
    md << "- Not run: " << name << " (" << why << ")\n";
  md << "- Plot: " << (plot.empty() ? "work_precision.png, work_precision.svg" : plot)
     << " (also as a gnuplot script: `gnuplot work_precision.gp` in this folder); data: "
        "work_precision.csv\n\n"
     << "Cost at error " << opt.target_error << " (interpolated along each curve, µs per unit time):\n\n"
     << "| method | µs per unit time |\n| --- | --- |\n";
  for (const auto& [method, curve] : curves)
    md << "| " << method << " | " << wp::format_cost(wp::cost_at(curve, opt.target_error)) << " |\n";
  md << "\nEvery point:\n\n" << wp::points_table(curves);
  // The file starts with the provenance as a comment (not rendered; the CSV header's lines).
  write_whole_file((fs::path(opt.out) / "summary.md").string(), "<!--\n" + header + "-->\n" + md.str());
  std::cout << md.str();
  return 0;
}

}  // namespace

CLI::App* add_work_precision_command(CLI::App& app, WorkPrecisionOptions& opt) {
  CLI::App* cmd = app.add_subcommand(
      "work-precision", "Run time against error for each integrator on a scene (CSV, plot, recommendation)");
  cmd->add_option("scene_file", opt.scene_file, "A scene file, or a preset's name if no file has it");
  cmd->add_option("--scene", opt.preset, "An embedded preset by name (see `spinfold scenes`)");
  cmd->add_option("--integrators", opt.integrators,
                  "Comma-separated catalog names and/or auto (default: all, auto at the scene's tolerance)");
  cmd->add_option("--t-end", opt.t_end, "Horizon T (default: 20 characteristic periods)");
  cmd->add_option("--target-error", opt.target_error, "Error the recommendation is for")
      ->capture_default_str();
  cmd->add_option("--max-seconds-per-run", opt.max_seconds_per_run,
                  "Stop refining a method once one run takes longer [s]")
      ->capture_default_str();
  cmd->add_option("--out", opt.out, "Folder to write")->required();
  return cmd;
}

int run_work_precision_command(const WorkPrecisionOptions& opt, int argc, char** argv) {
  try {
    return work_precision(opt, argc, argv);
  } catch (const BadInput& e) {
    std::cerr << "spinfold: " << e.message << (e.message.ends_with('\n') ? "" : "\n");
    return kExitBadInput;
  }
}

}  // namespace spinfold::cli
