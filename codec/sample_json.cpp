#include "codec/sample_json.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

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

json sample_to_json(const Simulation& run, double events_since) {
  json j = sample_to_json(readout(run), events_after(run, events_since));
  if (run.companions.empty()) return j;
  json companions = json::array();
  for (std::size_t i = 0; i < run.companions.size(); ++i) {
    const Simulation& c = run.companions[i];
    json sample = {{"label", companion_label(run.scene, i)}};
    sample.update(sample_to_json(readout(c), events_after(c, events_since)));
    companions.push_back(std::move(sample));
  }
  j["companions"] = std::move(companions);
  return j;
}

json sample_to_json(const Readout& r, std::span<const DegenerateEvent> new_events) {
  const PaperCoordinates& c = r.coordinates;
  json j;
  // Where the curvature varies the chart is (u, φ): u, u_dot and p_u stand where r, r_dot and p_r
  // stand elsewhere, and K follows det_L.
  // On a formula surface (r.embedded) there is no chart: no r or u, and the body in ℝ³ follows X.
  const bool free = r.embedded.has_value();
  const bool profile = r.curvature.has_value() && !free;
  j["t"] = number(r.t);
  if (!free) j[profile ? "u" : "r"] = number(c.r);
  j["phi"] = number(c.phi);
  j["alpha"] = number(c.alpha);
  j["beta"] = number(c.beta);
  j["theta"] = number(c.theta);
  j["lambda"] = number(c.lambda);
  j["mu"] = number(c.mu);
  if (!free) j[profile ? "u_dot" : "r_dot"] = number(c.r_dot);
  j["phi_dot"] = number(c.phi_dot);
  j["alpha_dot"] = number(c.alpha_dot);
  j["beta_dot"] = number(c.beta_dot);
  j["theta_dot"] = number(c.theta_dot);
  j["lambda_dot"] = number(c.lambda_dot);
  j["mu_dot"] = number(c.mu_dot);
  if (!free) j[profile ? "p_u" : "p_r"] = number(c.p_r);
  // p_φ far out on H² is computed but has lost its digits: null, with the reason under undefined.
  const bool p_phi_lost = std::any_of(c.undefined.begin(), c.undefined.end(),
                                      [](const UndefinedValue& u) { return u.field == "p_phi"; });
  j["p_phi"] = p_phi_lost ? json(nullptr) : number(c.p_phi);
  j["p_alpha"] = number(c.p_alpha);
  j["p_beta"] = number(c.p_beta);
  j["p_lambda"] = number(c.p_lambda);
  j["p_mu"] = number(c.p_mu);
  const auto vector = [](const Vec3& v) { return json{number(v.x()), number(v.y()), number(v.z())}; };
  j["X"] = vector(c.X);
  if (free) {
    j["V"] = vector(r.embedded->V);
    j["e1"] = vector(r.embedded->e1);
    j["e2"] = vector(r.embedded->e2);
    j["n"] = vector(r.embedded->n);
  }
  j["L"] =
      c.L ? json{{number((*c.L)(0, 0)), number((*c.L)(0, 1))}, {number((*c.L)(1, 0)), number((*c.L)(1, 1))}}
          : json(nullptr);
  j["det_L"] = number(r.det_L);
  if (r.curvature) j["K"] = number(*r.curvature);
  if (free) j["constraint_drift"] = number(r.embedded->drift);

  j["energy"] = number(r.energy);
  j["energy_error"] = number(r.energy_error);
  j["energy_reference_t"] = number(r.energy_reference_t);
  j["energy_orbital"] = number(r.energy_orbital);
  j["energy_deformation"] = number(r.energy_deformation);
  j["spin"] = number(r.spin);
  j["speed"] = number(r.speed);
  j["heading"] = number(r.heading);
  j["vorticity"] = number(r.vorticity);
  if (r.separated) {
    j["C_x"] = number(r.separated->C_x);
    j["C_y"] = number(r.separated->C_y);
  }
  if (r.momentum_map) {
    const Vec3& M = *r.momentum_map;
    j["M"] = {number(M.x()), number(M.y()), number(M.z())};
  } else if (!r.undefined.empty() && r.casimir) {
    j["M"] = nullptr;  // computed but lost its digits: the reason is under undefined
  }
  if (r.casimir) j["casimir"] = number(*r.casimir);

  // Action variables J = ∮p dq and frequencies ν = ∂E/∂J [1/time] (engine/actions.h): null where
  // undefined, with the reason under undefined ("actions.J_r", "frequencies.r", or "actions").
  if (r.actions) {
    const ActionVariables& a = *r.actions;
    j["actions"] = {{"J_r", number(a.J_r)},       {"J_phi", number(a.J_phi)}, {"J_alpha", number(a.J_alpha)},
                    {"J_beta", number(a.J_beta)}, {"J_x", number(a.J_x)},     {"J_y", number(a.J_y)}};
    j["frequencies"] = {
        {"r", number(a.nu_r)}, {"phi", number(a.nu_phi)}, {"x", number(a.nu_x)}, {"y", number(a.nu_y)}};
  } else {
    j["actions"] = nullptr;
    j["frequencies"] = nullptr;
  }
  json undefined = json::object();
  for (const auto& [field, reason] : undefined_values(r)) undefined[field] = reason;
  j["undefined"] = undefined;
  json events = json::array();
  for (const DegenerateEvent& e : new_events) events.push_back({{"kind", "det_L_zero"}, {"t", number(e.t)}});
  j["events"] = events;
  j["status"] = std::string(r.status_name);
  j["status_detail"] = std::string(r.status_detail);
  j["integrator"] = std::string(r.integrator);
  j["steps"] = r.steps;
  return j;
}

