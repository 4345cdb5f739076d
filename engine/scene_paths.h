// The scene's fields by their dotted paths ("initial.r", "potential.deformation.A"), walked through
// the tables of engine/scene_fields.h: the one walk the sweep (sweep/grid.h) and the tests use, so
// that nothing lists the fields by hand.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "engine/scene_fields.h"

namespace spinfold {

namespace detail {

// `surfaces`: the surface kinds the enclosing sections belong to; a leaf is given with its own
// Field::surfaces narrowed to them (potential.height.g belongs where potential.height does).
template <typename S, typename Place, typename Fn>
void walk_fields(const std::string& path, std::string_view kind, unsigned surfaces, Place place, Fn& fn) {
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& table_field) {
    using T = typename std::remove_cvref_t<decltype(table_field)>::Value;
    auto field = table_field;
    field.surfaces &= surfaces;
    const std::string name = path.empty() ? std::string(field.name) : path + "." + std::string(field.name);
    const auto member = field.member;
    auto here = [place, member](Scene& s) -> T& { return place(s).*member; };
    if constexpr (std::is_same_v<T, double> || OptionalNumber<T> || std::is_same_v<T, std::string> ||
                  Enumerated<T>) {
      fn(name, kind, field, here);
    } else if constexpr (Point3<T> || NamedNumbers<T> || OptionalBox<T>) {
      // not one leaf: a formula's parameters are paths of their own (find_scene_path)
    } else if constexpr (HasFields<T>) {
      walk_fields<T>(name, kind, field.surfaces, here, fn);
    } else if constexpr (OptionalSection<T>) {
      using U = typename T::value_type;
      walk_fields<U>(
          name, kind, field.surfaces,
          [here](Scene& s) -> U& {
            T& slot = here(s);
            if (!slot) slot.emplace();
            return *slot;
          },
          fn);
    } else {
      static_assert(KindVariant<T>);
      for_each_kind<T>([&](auto index, auto alternative) {
        using A = typename decltype(alternative)::type;
        walk_fields<A>(
            name, kind_names(std::type_identity<T>{})[index], field.surfaces,
            [here](Scene& s) -> A& {
              T& slot = here(s);
              if (!std::holds_alternative<A>(slot)) slot = A{};
              return std::get<A>(slot);
            },
            fn);
      });
    }
  });
}

}  // namespace detail

// Calls fn(path, kind, field, place) for every leaf field of a scene: `path` as in the scene JSON
// ("initial.r"), `kind` the kind of the section chosen by kind it belongs to ("abc", "gravity"; ""
// outside one), `field` its table entry (its `surfaces` narrowed to the sections it is in), and place(Scene&)
// the field's value in a scene, made present first (the optional radial potential, the deformation or height
// potential of that kind).
template <typename Fn>
void for_each_scene_field(Fn&& fn) {
  detail::walk_fields<Scene>(
      "", "", ~0u, [](Scene& s) -> Scene& { return s; }, fn);
}

// A leaf of the scene by its path, as a value can be set at it: a number (its range) or a text (its
// names: an enumeration's, the integrators', the deformation kinds'; none: free text).
struct ScenePath {
  enum class Leaf { number, text };
  std::string path;
  Leaf leaf = Leaf::number;
  Range range{};
  std::vector<std::string> names;
  unsigned surfaces = ~0u;  // the surface kinds it belongs to (bits of surface_bit)
};

// Every path, each once, in table order, with the deformation's "kind" before its coefficients.
const std::vector<ScenePath>& scene_paths();
// The path's leaf, or nullptr. A formula's parameter, surface.parameters.NAME (NAME a valid
// parameter name, engine/formula.h), is a number leaf on the formula surfaces.
inline constexpr std::string_view kParametersPath = "surface.parameters.";
const ScenePath* find_scene_path(std::string_view path);

}  // namespace spinfold
