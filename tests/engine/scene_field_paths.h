// Test support: every number, text and enumerated field a scene can hold, walked through the
// tables of engine/scene_fields.h with its dotted path (engine/scene_paths.h), so that tests iterate
// the tables and cannot drift from them.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

#include "engine/scene_fields.h"
#include "engine/scene_paths.h"

namespace spinfold::testing_support {

// The walk itself is the engine's (engine/scene_paths.h), the one the sweep uses.
using spinfold::for_each_scene_field;

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

// The surface a field is tried on: the sphere when it belongs there, else the first kind it belongs
// to (Field::surfaces, as the walk narrows it).
inline SurfaceKind home_surface(unsigned surfaces) {
  if (surfaces & surface_bit(SurfaceKind::sphere)) return SurfaceKind::sphere;
  for (const EnumName<SurfaceKind>& n : kSurfaceKindNames)
    if (surfaces & surface_bit(n.value)) return n.value;
  return SurfaceKind::sphere;
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
