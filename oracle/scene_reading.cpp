// The oracle's own reading of a scene (the scene format's fields and defaults, nlohmann-json
// directly, no engine code) and the exact isometry that moves the start to the embedding's origin.
#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "oracle/formula.h"
#include "oracle/oracle.h"
#include "oracle/scalars.h"

namespace spinfold::oracle {

// ---- reading the scene ----------------------------------------------------------------------
namespace {

using nlohmann::json;

double number(const json& j, const char* key, double fallback, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return fallback;
  if (!it->is_number()) throw std::runtime_error(path + "." + key + ": not a number");
  return it->get<double>();
}
std::optional<double> maybe(const json& j, const char* key, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return std::nullopt;
  if (!it->is_number()) throw std::runtime_error(path + "." + key + ": not a number");
  return it->get<double>();
}
const json& block(const json& j, const char* key) {
  static const json empty = json::object();
  const auto it = j.find(key);
  return it != j.end() && it->is_object() ? *it : empty;
}

}  // namespace

OracleScene read_scene(std::string_view json_text) {
  const json j = json::parse(json_text);
  OracleScene s;
  const json& surface = block(j, "surface");
  if (const auto K = maybe(surface, "curvature", "surface")) {
    if (std::abs(*K) < 1e-24) {  // the scene format's flat limit
      s.kind = Kind::plane;
      s.R = 1.0;
    } else {
      s.kind = *K > 0 ? Kind::sphere : Kind::pseudosphere;
      s.R = 1.0 / std::sqrt(std::abs(*K));
    }
  } else {
    const std::string kind = surface.value("kind", std::string("sphere"));
    if (kind == "implicit" || kind == "graph") {  // the formula, read by the oracle's own reader
      s.kind = Kind::formula;
      s.graph = kind == "graph";
      const char* key = s.graph ? "z" : "F";
      const std::string text = surface.value(key, std::string(s.graph ? "0" : "x^2 + y^2 + z^2 - 1"));
      std::map<std::string, double> parameters;
      if (const auto it = surface.find("parameters"); it != surface.end() && it->is_object())
        for (const auto& [name, value] : it->items()) parameters[name] = value.get<double>();
      std::string why;
      auto formula = OracleFormula::read(text, parameters, s.graph, &why);
      if (!formula) throw std::runtime_error(std::string("surface.") + key + ": " + why);
      s.formula = std::make_shared<const OracleFormula>(std::move(*formula));
    }
    const std::pair<const char*, Kind> kinds[] = {
        {"sphere", Kind::sphere},    {"pseudosphere", Kind::pseudosphere}, {"plane", Kind::plane},
        {"torus", Kind::torus},      {"spheroid", Kind::spheroid},         {"bump", Kind::bump},
        {"catenoid", Kind::catenoid}};
    const auto it =
        std::find_if(std::begin(kinds), std::end(kinds), [&](const auto& k) { return kind == k.first; });
    if (it != std::end(kinds))
      s.kind = it->second;
    else if (!s.formula)
      throw std::runtime_error("surface.kind: unknown '" + kind + "'");
    s.R = number(surface, "radius", 1.0, "surface");
    s.tube_radius = number(surface, "tube_radius", s.tube_radius, "surface");
    s.center_radius = number(surface, "center_radius", s.center_radius, "surface");
    s.equatorial_radius = number(surface, "equatorial_radius", s.equatorial_radius, "surface");
    s.polar_radius = number(surface, "polar_radius", s.polar_radius, "surface");
    s.bump_height = number(surface, "height", s.bump_height, "surface");
    s.bump_width = number(surface, "width", s.bump_width, "surface");
    s.neck_radius = number(surface, "neck_radius", s.neck_radius, "surface");
  }
  const json& friction = block(j, "friction");
  s.friction_t = number(friction, "translational", 0.0, "friction");
  s.friction_i = number(friction, "internal", 0.0, "friction");
  const json& body = block(j, "body");
  s.mass = number(body, "mass", 1.0, "body");
  if (const auto it = body.find("inertia"); it != body.end() && it->is_array()) {
    s.J = {(*it)[0][0].get<double>(), (*it)[0][1].get<double>(), (*it)[1][0].get<double>(),
           (*it)[1][1].get<double>()};
  } else {
    const double J = number(body, "inertia", 0.1, "body");
    s.J = {J, 0.0, 0.0, J};
  }
  const std::string model = body.value("model", std::string("affine"));
  s.model = model == "rigid"            ? Model::rigid
            : model == "incompressible" ? Model::incompressible
                                        : Model::affine;
  const json& potential = block(j, "potential");
  if (const auto it = potential.find("radial"); it != potential.end() && it->is_object()) {
    s.radial = true;
    s.g = number(*it, "gamma", 0.0, "potential.radial");
  }
  if (const auto it = potential.find("deformation"); it != potential.end() && it->is_object()) {
    const std::string kind = it->value("kind", std::string());
    if (kind == "abc") {
      s.def = DefKind::abc;
      s.A = number(*it, "A", 0, "potential.deformation");
      s.B = number(*it, "B", 0, "potential.deformation");
      s.C = number(*it, "C", 0, "potential.deformation");
    } else if (kind == "polar") {
      s.def = DefKind::polar;
      s.ghat = number(*it, "ghat", 0, "potential.deformation");
      s.gtilde = number(*it, "gtilde", 0, "potential.deformation");
      s.literal = it->value("form", std::string("cot2")) == "literal";
    } else if (!kind.empty()) {
      throw std::runtime_error("potential.deformation.kind: unknown '" + kind + "'");
    }
  }
  if (const auto it = potential.find("height"); it != potential.end() && it->is_object()) {
    const std::string kind = it->value("kind", std::string());
    if (kind == "gravity") {
      s.height = HeightKind::gravity;
      s.height_coefficient = number(*it, "g", 0, "potential.height");
    } else if (kind == "spring") {
      s.height = HeightKind::spring;
      s.height_coefficient = number(*it, "k", 0, "potential.height");
    } else {
      throw std::runtime_error("potential.height.kind: unknown '" + kind + "'");
    }
  }
  const json& q = block(j, "initial");
  const std::string p = "initial";
  s.r = number(q, "r", 1.0, p), s.phi = number(q, "phi", 0.0, p);
  s.u = number(q, "u", 0.0, p), s.u_dot = number(q, "u_dot", 0.0, p);
  s.alpha = number(q, "alpha", 0.0, p), s.beta = number(q, "beta", 0.0, p);
  s.lambda = number(q, "lambda", 1.0, p), s.mu = number(q, "mu", 1.0, p);
  s.r_dot = number(q, "r_dot", 0.0, p), s.phi_dot = number(q, "phi_dot", 0.0, p);
  s.alpha_dot = number(q, "alpha_dot", 0.0, p), s.beta_dot = number(q, "beta_dot", 0.0, p);
  s.lambda_dot = number(q, "lambda_dot", 0.0, p), s.mu_dot = number(q, "mu_dot", 0.0, p);
  s.spin = maybe(q, "spin", p), s.speed = maybe(q, "speed", p), s.heading = maybe(q, "heading", p);
  if (const auto it = q.find("X"); it != q.end() && it->is_array() && it->size() == 3)
    for (int k = 0; k < 3; ++k) s.X[k] = (*it)[k].get<double>();
  return s;
}

// ---- the start isometry ---------------------------------------------------------------------
Isometry start_isometry(const OracleScene& s) {
  const Big phi(s.phi), c = num::cos(phi), sn = num::sin(phi);
  const std::array<std::array<Big, 3>, 3> Rz{{{c, -sn, Big(0)}, {sn, c, Big(0)}, {Big(0), Big(0), Big(1)}}};
  std::array<std::array<Big, 3>, 3> T2{};
  Isometry iso;
  iso.b = {Big(0), Big(0), Big(0)};
  if (implicit_kind(s.kind)) {  // the scene's own frame
    iso.M = {{{Big(1), Big(0), Big(0)}, {Big(0), Big(1), Big(0)}, {Big(0), Big(0), Big(1)}}};
    return iso;
  }
  if (s.kind == Kind::plane) {
    iso.M = Rz;
    iso.b = {Big(s.r) * c, Big(s.r) * sn, Big(0)};
    return iso;
  }
  const Big th = Big(s.r) / Big(s.R);
  if (s.kind == Kind::sphere)
    T2 = {{{num::cos(th), Big(0), num::sin(th)},
           {Big(0), Big(1), Big(0)},
           {-num::sin(th), Big(0), num::cos(th)}}};
  else
    T2 = {{{num::cosh(th), Big(0), num::sinh(th)},
           {Big(0), Big(1), Big(0)},
           {num::sinh(th), Big(0), num::cosh(th)}}};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      Big sum = 0;
      for (int l = 0; l < 3; ++l) sum += Rz[i][l] * T2[l][k];
      iso.M[i][k] = sum;
    }
  return iso;
}

std::array<Big, 3> to_start_vector(const OracleScene& s, const Isometry& iso, const std::array<Big, 3>& v) {
  // M⁻¹ = Mᵀ (rotations), ηMᵀη (Lorentz)
  const Big eta = s.kind == Kind::pseudosphere ? Big(-1) : Big(1);
  std::array<Big, 3> w = v;
  w[2] *= eta;
  std::array<Big, 3> out;
  for (int k = 0; k < 3; ++k) out[k] = iso.M[0][k] * w[0] + iso.M[1][k] * w[1] + iso.M[2][k] * w[2];
  out[2] *= eta;
  return out;
}

std::array<Big, 3> to_start_point(const OracleScene& s, const Isometry& iso, const std::array<Big, 3>& x) {
  return to_start_vector(s, iso, {x[0] - iso.b[0], x[1] - iso.b[1], x[2] - iso.b[2]});
}

}  // namespace spinfold::oracle
