#include "codec/scene_schema.h"

#include "engine/integrator.h"
#include "engine/scene.h"

namespace spinfold {

using json = nlohmann::ordered_json;

namespace {

json number(double fallback, const char* description, const char* unit) {
  return {{"type", "number"}, {"default", fallback}, {"description", description}, {"x-unit", unit}};
}

json positive(double fallback, const char* description, const char* unit) {
  json n = number(fallback, description, unit);
  n["exclusiveMinimum"] = 0;
  return n;
}

json object(json properties, std::vector<std::string> required = {}) {
  json o{{"type", "object"}, {"additionalProperties", false}, {"properties", std::move(properties)}};
  if (!required.empty()) o["required"] = required;
  return o;
}

}  // namespace

json scene_schema() {
  const Scene d;  // the documented defaults
  const InitialState& q = d.initial;
  json integrators = json::array({std::string(kAutoIntegrator)});
  for (const CatalogEntry& e : integrator_catalog()) integrators.push_back(std::string(e.info.name));

  json initial = object({
      {"r",
       [&] {
         json n = number(q.r, "geodesic distance from the pole (<= pi R on the sphere)", "length");
         n["minimum"] = 0;
         return n;
       }()},
      {"phi", number(q.phi, "polar angle", "rad")},
      {"alpha", number(q.alpha, "left rotation angle of L = U(alpha) diag(lambda, mu) U(beta)^T", "rad")},
      {"beta", number(q.beta, "right rotation angle", "rad")},
      {"lambda", positive(q.lambda, "first stretch (the rigid body's scale)", "1")},
      {"mu", positive(q.mu, "second stretch (= lambda for a rigid body)", "1")},
      {"r_dot", number(q.r_dot, "rate of r", "length/time")},
      {"phi_dot", number(q.phi_dot, "rate of phi", "rad/time")},
      {"alpha_dot", number(q.alpha_dot, "rate of alpha", "rad/time")},
      {"beta_dot", number(q.beta_dot, "rate of beta", "rad/time")},
      {"lambda_dot", number(q.lambda_dot, "rate of lambda (0 for a rigid body)", "1/time")},
      {"mu_dot", number(q.mu_dot, "rate of mu (0 for a rigid body)", "1/time")},
  });
  json abc = object({{"kind", {{"const", "abc"}}},
                     {"A",
                      [] {
                        json n = number(0, "A/x^2 barrier at lambda = mu", "energy");
                        n["minimum"] = 0;
                        return n;
                      }()},
                     {"B",
                      [] {
                        json n = number(0, "B/y^2 barrier at lambda = -mu", "energy");
                        n["minimum"] = 0;
                        return n;
                      }()},
                     {"C", number(0, "isotonic C (x^2 + y^2)", "energy")}},
                    {"kind"});
  json polar = object({{"kind", {{"const", "polar"}}},
                       {"ghat", number(0, "angular coefficient g-hat of W(epsilon)", "energy")},
                       {"gtilde", number(0, "radial coefficient g-tilde / varsigma", "energy")},
                       {"form", {{"enum", {"cot2", "literal"}}, {"default", "cot2"}}}},
                      {"kind"});
  json schema{
      {"$schema", "https://json-schema.org/draft/2020-12/schema"},
      {"title", "Spinfold scene"},
      {"description", "An affinely-rigid body on a surface of constant curvature (docs/physics.md)."},
  };
  json top = object({
      {"name", {{"type", "string"}}},
      {"description", {{"type", "string"}}},
      {"surface", object({{"kind", {{"enum", {"sphere", "pseudosphere", "plane"}}, {"default", "sphere"}}},
                          {"radius", positive(d.surface.radius, "R (the plane's length scale)", "length")}})},
      {"body", object({{"mass", positive(d.body.mass, "m", "mass")},
                       {"inertia", positive(d.body.inertia, "J (isotropic)", "mass length^2")},
                       {"model", {{"enum", {"affine", "rigid"}}, {"default", "affine"}}}})},
      {"potential",
       object({{"radial",
                object({{"gamma",
                         [] {
                           json n = number(
                               0, "g: V_r = g/sin^2(r/R) (S2), g/(R^2 sinh^2(r/R)) (H2), g/r^2 (plane)",
                               "energy");
                           n["minimum"] = 0;
                           return n;
                         }()}})},
               {"deformation", {{"oneOf", {abc, polar}}}}})},
      {"initial", initial},
      {"integrator",
       object({{"name", {{"enum", integrators}, {"default", d.integrator.name}}},
               {"dt", positive(d.integrator.dt, "step (fixed-step) or first trial step", "time")},
               {"tolerance",
                [&] {
                  json n = number(d.integrator.tolerance, "error per step (adaptive)", "1");
                  n["minimum"] = 1e-15;
                  n["maximum"] = 1e-2;
                  return n;
                }()}})},
      {"on_degenerate", {{"enum", {"report", "stop"}}, {"default", "report"}}},
  });
  for (auto& [key, value] : top.items()) schema[key] = value;
  return schema;
}

}  // namespace spinfold
