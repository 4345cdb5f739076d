#include "engine/formula_surface.h"

#include <list>
#include <mutex>
#include <stdexcept>
#include <utility>

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

FormulaSurfaceForm formula_form(const Surface& surface) {
  if (!offers(surface, Offer::formula)) throw std::logic_error("formula_form: not a formula surface");
  return surface.kind == SurfaceKind::graph ? FormulaSurfaceForm::graph : FormulaSurfaceForm::implicit;
}

const std::string& formula_text(const Surface& surface) {
  return formula_form(surface) == FormulaSurfaceForm::graph ? surface.z : surface.F;
}

std::string_view formula_key(const Surface& surface) {
  return formula_form(surface) == FormulaSurfaceForm::graph ? "z" : "F";
}

FormulaSurfaceParse parse_scene_formula(const Surface& surface) {
  return parse_formula_surface(formula_form(surface), formula_text(surface), surface.parameters);
}

std::shared_ptr<const FormulaSurface> formula_surface_of(const Surface& surface) {
  struct Entry {
    FormulaSurfaceForm form;
    std::string text;
    SurfaceParameters parameters;
    std::shared_ptr<const FormulaSurface> value;
  };
  static std::mutex mutex;
  static std::list<Entry> cache;  // most recently used first
  const FormulaSurfaceForm form = formula_form(surface);
  const std::string& text = formula_text(surface);
  {
    const std::lock_guard lock(mutex);
    for (auto it = cache.begin(); it != cache.end(); ++it)
      if (it->form == form && it->text == text && it->parameters == surface.parameters) {
        cache.splice(cache.begin(), cache, it);
        return cache.front().value;
      }
  }
  FormulaSurfaceParse parsed = parse_formula_surface(form, text, surface.parameters);
  if (!parsed.surface)
    throw std::invalid_argument("surface." + std::string(formula_key(surface)) + ": " + parsed.error.reason);
  auto value = std::make_shared<const FormulaSurface>(std::move(*parsed.surface));
  const std::lock_guard lock(mutex);
  cache.push_front({form, text, surface.parameters, value});
  if (cache.size() > kFormulaSurfaceCacheSize) cache.pop_back();
  return value;
}

}  // namespace spinfold
