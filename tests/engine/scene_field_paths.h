// Test support: every number, text and enumerated field a scene can hold, walked through the
// tables of engine/scene_fields.h with its dotted path, so that tests iterate the tables and
// cannot drift from them.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

#include "engine/scene_fields.h"

namespace spinfold::testing_support {

template <typename S, typename Place, typename Fn>
void walk_fields(const std::string& path, std::string_view kind, Place place, Fn& fn) {
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    const std::string name = path.empty() ? std::string(field.name) : path + "." + std::string(field.name);
    const auto member = field.member;
    auto here = [place, member](Scene& s) -> T& { return place(s).*member; };
    if constexpr (std::is_same_v<T, double> || OptionalNumber<T> || std::is_same_v<T, std::string> ||
                  Enumerated<T>) {
      fn(name, kind, field, here);
    } else if constexpr (HasFields<T>) {
      walk_fields<T>(name, kind, here, fn);
    } else if constexpr (OptionalSection<T>) {
      using U = typename T::value_type;
      walk_fields<U>(
          name, kind,
          [here](Scene& s) -> U& {
            T& slot = here(s);
            if (!slot) slot.emplace();
            return *slot;
          },
          fn);
    } else {
      static_assert(std::is_same_v<T, DeformationPotential>);
      for_each_deformation_kind([&](auto index, auto alternative) {
        using A = typename decltype(alternative)::type;
        walk_fields<A>(
            name, kDeformationKindNames[index],
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

// Calls fn(path, kind, field, place) for every leaf field of a scene: `path` as in the scene JSON
// ("initial.r"), `kind` the deformation kind it belongs to ("" outside a deformation), `field` its
// table entry, and place(Scene&) the field's value in a scene, made present first (the optional
// radial potential, the deformation of that kind).
template <typename Fn>
void for_each_scene_field(Fn&& fn) {
  walk_fields<Scene>(
      "", "", [](Scene& s) -> Scene& { return s; }, fn);
}

// A number other than the field's default and allowed by its range (alone).
template <typename S>
double other_number(const Field<S, double>& field) {
  const Range& r = field.range;
  if (r.has_min() && r.has_max()) return (r.min + r.max) / 2;
  return field.fallback() * 1.5 + 0.25;
}
// An optional number: one allowed by its range (it has no default).
template <typename S>
double other_number(const Field<S, std::optional<double>>& field) {
  const Range& r = field.range;
  if (r.has_min() && r.has_max()) return (r.min + r.max) / 2;
  return r.has_min() ? r.min + 0.25 : 0.25;
}

// Sets the partner of an optional number (speed for heading) in `scene.initial`, the struct that
// holds them, to `value`; nothing for a field without one (surface.curvature).
template <typename S>
void set_partner(Scene& scene, const Field<S, std::optional<double>>& field, double value) {
  if constexpr (!std::is_same_v<S, InitialState>) {
    EXPECT_TRUE(field.partner.empty()) << field.name << ": partners are looked up in InitialState only";
    return;
  } else {
    for_each_field(kInitialStateFields, [&](const auto& other) {
      using U = typename std::remove_cvref_t<decltype(other)>::Value;
      if constexpr (OptionalNumber<U>)
        if (!field.partner.empty() && other.name == field.partner) scene.initial.*other.member = value;
    });
  }
}

}  // namespace spinfold::testing_support
