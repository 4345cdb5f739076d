#include "engine/formula_surface.h"

#include <stdexcept>

namespace spinfold {

ImplicitPoint FormulaSurface::at(const Vec3& X) const {
  const FormulaJet f = formula_.jet(X);
  if (form_ == FormulaSurfaceForm::implicit) return {f.value, f.gradient, f.hessian};
  // F = z − f(x, y): ∇F = ẑ − ∇f, Hess F = −Hess f (f does not depend on z).
  ImplicitPoint p;
  p.F = X.z() - f.value;
  p.gradient = Vec3(-f.gradient.x(), -f.gradient.y(), 1.0);
  p.hessian = -f.hessian;
  return p;
}

double FormulaSurface::value(const Vec3& X) const {
  const double f = formula_.value(X);
  return form_ == FormulaSurfaceForm::implicit ? f : X.z() - f;
}

double FormulaSurface::height(double x, double y) const {
  if (form_ != FormulaSurfaceForm::graph) throw std::logic_error("FormulaSurface::height: not a graph");
  return formula_.value(Vec3(x, y, 0.0));
}

FormulaSurfaceParse parse_formula_surface(FormulaSurfaceForm form, std::string_view text,
                                          const FormulaParameters& parameters) {
  FormulaParse parsed = parse_formula(
      text, parameters, form == FormulaSurfaceForm::graph ? FormulaVariables::xy : FormulaVariables::xyz);
  if (!parsed.formula) return {std::nullopt, parsed.error};
  return {FormulaSurface(std::move(*parsed.formula), form), {}};
}

}  // namespace spinfold
