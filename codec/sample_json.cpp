#include "codec/sample_json.h"

#include <cmath>

#include "engine/invariants.h"
#include "engine/paper_coordinates.h"

namespace spinfold {

using json = nlohmann::ordered_json;

namespace {

// Non-finite numbers never reach a client: they become null (and cannot occur in a good state).
json number(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}
json number(const std::optional<double>& v) {
  return v ? number(*v) : json(nullptr);
}

}  // namespace

json sample_to_json(const Simulation& run, std::span<const DegenerateEvent> new_events) {
  const Scene& scene = run.scene;
  const State& state = run.state;
  const PaperCoordinates c = paper_coordinates(scene, state);
  json j;
  j["t"] = number(state.t);
  j["r"] = number(c.r);
  j["phi"] = number(c.phi);
  j["alpha"] = number(c.alpha);
  j["beta"] = number(c.beta);
  j["theta"] = number(c.theta);
  j["lambda"] = number(c.lambda);
  j["mu"] = number(c.mu);
  j["r_dot"] = number(c.r_dot);
  j["phi_dot"] = number(c.phi_dot);
  j["alpha_dot"] = number(c.alpha_dot);
  j["beta_dot"] = number(c.beta_dot);
  j["theta_dot"] = number(c.theta_dot);
  j["lambda_dot"] = number(c.lambda_dot);
  j["mu_dot"] = number(c.mu_dot);
  j["p_r"] = number(c.p_r);
  j["p_phi"] = number(c.p_phi);
  j["p_alpha"] = number(c.p_alpha);
  j["p_beta"] = number(c.p_beta);
  j["p_lambda"] = number(c.p_lambda);
  j["p_mu"] = number(c.p_mu);
  j["X"] = {number(c.X.x()), number(c.X.y()), number(c.X.z())};
  j["L"] =
      c.L ? json{{number((*c.L)(0, 0)), number((*c.L)(0, 1))}, {number((*c.L)(1, 0)), number((*c.L)(1, 1))}}
          : json(nullptr);
  j["det_L"] = number(c.det_L);

  const double H = energy(scene, state);
  j["energy"] = number(H);
  j["energy_error"] = number((H - run.initial_energy) / std::max(std::abs(run.initial_energy), 1e-300));
  j["energy_orbital"] = number(orbital_energy(scene, state));
  j["energy_deformation"] = number(deformation_energy(scene, state));
  j["spin"] = number(c.p_alpha);
  j["vorticity"] = number(c.p_beta);
  if (const auto sep = separated_energies(scene, state)) {
    j["C_x"] = number(sep->C_x);
    j["C_y"] = number(sep->C_y);
  }
  if (const auto M = momentum_map(scene, state)) {
    j["M"] = {number(M->x()), number(M->y()), number(M->z())};
    if (scene.surface.kind != SurfaceKind::plane) j["casimir"] = number(casimir(scene.surface, *M));
  }

  json undefined = json::object();
  for (const UndefinedValue& u : c.undefined) undefined[u.field] = u.reason;
  j["undefined"] = undefined;
  json events = json::array();
  for (const DegenerateEvent& e : new_events) events.push_back({{"kind", "det_L_zero"}, {"t", number(e.t)}});
  j["events"] = events;
  j["status"] = std::string(status_name(state.status));
  j["status_detail"] = std::string(status_description(state.status));
  j["integrator"] = std::string(run.info->name);
  j["steps"] = run.steps;
  return j;
}

}  // namespace spinfold
