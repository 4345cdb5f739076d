// A surface given by a formula (physics-anysurface.md §1): F(x, y, z) = 0, or a graph z = f(x, y)
// read as F = z − f (so that its normal points up). It is an ImplicitSurface: the chart-free
// equations (embedded_dynamics.h) run on it as they are, with F, ∇F and Hess F exact from the
// formula's jet (formula.h).
#pragma once

#include <memory>
#include <optional>
#include <string_view>

#include "engine/formula.h"
#include "engine/revolution.h"
#include "engine/surface.h"

namespace spinfold {

enum class FormulaSurfaceForm {
  implicit,  // F(x, y, z) = 0, n = ∇F/|∇F|
  graph,     // z = f(x, y): F = z − f, ∇F = (−f_x, −f_y, 1) never vanishes
};

class FormulaSurface final : public ImplicitSurface {
 public:
  FormulaSurface(Formula formula, FormulaSurfaceForm form) : formula_(std::move(formula)), form_(form) {}

  // F, ∇F and Hess F at X (for a graph: z − f(x, y) and its derivatives).
  ImplicitPoint at(const Vec3& X) const override;
  // F alone at X (a mesher's many evaluations).
  double value(const Vec3& X) const;
  // A graph's height f(x, y) [length]; std::logic_error on an implicit surface.
  double height(double x, double y) const;

  FormulaSurfaceForm form() const { return form_; }
  const Formula& formula() const { return formula_; }

 private:
  Formula formula_;
  FormulaSurfaceForm form_;
};

struct FormulaSurfaceParse {
  std::optional<FormulaSurface> surface;
  FormulaError error;  // meaningful when surface is empty
};

// The surface of a formula in the form's variables (x, y, z; a graph's x, y), with these
// parameters; refused as parse_formula refuses.
FormulaSurfaceParse parse_formula_surface(FormulaSurfaceForm form, std::string_view text,
                                          const FormulaParameters& parameters = {});

// The scene's formula surface (surface.kind implicit or graph): its form, and the text it reads
// (surface.F or surface.z) with the scene's key for it.
FormulaSurfaceForm formula_form(const Surface& surface);
const std::string& formula_text(const Surface& surface);
std::string_view formula_key(const Surface& surface);  // "F" or "z"

// The scene's surface parsed, or why not (the validator's message).
FormulaSurfaceParse parse_scene_formula(const Surface& surface);

// The scene's surface parsed once per (form, text, parameters) and shared: runs, read-outs and
// pictures of one scene ask it many times. A cache of at most kFormulaSurfaceCacheSize entries,
// thread-safe. std::invalid_argument for a formula the validator refuses (it names why first).
inline constexpr std::size_t kFormulaSurfaceCacheSize = 64;
std::shared_ptr<const FormulaSurface> formula_surface_of(const Surface& surface);

}  // namespace spinfold
