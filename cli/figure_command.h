// Vector figures from the command line (render/figure.h, render/series_plot.h):
//  - `spinfold render --format png|svg|pdf`: which format a render writes (by --out's extension
//    when not given; a name whose extension says another format is refused), and the SVG or PDF
//    frame itself;
//  - `spinfold plot SCENE.json | --scene PRESET --fields t,energy_error,r --t-end T --out F.svg|pdf`:
//    the quantities a paper plots against the first field (time by default), one panel each.
// Bad input: FigureInputError (exit 2 in main) or, for plot, a message on stderr and exit code 2.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "engine/scene.h"
#include "render/figure_page.h"
#include "render/snapshot.h"
#include "render/view.h"

namespace spinfold::cli {

struct FigureInputError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The format `render` writes: --format when given, else --out's extension (.png, .svg, .pdf),
// else png. Throws FigureInputError for an unknown --format, an extension that names no format
// (".jpg") or one that disagrees with --format.
render::FigureFormat render_format(const std::string& format_option, const std::string& out);

// The frame at time t as an SVG or PDF file at `out`: the camera aimed at the bodies (as for the
// PNG, with no HUD box to keep clear) unless `aim` is false, the caption from the scene, its
// snapshot and the provenance (with `command`, the command line). Throws FigureInputError when
// `out` cannot be written.
void write_frame_figure(const Scene& scene, const render::Snapshot& snapshot, render::ViewOptions view,
                        bool aim, render::FigureFormat format, const std::string& out,
                        const std::string& command, double t);

struct PlotOptions {
  std::string scene_file;
  std::string preset;
  std::string fields = "t,energy_error";  // the x axis, then one panel per quantity
  std::string log;                        // fields drawn on a logarithmic axis of |value|
  double t_end = 10.0;                    // [time]
  std::optional<double> every;            // sample spacing [time]; default t_end/1000
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> tolerance;
  std::string format;  // svg | pdf; "": by --out's extension
  std::string out;
  double width = 480;         // [pt]
  double panel_height = 120;  // [pt]
  bool no_footer = false;     // no provenance line on the page (it stays in the file's metadata)
};

// Registers `plot`; `opt` must outlive the parse.
CLI::App* add_plot_command(CLI::App& app, PlotOptions& opt);

// Runs it: 0, 2 for bad input (a message on stderr, nothing written), 3 when the run stopped before
// t_end (the figure shows what there is).
int run_plot_command(const PlotOptions& opt, int argc, char** argv);

}  // namespace spinfold::cli
