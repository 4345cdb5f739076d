// `spinfold work-precision`: registered here, run by cli/work_precision_command.cpp.
#include <memory>

#include "cli/commands/command.h"
#include "cli/work_precision_command.h"

namespace spinfold::cli {

Command register_work_precision(CLI::App& app) {
  auto options = std::make_shared<WorkPrecisionOptions>();
  CLI::App* cmd = add_work_precision_command(app, *options);
  return {cmd, [options](int argc, char** argv) { return run_work_precision_command(*options, argc, argv); }};
}

}  // namespace spinfold::cli
