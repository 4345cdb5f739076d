// The surfaces by formula that Spinfold offers as examples (the page's menu beside the formula field,
// the schema's x-examples, the presets on them, and the tests that run over every one): each a
// formula with its parameters and the point a body starts from. One table (formula_examples.cpp).
#pragma once

#include <array>
#include <span>
#include <string_view>
#include <utility>

#include "engine/surface.h"

namespace spinfold {

struct FormulaExample {
  std::string_view name;                                          // a key ("triaxial_ellipsoid")
  std::string_view title;                                         // a menu's words ("triaxial ellipsoid")
  SurfaceKind kind;                                               // implicit (F) or graph (z)
  std::string_view formula;                                       // F(x, y, z) or f(x, y)
  std::array<std::pair<std::string_view, double>, 4> parameters;  // the first `count` are used
  int count;
  std::array<double, 3> start;  // initial.X [length]
  std::string_view note;        // what the surface shows, one line
};

std::span<const FormulaExample> formula_examples();
// The example's surface (kind, F or z, parameters; no bounds: the shape chooses its box).
Surface example_surface(const FormulaExample& example);

}  // namespace spinfold
