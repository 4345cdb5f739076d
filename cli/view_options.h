// The picture options that `spinfold render` and `spinfold record` share: one --NAME per row of the
// view-parameter table (render/view_parameters.h: --width, --height, --view, --layers, --scale, --yaw,
// --pitch, --distance, --trail), with the table's help, unit, range and default, checked in the
// table's words; and --camera yaw,pitch,distance, the three camera options at once.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <stdexcept>
#include <string>

#include "render/view_parameters.h"

namespace spinfold::cli {

// The options as typed, by parameter name (only those given).
struct ViewArgs {
  std::map<std::string, std::string, std::less<>> text;  // bound to the options; read where given
  std::map<std::string, CLI::Option*, std::less<>> options;
  std::string camera;  // "yaw,pitch,distance"; "" when not given
};

// A refused option: "--width: must be a whole number from 16 to 4096 [pixels] (got 5000)".
struct BadViewOption : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Adds the options to a command; `args` must outlive the parse.
void add_view_options(CLI::App& command, ViewArgs& args);

// The request the options make (the table's defaults for those not given); BadViewOption naming the
// first option refused, its value and the reason.
render::ViewRequest view_request(const ViewArgs& args);

// The option's name for a parameter: "--" + name.
std::string option_name(const render::ViewParameter& p);

}  // namespace spinfold::cli