std::vector<std::pair<std::string, std::string>> undefined_values(const Readout& r) {
  std::vector<std::pair<std::string, std::string>> out;
  for_each_undefined(r, [&](std::string_view prefix, std::string_view field, std::string_view reason) {
    out.emplace_back(std::string(prefix).append(field), std::string(reason));
  });
  return out;
}

void sample_values(const Readout& r, std::span<double> out) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const auto finite = [](double v) { return std::isfinite(v) ? v : nan; };
  const auto optional = [&](const std::optional<double>& v) { return v ? finite(*v) : nan; };
  const PaperCoordinates& c = r.coordinates;
  const bool p_phi_lost = std::any_of(c.undefined.begin(), c.undefined.end(),
                                      [](const UndefinedValue& u) { return u.field == "p_phi"; });
  const ActionVariables* a = r.actions ? &*r.actions : nullptr;
  const bool free = r.embedded.has_value();               // no chart: X, V, e₁, e₂, n at the end
  const bool profile = r.curvature.has_value() && !free;  // (u, φ): u, u̇, p_u in the last columns
  const auto chart = [&](bool polar, const std::optional<double>& v) {
    return !free && polar == !profile ? optional(v) : nan;
  };
  const auto embedded = [&](const Vec3 Readout::Embedded::*member, int i) {
    return free ? finite((*r.embedded.*member)[i]) : nan;
  };
  // In the order of sample_value_names(); a test holds the two to the same names and numbers.
  const double values[] = {
      finite(r.t),
      chart(true, c.r),
      optional(c.phi),
      optional(c.alpha),
      optional(c.beta),
      optional(c.theta),
      optional(c.lambda),
      optional(c.mu),
      chart(true, c.r_dot),
      optional(c.phi_dot),
      optional(c.alpha_dot),
      optional(c.beta_dot),
      optional(c.theta_dot),
      optional(c.lambda_dot),
      optional(c.mu_dot),
      chart(true, c.p_r),
      p_phi_lost ? nan : optional(c.p_phi),
      optional(c.p_alpha),
      optional(c.p_beta),
      optional(c.p_lambda),
      optional(c.p_mu),
      finite(c.X.x()),
      finite(c.X.y()),
      finite(c.X.z()),
      c.L ? finite((*c.L)(0, 0)) : nan,
      c.L ? finite((*c.L)(0, 1)) : nan,
      c.L ? finite((*c.L)(1, 0)) : nan,
      c.L ? finite((*c.L)(1, 1)) : nan,
      finite(r.det_L),
      finite(r.energy),
      finite(r.energy_error),
      finite(r.energy_reference_t),
      finite(r.energy_orbital),
      finite(r.energy_deformation),
      finite(r.spin),
      optional(r.speed),
      optional(r.heading),
      finite(r.vorticity),
      r.separated ? finite(r.separated->C_x) : nan,
      r.separated ? finite(r.separated->C_y) : nan,
      r.momentum_map ? finite(r.momentum_map->x()) : nan,
      r.momentum_map ? finite(r.momentum_map->y()) : nan,
      r.momentum_map ? finite(r.momentum_map->z()) : nan,
      optional(r.casimir),
      a ? optional(a->J_r) : nan,
      a ? optional(a->J_phi) : nan,
      a ? optional(a->J_alpha) : nan,
      a ? optional(a->J_beta) : nan,
      a ? optional(a->J_x) : nan,
      a ? optional(a->J_y) : nan,
      a ? optional(a->nu_r) : nan,
      a ? optional(a->nu_phi) : nan,
      a ? optional(a->nu_x) : nan,
      a ? optional(a->nu_y) : nan,
      chart(false, c.r),
      chart(false, c.r_dot),
      chart(false, c.p_r),
      optional(r.curvature),
      embedded(&Readout::Embedded::V, 0),
      embedded(&Readout::Embedded::V, 1),
      embedded(&Readout::Embedded::V, 2),
      embedded(&Readout::Embedded::e1, 0),
      embedded(&Readout::Embedded::e1, 1),
      embedded(&Readout::Embedded::e1, 2),
      embedded(&Readout::Embedded::e2, 0),
      embedded(&Readout::Embedded::e2, 1),
      embedded(&Readout::Embedded::e2, 2),
      embedded(&Readout::Embedded::n, 0),
      embedded(&Readout::Embedded::n, 1),
      embedded(&Readout::Embedded::n, 2),
      free ? finite(r.embedded->drift) : nan,
  };
  std::copy(std::begin(values), std::end(values), out.begin());
}

}  // namespace spinfold
