#include "codec/scene_json.h"

#include <algorithm>
#include <sstream>

namespace spinfold {

using nlohmann::json;

namespace {

struct TooDeep {};

// Reads one JSON object into plain fields, recording every problem with its dotted path.
class Reader {
 public:
  explicit Reader(std::vector<FieldError>& errors) : errors_(errors) {}

  // True if `j` is an object whose keys are all in `allowed`; unknown keys are errors.
  bool object(const json& j, const std::string& path, std::initializer_list<std::string_view> allowed) {
    if (!j.is_object()) {
      error(path, j, "must be a JSON object");
      return false;
    }
    for (const auto& [key, value] : j.items())
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        error(join(path, key), value, "is not a known field here");
    return true;
  }

  void number(const json& obj, const std::string& path, const char* key, double& out) {
    const auto it = obj.find(key);
    if (it == obj.end()) return;
    if (it->is_number())
      out = it->get<double>();
    else
      error(join(path, key), *it, "must be a number");
  }

  void text(const json& obj, const std::string& path, const char* key, std::string& out) {
    const auto it = obj.find(key);
    if (it == obj.end()) return;
    if (it->is_string())
      out = it->get<std::string>();
    else
      error(join(path, key), *it, "must be a string");
  }

  // A string that must be one of `names`; sets `out` to the index of the match.
  template <typename Enum>
  void choice(const json& obj, const std::string& path, const char* key,
              std::initializer_list<std::pair<std::string_view, Enum>> names, Enum& out) {
    const auto it = obj.find(key);
    if (it == obj.end()) return;
    std::string allowed;
    for (const auto& [name, value] : names) {
      if (it->is_string() && it->get<std::string>() == name) {
        out = value;
        return;
      }
      allowed += (allowed.empty() ? "" : ", ") + std::string(name);
    }
    error(join(path, key), *it, "must be one of: " + allowed);
  }

  void error(const std::string& field, const json& value, const std::string& reason) {
    errors_.push_back({field, value.dump(), reason});
  }

  // Dotted path; a key that is empty or holds a dot is written quoted, so that the field named
  // is never "" (the whole document) nor ambiguous.
  static std::string join(const std::string& path, std::string_view key) {
    const std::string name =
        key.empty() || key.find('.') != std::string_view::npos ? json(std::string(key)).dump() : std::string(key);
    return path.empty() ? name : path + "." + name;
  }

