// `spinfold plot`: registered here, run by cli/figure_command.cpp.
#include <memory>

#include "cli/commands/command.h"
#include "cli/figure_command.h"

namespace spinfold::cli {

Command register_plot(CLI::App& app) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* cmd = add_plot_command(app, *options);
  return {cmd, [options](int argc, char** argv) { return run_plot_command(*options, argc, argv); }};
}

}  // namespace spinfold::cli
