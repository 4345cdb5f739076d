#include "cli/figure_command.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/commands/command.h"
#include "codec/output_file.h"
#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "codec/scene_source.h"
#include "engine/sampling.h"
#include "engine/simulation.h"
#include "render/figure.h"
#include "render/scene_builder.h"
#include "render/series_plot.h"
#include "render/view_parameters.h"

namespace spinfold::cli {

namespace {

constexpr double kMaxPlotSamples = 1e6;

// Checked to the close: a full disk is an error naming the file (WriteError, exit 1).
void write_bytes(const std::string& out, const std::vector<std::uint8_t>& bytes) {
  write_whole_file(out, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

std::string extension_of(const std::string& out) {
  const std::string name = std::filesystem::path(out).filename().string();
  const std::size_t dot = name.find_last_of('.');
  return dot == std::string::npos ? "" : name.substr(dot);
}

// The scene of `plot`, with the command line's overrides checked as the scene file is (the one
// scene rule, codec/scene_source.h).
Scene load_plot_scene(const PlotOptions& opt) {
  try {
    return load_scene(scene_source(opt.scene_file, opt.preset),
                      {.name = opt.integrator, .dt = opt.dt, .tolerance = opt.tolerance});
  } catch (const SceneSourceError& e) {
    throw FigureInputError(e.what());
  }
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::istringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

glm::dvec4 rgba(const std::array<float, 3>& c) {
  return {c[0], c[1], c[2], 1.0};
}

int plot(const PlotOptions& opt, int argc, char** argv) {
  if (!std::isfinite(opt.t_end) || !(opt.t_end > 0.0))
    throw FigureInputError("--t-end: must be a finite number > 0");
  const double every = opt.every.value_or(opt.t_end / 1000.0);
  if (!std::isfinite(every) || !(every > 0.0)) throw FigureInputError("--every: must be a finite number > 0");
  if (opt.t_end / every > kMaxPlotSamples) throw FigureInputError("--every: more than 1e6 samples requested");
  if (!(opt.width >= 200.0 && opt.width <= 2000.0))
    throw FigureInputError("--width: must be 200..2000 points");
  if (!(opt.panel_height >= 40.0 && opt.panel_height <= 1000.0))
    throw FigureInputError("--panel-height: must be 40..1000 points");
  if (opt.out.empty()) throw FigureInputError("--out: the SVG or PDF file to write is required");
  const render::FigureFormat format = render_format(opt.format, opt.out);
  if (format == render::FigureFormat::png)
    throw FigureInputError(
        "--format: plot writes svg or pdf (got png; `spinfold simulate --format csv` gives the numbers)");
  const std::vector<std::string> fields = split(opt.fields);
  if (fields.size() < 2)
    throw FigureInputError("--fields: an x axis and at least one quantity, e.g. t,energy_error");
  const std::vector<std::string> numeric(sample_value_names().begin(), sample_value_names().end());
  for (const std::string& f : fields)
    if (std::find(numeric.begin(), numeric.end(), f) == numeric.end())
      throw FigureInputError("--fields: '" + f +
                             "' is not a numeric column (see `spinfold simulate --list-fields`)");
  const std::vector<std::string> log = split(opt.log);
  for (const std::string& f : log)
    if (std::find(fields.begin() + 1, fields.end(), f) == fields.end())
      throw FigureInputError("--log: '" + f + "' is not one of the plotted --fields");
  const Scene scene = load_plot_scene(opt);

  Simulation run = start_simulation(scene);
  const SampleTable table = make_sample_table(opt.fields, sample_to_json(run, -1.0));
  render::SeriesPlot plot;
  // The axes' titles from the column table (codec/sample_table.h): symbols and units, "ΔH/H₀", "t [time]".
  plot.x_quantity = column_symbol(fields.front());
  plot.x_unit = column_unit(fields.front());
  plot.width = opt.width;
  plot.panel_height = opt.panel_height;
  for (std::size_t i = 1; i < fields.size(); ++i) {
    render::PlotPanel panel{column_symbol(fields[i]),
                            column_unit(fields[i]),
                            std::find(log.begin(), log.end(), fields[i]) != log.end(),
                            {}};
    panel.lines.push_back({main_body_label(scene), rgba(render::kMainTrailColor), {}});
    for (std::size_t c = 0; c < table.companion_labels.size(); ++c)
      panel.lines.push_back({table.companion_labels[c], rgba(render::companion_color(scene, c)), {}});
    plot.panels.push_back(std::move(panel));
  }
  const auto number = [](const nlohmann::ordered_json& row, const std::string& name) {
    const auto it = row.find(name);
    return it != row.end() && it->is_number() ? it->get<double>() : std::nan("");
  };
  double reported_until = -1.0;
  const auto emit = [&] {
    const nlohmann::ordered_json row = table.json_row(sample_to_json(run, reported_until));
    reported_until = run.state.t;
    plot.x.push_back(number(row, fields.front()));
    for (std::size_t p = 0; p < plot.panels.size(); ++p) {
      render::PlotPanel& panel = plot.panels[p];
      const std::string& field = fields[p + 1];
      panel.lines.front().y.push_back(number(row, field));
      for (std::size_t c = 0; c < table.companion_labels.size(); ++c)
        panel.lines[c + 1].y.push_back(number(row, table.companion_labels[c] + "." + field));
    }
  };
  sample_run(
      run, opt.t_end, every, [&](double t) { return advance_to(run, t); }, emit);

  const std::string command = provenance_command(argc, argv);
  plot.title = scene.name.empty() ? "Spinfold scene" : scene.name;
  plot.description = scene.description;
  if (!opt.no_footer) plot.provenance = provenance_header(scene) + "; command=" + command;
  plot.metadata = provenance_json(scene, command).dump();
  write_bytes(opt.out, render::draw_figure(render::series_page(plot), format));
  return run_exit_code(run.state);
}

}  // namespace

render::FigureFormat render_format(const std::string& format_option, const std::string& out) {
  std::optional<render::FigureFormat> chosen;
  if (!format_option.empty()) {
    chosen = render::parse_figure_format(format_option);
    if (!chosen) throw FigureInputError("--format: must be png, svg or pdf (got '" + format_option + "')");
  }
  const std::string extension = extension_of(out);
  if (extension.empty()) return chosen.value_or(render::FigureFormat::png);
  const auto named = render::figure_format_of_path(out);
  if (!named)
    throw FigureInputError("--out: '" + out + "' ends in " + extension +
                           ", which names no format written here (.png, .svg or .pdf)");
  if (chosen && *chosen != *named)
    throw FigureInputError("--out: '" + out + "' ends in " + extension + " but --format is " + format_option +
                           " (name the file ." + format_option + " or leave --format out)");
  return *named;
}

void write_frame_figure(const Scene& scene, const render::Snapshot& snapshot, render::ViewOptions view,
                        bool aim, render::FigureFormat format, const std::string& out,
                        const std::string& command, double t) {
  if (aim) render::place_camera(view, {}, snapshot, render::Picture::figure);  // aimed at the body
  render::FigureCaption caption;
  caption.title = scene.name.empty() ? "Spinfold scene" : scene.name;
  caption.description = scene.description;
  char at[64];
  std::snprintf(at, sizeof at, "; t=%.17g; view=", t);
  caption.provenance = provenance_header(scene) + at + std::string(render::view_name(view.kind)) +
                       (command.empty() ? "" : "; command=" + command);
  for (const auto& [key, value] : picture_texts(scene, command, t, render::view_name(view.kind)))
    if (key == "Source") caption.metadata = value;
  write_bytes(out, render::draw_figure(render::figure_page(snapshot, view, caption), format));
}

CLI::App* add_plot_command(CLI::App& app, PlotOptions& opt) {
  CLI::App* cmd = app.add_subcommand(
      "plot", "Plot quantities of a run against time (or another field) as an SVG or PDF figure for a paper");
  cmd->add_option("scene_file", opt.scene_file,
                  "A scene file, or a preset's name if no file has it (default: the default preset)");
  cmd->add_option("--scene", opt.preset, "Plot an embedded preset by name (see `spinfold scenes`)");
  cmd->add_option(
         "--fields", opt.fields,
         "The x axis, then one panel per quantity (numeric columns of `spinfold simulate --list-fields`)")
      ->capture_default_str();
  cmd->add_option("--log", opt.log, "Fields plotted as |value| on a logarithmic axis (e.g. energy_error)");
  cmd->add_option("--t-end", opt.t_end, "Simulated time to reach")->capture_default_str();
  cmd->add_option("--every", opt.every, "Sample interval [time] (default: t-end/1000)");
  cmd->add_option("--integrator", opt.integrator, "Override the scene's integrator name");
  cmd->add_option("--dt", opt.dt, "Override the step (fixed-step) or first trial step");
  cmd->add_option("--tolerance", opt.tolerance, "Override the error tolerance per step");
  cmd->add_option("--format", opt.format, "svg | pdf (default: by --out's extension)");
  cmd->add_option("--out", opt.out, "SVG or PDF file to write")->required();
  cmd->add_option("--width", opt.width, "Figure width [pt]")->capture_default_str();
  cmd->add_option("--panel-height", opt.panel_height, "Height of each panel's plot area [pt]")
      ->capture_default_str();
  cmd->add_flag(
      "--no-footer", opt.no_footer,
      "No provenance line under the figure (a paper's caption says it); it stays in the file's metadata");
  return cmd;
}

int run_plot_command(const PlotOptions& opt, int argc, char** argv) {
  try {
    return plot(opt, argc, argv);
  } catch (const FigureInputError& e) {
    std::cerr << "spinfold: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {  // make_sample_table's unknown field
    std::cerr << "spinfold: --fields: " << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace spinfold::cli
