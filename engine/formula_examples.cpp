#include "engine/formula_examples.h"

#include <string>

#include "engine/formula_surface.h"

namespace spinfold {

namespace {

constexpr FormulaExample kExamples[] = {
    {"triaxial_ellipsoid",
     "triaxial ellipsoid",
     SurfaceKind::implicit,
     "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1",
     {{{"a", 2.0}, {"b", 1.4}, {"c", 0.9}, {}}},
     3,
     {0.3, 1.2, 0.5},
     "no symmetry: without spin a body keeps Joachimsthal's integral, with spin it does not"},
    {"monkey_saddle",
     "monkey saddle",
     SurfaceKind::graph,
     "x^3 - 3*x*y^2",
     {},
     0,
     {0.4, 0.2, 0.0},
     "K < 0 everywhere but at the flat centre: spin bends the path by K s/(m v)"},
    {"egg_crate",
     "egg crate",
     SurfaceKind::graph,
     "a*sin(x/b)*sin(y/b)",
     {{{"a", 0.4}, {"b", 1.0}, {}, {}}},
     2,
     {-2.5, 0.3, 0.0},
     "K > 0 on the crests and hollows, K < 0 between: the spin's bend changes side"},
    {"two_bumps",
     "two bumps",
     SurfaceKind::graph,
     "h*exp(-((x - d)^2 + y^2)/(2*w^2)) + h*exp(-((x + d)^2 + y^2)/(2*w^2))",
     {{{"h", 0.8}, {"d", 1.2}, {"w", 0.6}, {}}},
     3,
     {-1.9, -1.0, 0.0},
     "two Gaussian bumps side by side: a spinning body can be caught by one and not the other"},
    {"genus_two",
     "genus-2 surface",
     SurfaceKind::implicit,
     "((x^2 + y^2)^2 - 2*a^2*(x^2 - y^2))^2 + (z/c)^2 - r^2",
     {{{"a", 1.0}, {"c", 0.5}, {"r", 0.6}, {}}},
     3,
     {1.2, 0.3, 0.2},
     "a closed surface with two holes, of curvature both signs"},
};

}  // namespace

std::span<const FormulaExample> formula_examples() {
  return kExamples;
}

Surface example_surface(const FormulaExample& example) {
  Surface s;
  s.kind = example.kind;
  (formula_form(s) == FormulaSurfaceForm::graph ? s.z : s.F) = std::string(example.formula);
  for (int i = 0; i < example.count; ++i)
    s.parameters[std::string(example.parameters[i].first)] = example.parameters[i].second;
  return s;
}

}  // namespace spinfold
