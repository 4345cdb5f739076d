// `spinfold render`: one frame at time T as a PNG (GL), or an SVG or PDF figure
// (cli/figure_command.h).
#include "cli/commands/render.h"

#include <fstream>
#include <iostream>
#include <memory>
#include <vector>

#include "cli/commands/command.h"
#include "cli/commands/gl_option.h"
#include "cli/figure_command.h"
#include "codec/output_file.h"
#include "codec/provenance.h"
#include "render/renderer.h"
#include "render/snapshot.h"
#include "render/view_parameters.h"

namespace spinfold::cli {

// The view options as the table reads them; the view checked against the scene's surface.
render::ViewRequest view_request(const RenderOptions& opt) {
  try {
    return cli::view_request(opt.view);
  } catch (const BadViewOption& e) {
    throw BadInput{e.what()};
  }
}

// The view of the request on the scene's surface (render::view_options: the one resolver).
render::ViewOptions view_options(const render::ViewRequest& request, const Scene& scene) {
  try {
    return render::view_options(request, scene.surface);
  } catch (const render::ViewRefused& e) {
    throw BadInput{"--" + e.parameter + ": " + e.what()};
  }
}

namespace {

struct RenderCommandOptions : RenderOptions {
  std::string format;  // png | svg | pdf (cli/figure_command.h)
  std::string gl;
};

int render_frame(const RenderOptions& opt, const std::string& format_option) {
  check_run_limit("t", opt.t);
  if (opt.out.empty()) throw BadInput{"--out: the PNG file to write is required"};
  const render::FigureFormat format = render_format(format_option, opt.out);  // before any work
  const render::ViewRequest request = view_request(opt);
  const Scene scene = load_scene(opt.scene);
  render::ViewOptions view = view_options(request, scene);

  Simulation run;
  const render::Snapshot snapshot =
      render::snapshot_at(scene, opt.t, view.layers & render::kTrail, request.trail, run);
  // The camera aimed at the body, the parts given replacing the aimed ones (as every front door).
  render::place_camera(
      view, request, snapshot,
      format == render::FigureFormat::png ? render::Picture::frame : render::Picture::figure);
  if (format != render::FigureFormat::png) {  // a vector figure (cli/figure_command.h)
    write_frame_figure(scene, snapshot, view, false, format, opt.out, opt.scene.command, opt.t);
  } else {
    render::Renderer renderer;
    const std::vector<render::PngText> texts =
        picture_texts(scene, opt.scene.command, opt.t, render::view_name(view.kind));
    const std::vector<std::uint8_t> png = renderer.render_png(snapshot, view, texts);
    write_whole_file(opt.out, {reinterpret_cast<const char*>(png.data()), png.size()});
  }
  return run_exit_code(run.state);
}

}  // namespace

Command register_render(CLI::App& app) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* render_cmd =
      app.add_subcommand("render", "Render the state at time T as a PNG, or an SVG or PDF figure");
  render_cmd->add_option("scene_file", options->scene.scene_file,
                         "A scene file, or a preset's name if no file has it (default: the default preset)");
  render_cmd->add_option("--scene", options->scene.preset, "Render an embedded preset by name");
  render_cmd->add_option("--t", options->t, "Time of the frame")->capture_default_str();
  add_view_options(*render_cmd, options->view);
  render_cmd->add_option("--out", options->out, "File to write (.png, .svg or .pdf)");
  render_cmd->add_option("--format", options->format,
                         "png | svg | pdf: the GL frame, or a vector figure for a paper (default: by --out's "
                         "extension, else png)");
  render_cmd->add_option("--integrator", options->scene.integrator, "Override the scene's integrator name");
  add_gl_option(render_cmd, options->gl);
  return {render_cmd, [options](int argc, char** argv) {
            apply_gl_choice(options->gl);
            options->scene.command = provenance_command(argc, argv);
            return render_frame(*options, options->format);
          }};
}

}  // namespace spinfold::cli
