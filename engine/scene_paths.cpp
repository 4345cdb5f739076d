#include "engine/scene_paths.h"

#include <algorithm>
#include <deque>
#include <mutex>

#include "engine/formula.h"

namespace spinfold {

const std::vector<ScenePath>& scene_paths() {
  static const std::vector<ScenePath> paths = [] {
    std::vector<ScenePath> out;
    const auto add = [&](ScenePath p) {
      // Two kinds of one section may share a coefficient name: each path once.
      if (std::none_of(out.begin(), out.end(), [&](const ScenePath& o) { return o.path == p.path; }))
        out.push_back(std::move(p));
    };
    for_each_scene_field([&](const std::string& path, std::string_view kind, const auto& field, auto) {
      using T = typename std::remove_cvref_t<decltype(field)>::Value;
      if (!kind.empty()) {  // the section's kind, a text of its own, before its first coefficient
        ScenePath k{path.substr(0, path.rfind('.')) + ".kind", ScenePath::Leaf::text, {}, {}, field.surfaces};
        for (std::string_view n : kind_family(kind))
          if (!n.empty()) k.names.emplace_back(n);
        add(std::move(k));
      }
      if constexpr (std::is_same_v<T, double> || OptionalNumber<T>) {
        add({path, ScenePath::Leaf::number, field.range, {}, field.surfaces});
      } else if constexpr (Enumerated<T>) {
        ScenePath p{path, ScenePath::Leaf::text, {}, {}, field.surfaces};
        for (const auto& n : enum_names(std::type_identity<T>{})) p.names.emplace_back(n.name);
        add(std::move(p));
      } else {
        ScenePath p{path, ScenePath::Leaf::text, {}, {}, field.surfaces};
        if (field.text_rule == TextRule::integrator_name)
          for (std::string_view n : integrator_names()) p.names.emplace_back(n);
        add(std::move(p));
      }
    });
    return out;
  }();
  return paths;
}

const ScenePath* find_scene_path(std::string_view path) {
  for (const ScenePath& p : scene_paths())
    if (p.path == path) return &p;
  if (!path.starts_with(kParametersPath) || parameter_name_problem(path.substr(kParametersPath.size())))
    return nullptr;
  // The parameters' paths, made as they are asked for and kept (a deque keeps its elements' places).
  static std::mutex mutex;
  static std::deque<ScenePath> parameters;
  const std::lock_guard lock(mutex);
  for (const ScenePath& p : parameters)
    if (p.path == path) return &p;
  return &parameters.emplace_back(ScenePath{
      std::string(path), ScenePath::Leaf::number, kAnyNumber, {}, surfaces_offering(Offer::formula)});
}

}  // namespace spinfold
