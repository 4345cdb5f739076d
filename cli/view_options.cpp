#include "cli/view_options.h"

#include <string_view>
#include <variant>
#include <vector>

#include "engine/number_rule.h"

namespace spinfold::cli {

namespace {

// "image width [pixels; 16 to 4096]", "… [surface radii; (0, 10]]": the help of the table, its unit
// and range (the default is CLI11's).
std::string help_of(const render::ViewParameter& p) {
  std::string help(p.help);
  const render::ParameterType type = render::parameter_type(p);
  if (type == render::ParameterType::enumeration) {
    std::string names;
    for (const std::string_view n : render::choices(p))
      names += (names.empty() ? "" : " | ") + std::string(n);
    return "one of " + names + ": " + help;
  }
  if (type == render::ParameterType::list) {
    std::string names;
    for (const std::string_view n : render::layer_names()) {
      if (!names.empty()) names += ',';
      names += n;
    }
    return "comma-separated, of " + names + ": " + help;
  }
  const Range r = render::allowed_range(p);
  std::string bounds;
  if (r.has_min() && r.has_max())
    bounds = r.min_open ? "(" + shortest(r.min) + ", " + shortest(r.max) + "]"
                        : shortest(r.min) + " to " + shortest(r.max);
  else if (r.has_min())
    bounds = (r.min_open ? "> " : ">= ") + shortest(r.min);
  std::string unit(p.unit);
  if (!bounds.empty()) unit += (unit.empty() ? "" : "; ") + bounds;
  return unit.empty() ? help : help + " [" + unit + "]";
}

}  // namespace

std::string option_name(const render::ViewParameter& p) {
  return "--" + std::string(p.name);
}

void add_view_options(CLI::App& command, ViewArgs& args) {
  for (const render::ViewParameter& p : render::view_parameters()) {
    const std::string name(p.name);
    CLI::Option* option = command.add_option(option_name(p), args.text[name], help_of(p));
    if (const auto fallback = render::default_value(p))
      option->default_str(std::holds_alternative<double>(*fallback) ? shortest(std::get<double>(*fallback))
                                                                    : std::get<std::string>(*fallback));
    switch (render::parameter_type(p)) {
      case render::ParameterType::integer: option->type_name("INT"); break;
      case render::ParameterType::number: option->type_name("FLOAT"); break;
      case render::ParameterType::enumeration: option->type_name(p.name == "view" ? "VIEW" : "CHOICE"); break;
      case render::ParameterType::list: option->type_name("LIST"); break;
    }
    args.options[name] = option;
  }
  command.add_option("--camera", args.camera,
                     "yaw,pitch,distance: --yaw, --pitch and --distance at once (3-D views; without them the "
                     "camera is aimed at the body)");
}

render::ViewRequest view_request(const ViewArgs& args) {
  render::ViewRequest request;
  const auto refuse = [](const std::string& flag, const std::string& value, const std::string& why) {
    throw BadViewOption(refused(flag, why, "'" + value + "'"));
  };
  if (!args.camera.empty()) {
    // Three items, each read by the one number reader (engine/number_rule.h) and its row's rule.
    std::vector<std::string> items;
    for (std::string_view rest = args.camera;;) {
      const std::size_t comma = rest.find(',');
      items.emplace_back(rest.substr(0, comma));
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    if (items.size() != 3) refuse("--camera", args.camera, "must be yaw,pitch,distance (three numbers)");
    const char* names[] = {"yaw", "pitch", "distance"};
    for (std::size_t i = 0; i < 3; ++i)
      if (const auto why = render::set_parameter(request, render::view_parameter(names[i]), items[i]))
        refuse("--camera", args.camera, std::string(names[i]) + " " + *why);
  }
  for (const render::ViewParameter& p : render::view_parameters()) {
    const std::string name(p.name);
    const auto option = args.options.find(name);
    if (option == args.options.end() || option->second->count() == 0) continue;
    const std::string& text = args.text.at(name);
    if (const auto why = render::set_parameter(request, p, text)) refuse(option_name(p), text, *why);
  }
  return request;
}

}  // namespace spinfold::cli
