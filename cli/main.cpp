// spinfold: the command line. `simulate` prints JSON Lines samples of a run; `sweep` runs a scene
// over varied fields; `render` draws one frame; `record` a time window as a GIF, WebM, MP4 or zip
// of PNGs; `work-precision` measures run time against error on a scene; `plot` draws quantities of
// a run as an SVG or PDF figure; `serve` the HTTP API; `scenes` lists the presets; `integrators`
// prints the catalog; `rerun` runs again the command an output records. Each subcommand is one file,
// cli/commands/<name>.cpp, and one row of the table below. Bad input: a message on stderr and exit code 2.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "cli/commands/command.h"
#include "codec/provenance.h"
#ifndef SPINFOLD_COMPUTE_ONLY  // the compute-only build: simulate and sweep, no GL, FFmpeg or HTTP
#include "cli/commands/gl_option.h"
#include "cli/figure_command.h"
#endif

namespace {

using namespace spinfold;

using Registrar = cli::Command (*)(CLI::App&);

// The subcommands, in the order --help lists them.
constexpr Registrar kCommands[] = {
    cli::register_simulate, cli::register_sweep,
#ifndef SPINFOLD_COMPUTE_ONLY
    cli::register_render,   cli::register_record,      cli::register_work_precision,
    cli::register_plot,     cli::register_serve,
#endif
    cli::register_scenes,   cli::register_integrators, cli::register_rerun,
};

// What the full build has beyond the compute-only one: named when asked for on a cluster node's build.
constexpr std::string_view kFullBuildOnly[] = {"render", "record", "work-precision", "plot", "serve"};

}  // namespace

int spinfold::cli::run_command_line(int argc, char** argv) {
  CLI::App app{"Spinfold: affinely-rigid bodies moving on curved surfaces"};
#ifdef SPINFOLD_COMPUTE_ONLY
  app.set_version_flag("--version", "spinfold " + version_line());
#else
  app.set_version_flag("--version",
                       [] { return "spinfold " + version_line() + "\n" + cli::gl_version_lines(); });
#endif
  app.require_subcommand(1);
#ifdef SPINFOLD_COMPUTE_ONLY
  if (argc > 1 && std::ranges::find(kFullBuildOnly, std::string_view(argv[1])) != std::end(kFullBuildOnly)) {
    std::cerr << "spinfold: " << argv[1]
              << " is not in this build (the compute-only build has simulate, sweep, scenes and integrators: "
                 "no GL, FFmpeg or HTTP; build without SPINFOLD_COMPUTE_ONLY for it)\n";
    return cli::kExitBadInput;
  }
#else
  (void)kFullBuildOnly;
#endif
  std::vector<cli::Command> commands;
  for (const Registrar add : kCommands) commands.push_back(add(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "spinfold: " << e.what() << "\n(run `spinfold --help` for usage)\n";
    return cli::kExitBadInput;
  }

  try {
    for (const cli::Command& command : commands)
      if (command.app->parsed()) return command.run(argc, argv);
  } catch (const cli::BadInput& e) {
    std::cerr << "spinfold: " << e.message << (e.message.ends_with('\n') ? "" : "\n");
    return cli::kExitBadInput;
#ifndef SPINFOLD_COMPUTE_ONLY
  } catch (const cli::FigureInputError& e) {
    std::cerr << "spinfold: " << e.what() << "\n";
    return cli::kExitBadInput;
#endif
  } catch (const std::runtime_error& e) {  // record::RecordError among them
    std::cerr << "spinfold: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  return spinfold::cli::run_command_line(argc, argv);
}