 private:
  std::vector<FieldError>& errors_;
};

void read_potential(Reader& in, const json& j, Potentials& pot) {
  if (!in.object(j, "potential", {"radial", "deformation"})) return;
  if (const auto it = j.find("radial"); it != j.end()) {
    pot.radial = RadialPotential{};
    if (in.object(*it, "potential.radial", {"gamma"}))
      in.number(*it, "potential.radial", "gamma", pot.radial->gamma);
  }
  const auto it = j.find("deformation");
  if (it == j.end()) return;
  const std::string path = "potential.deformation";
  if (!it->is_object()) {
    in.error(path, *it, "must be a JSON object");
    return;
  }
  const auto kind = it->find("kind");
  const std::string name = kind != it->end() && kind->is_string() ? kind->get<std::string>() : "";
  if (name == "abc") {
    AbcPotential abc;
    if (in.object(*it, path, {"kind", "A", "B", "C"})) {
      in.number(*it, path, "A", abc.A);
      in.number(*it, path, "B", abc.B);
      in.number(*it, path, "C", abc.C);
    }
    pot.deformation = abc;
  } else if (name == "polar") {
    PolarPotential polar;
    if (in.object(*it, path, {"kind", "ghat", "gtilde", "form"})) {
      in.number(*it, path, "ghat", polar.ghat);
      in.number(*it, path, "gtilde", polar.gtilde);
      in.choice(*it, path, "form", {{"cot2", PolarForm::cot2}, {"literal", PolarForm::literal}}, polar.form);
    }
    pot.deformation = polar;
  } else {
    in.error(path + ".kind", kind != it->end() ? *kind : json(nullptr), "must be one of: abc, polar");
  }
}

void read_initial(Reader& in, const json& j, InitialState& q) {
  const std::string path = "initial";
  if (!in.object(j, path,
                 {"r", "phi", "alpha", "beta", "lambda", "mu", "r_dot", "phi_dot", "alpha_dot", "beta_dot",
                  "lambda_dot", "mu_dot"}))
    return;
  for (const auto& [key, field] : {std::pair{"r", &q.r},
                                   {"phi", &q.phi},
                                   {"alpha", &q.alpha},
                                   {"beta", &q.beta},
                                   {"lambda", &q.lambda},
                                   {"mu", &q.mu},
                                   {"r_dot", &q.r_dot},
                                   {"phi_dot", &q.phi_dot},
                                   {"alpha_dot", &q.alpha_dot},
                                   {"beta_dot", &q.beta_dot},
                                   {"lambda_dot", &q.lambda_dot},
                                   {"mu_dot", &q.mu_dot}})
    in.number(j, path, key, *field);
}

}  // namespace

SceneParse parse_scene(const json& document) {
  SceneParse result;
  Reader in(result.errors);
  Scene scene;
  if (!in.object(
          document, "",
          {"name", "description", "surface", "body", "potential", "initial", "integrator", "on_degenerate"}))
    return result;
  in.text(document, "", "name", scene.name);
  in.text(document, "", "description", scene.description);
  if (const auto it = document.find("surface");
      it != document.end() && in.object(*it, "surface", {"kind", "radius"})) {
    in.choice(*it, "surface", "kind",
              {{"sphere", SurfaceKind::sphere},
               {"pseudosphere", SurfaceKind::pseudosphere},
               {"plane", SurfaceKind::plane}},
              scene.surface.kind);
    in.number(*it, "surface", "radius", scene.surface.radius);
  }
  if (const auto it = document.find("body");
      it != document.end() && in.object(*it, "body", {"mass", "inertia", "model"})) {
    in.number(*it, "body", "mass", scene.body.mass);
    in.number(*it, "body", "inertia", scene.body.inertia);
    in.choice(*it, "body", "model", {{"affine", BodyModel::affine}, {"rigid", BodyModel::rigid}},
              scene.body.model);
  }
  if (const auto it = document.find("potential"); it != document.end())
    read_potential(in, *it, scene.potential);
  if (const auto it = document.find("initial"); it != document.end()) read_initial(in, *it, scene.initial);
  if (const auto it = document.find("integrator");
      it != document.end() && in.object(*it, "integrator", {"name", "dt", "tolerance"})) {
    in.text(*it, "integrator", "name", scene.integrator.name);
    in.number(*it, "integrator", "dt", scene.integrator.dt);
    in.number(*it, "integrator", "tolerance", scene.integrator.tolerance);
  }
  in.choice(document, "", "on_degenerate", {{"report", OnDegenerate::report}, {"stop", OnDegenerate::stop}},
            scene.on_degenerate);

  // Report value errors too, except for fields whose structure was already wrong.
  for (FieldError& e : validate_scene(scene)) {
    const bool known = std::any_of(result.errors.begin(), result.errors.end(),
                                   [&](const FieldError& s) { return s.field == e.field; });
    if (!known) result.errors.push_back(std::move(e));
  }
  if (result.errors.empty()) result.scene = scene;
  return result;
}

SceneParse parse_scene_text(std::string_view text) {
  SceneParse result;
  try {
    const json::parser_callback_t depth_guard = [](int depth, json::parse_event_t, json&) {
      if (depth > kMaxJsonDepth) throw TooDeep{};
      return true;
    };
    return parse_scene(json::parse(text, depth_guard));
  } catch (const TooDeep&) {
    result.errors.push_back({"", "", "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels"});
  } catch (const json::exception& e) {
    result.errors.push_back({"", "", std::string("malformed JSON: ") + e.what()});
  }
  return result;
}

json scene_to_json(const Scene& scene) {
  const auto surface_kind = [](SurfaceKind k) {
    return k == SurfaceKind::sphere ? "sphere" : k == SurfaceKind::pseudosphere ? "pseudosphere" : "plane";
  };
  json j;
  if (!scene.name.empty()) j["name"] = scene.name;
  if (!scene.description.empty()) j["description"] = scene.description;
  j["surface"] = {{"kind", surface_kind(scene.surface.kind)}, {"radius", scene.surface.radius}};
  j["body"] = {{"mass", scene.body.mass},
               {"inertia", scene.body.inertia},
               {"model", scene.body.model == BodyModel::rigid ? "rigid" : "affine"}};
  json pot = json::object();
  if (scene.potential.radial) pot["radial"] = {{"gamma", scene.potential.radial->gamma}};
  if (const auto* abc = std::get_if<AbcPotential>(&scene.potential.deformation))
    pot["deformation"] = {{"kind", "abc"}, {"A", abc->A}, {"B", abc->B}, {"C", abc->C}};
  if (const auto* polar = std::get_if<PolarPotential>(&scene.potential.deformation))
    pot["deformation"] = {{"kind", "polar"},
                          {"ghat", polar->ghat},
                          {"gtilde", polar->gtilde},
                          {"form", polar->form == PolarForm::literal ? "literal" : "cot2"}};
  j["potential"] = pot;
  const InitialState& q = scene.initial;
  j["initial"] = {{"r", q.r},
                  {"phi", q.phi},
                  {"alpha", q.alpha},
                  {"beta", q.beta},
                  {"lambda", q.lambda},
                  {"mu", q.mu},
                  {"r_dot", q.r_dot},
                  {"phi_dot", q.phi_dot},
                  {"alpha_dot", q.alpha_dot},
                  {"beta_dot", q.beta_dot},
                  {"lambda_dot", q.lambda_dot},
                  {"mu_dot", q.mu_dot}};
  j["integrator"] = {{"name", scene.integrator.name},
                     {"dt", scene.integrator.dt},
                     {"tolerance", scene.integrator.tolerance}};
  j["on_degenerate"] = scene.on_degenerate == OnDegenerate::stop ? "stop" : "report";
  return j;
}

std::string describe_errors(const std::vector<FieldError>& errors) {
  std::ostringstream out;
  for (const FieldError& e : errors) {
    out << (e.field.empty() ? "scene" : e.field) << ": " << e.reason;
    if (!e.value.empty()) out << " (got " << e.value << ")";
    out << "\n";
  }
  return out.str();
}

}  // namespace spinfold
