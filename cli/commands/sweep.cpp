// `spinfold sweep`: registered here, translated in cli/sweep.cpp (the sweep library's front door).
#include "cli/sweep.h"

#include <memory>

#include "cli/commands/command.h"

namespace spinfold::cli {

Command register_sweep(CLI::App& app) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* cmd = add_sweep_command(app, *options);
  return {cmd, [options](int argc, char** argv) { return run_sweep_command(*options, argc, argv); }};
}

}  // namespace spinfold::cli
