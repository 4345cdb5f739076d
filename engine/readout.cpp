#include "engine/readout.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <utility>

#include "engine/implicit_start.h"
#include "engine/scene_fields.h"

namespace spinfold {

namespace {

// Each number that printed as a negative zero ("-0.0000", "-0.00e+00", "-0": a value that rounds
// to zero, or −0 itself) without its sign: the readout says 0, not a direction it cannot resolve.
std::string without_negative_zeros(std::string text) {
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '-' ||
        (i > 0 && (digit(text[i - 1]) || std::isalpha(static_cast<unsigned char>(text[i - 1])))))
      continue;
    // The mantissa after the sign (an exponent after zeros, "-0.00e+00", leaves the number zero).
    bool any_digit = false, all_zero = true;
    for (std::size_t k = i + 1; k < text.size() && (digit(text[k]) || text[k] == '.'); ++k)
      if (digit(text[k])) {
        any_digit = true;
        all_zero = all_zero && text[k] == '0';
      }
    if (any_digit && all_zero) text.erase(i, 1);
  }
  return text;
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return without_negative_zeros(text);
}

}  // namespace

namespace {

// What every chart-free read-out shares: the coordinates given (a chart's or the convention
// frame's), K, the energies, spin, vorticity, det L, C_x and C_y.
void read_embedded(const Simulation& run, const PaperCoordinates& c, double K, double speed, Readout& r) {
  const EmbeddedScene& model = *run.embedded;
  const Coords& y = run.state.y;
  r.coordinates = c;
  r.curvature = K;
  const EnergyParts parts = embedded_energy_parts(model, y);
  r.energy = parts.kinetic + parts.potential;
  const EmbeddedEnergy split = embedded_energy_split(model, y);
  r.energy_orbital = split.orbital;
  r.energy_deformation = r.energy - split.orbital;
  r.spin = c.p_alpha;
  r.speed = speed;
  r.vorticity = c.p_beta;
  r.det_L = c.det_L;
  r.separated = separated_energies(run.scene, run.state);
  r.actions_unsupported = *actions_unsupported_reason(run.scene);
}

// The read-out where the curvature varies (engine/embedded_run.h): the chart (u, φ) and K.
void read_profile(const Simulation& run, Readout& r) {
  const ProfileReadout p = profile_readout(*run.embedded, run.state.y);
  read_embedded(run, p.coordinates, p.K, p.speed, r);
  r.heading = p.heading;
}

// The read-out on a surface with no chart (engine/embedded_run.h FreeReadout).
void read_free(const Simulation& run, Readout& r) {
  const FreeReadout f = free_readout(*run.embedded, run.state.y);
  read_embedded(run, f.coordinates, f.K, f.speed, r);
  r.embedded = Readout::Embedded{f.body.V, f.body.e[0], f.body.e[1], f.normal, f.distance, f.tangency};
  // The heading as a start gives it: from the convention's E₁ towards E₂ at X (undefined at rest).
  if (f.speed > 0.0) {
    const StartFrame frame = start_frame(*run.surface->implicit, f.body.X);
    r.heading = std::atan2(f.body.V.dot(frame.E2), f.body.V.dot(frame.E1));
  }
}

}  // namespace

namespace {

// The read-out on a constant-curvature surface: the paper's coordinates of its polar chart.
void read_chart(const Simulation& run, Readout& r) {
  const Scene& scene = run.scene;
  const State& state = run.state;
  r.coordinates = paper_coordinates(scene, state);
  r.energy = energy(scene, state);
  r.energy_orbital = orbital_energy(scene, state);
  r.energy_deformation = deformation_energy(scene, state);
  r.spin = r.coordinates.p_alpha;
  // The scene's physical start (engine/initial_rates.h), read off the state at any time.
  const double S = polar_S(scene.surface, r.coordinates.r);
  const auto& [r_dot, phi_dot] = std::pair(r.coordinates.r_dot, r.coordinates.phi_dot);
  if (r_dot && phi_dot) {
    r.speed = std::hypot(*r_dot, S * *phi_dot);
    r.heading = std::atan2(S * *phi_dot, *r_dot);
  } else if (r_dot) {
    r.speed = std::abs(*r_dot);  // at a pole S = 0: all of the motion is radial
  }
  r.vorticity = r.coordinates.p_beta;
  r.det_L = r.coordinates.det_L;
  r.separated = separated_energies(scene, state);
  if (const auto why = actions_unsupported_reason(scene))
    r.actions_unsupported = *why;
  else
    r.actions = action_variables(scene, state);
  r.momentum_map = momentum_map(scene, state);
  if (r.momentum_map && !offers(scene.surface, Offer::zero_curvature)) {
    // The casimir from M in the body's chart (an invariant of the isometry): no cancellation.
    const ChartMomentum cm = chart_momentum(scene, state);
    r.casimir = casimir(scene.surface, cm.local);
    const double scale = cm.local.cwiseAbs().sum();
    bool digits = true;
    for (int i = 0; i < 3; ++i)
      digits = digits && well_conditioned(cm.rounding[i], std::abs(cm.global[i]) + scale);
    if (!digits) {
      r.momentum_map.reset();
      r.undefined.push_back(
          {"M",
           "far out on the pseudosphere the components of M are differences of numbers of "
           "size e^(r/R) and keep fewer than 8 digits in double (the casimir is computed in "
           "the body's chart and stays exact)"});
    }
  }
}

}  // namespace

Readout readout(const Simulation& run) {
  const State& state = run.state;
  Readout r;
  r.t = state.t;
  if (run.surface->profile)
    read_profile(run, r);
  else if (run.embedded)
    read_free(run, r);
  else
    read_chart(run, r);
  r.energy_error = (r.energy - run.initial_energy) / std::max(std::abs(run.initial_energy), 1e-300);
  r.energy_reference_t = run.segment_start;
  r.status = state.status;
  r.status_name = status_name(state.status);
  r.status_detail = status_description(state.status);
  r.integrator = run.info->name;
  r.steps = run.steps;
  return r;
}

namespace {

// "J = 0.1" or "J = [[0.2, 0.05], [0.05, 0.1]]".
std::string inertia_text(const Body& body) {
  if (!body.inertia_matrix) return format("J = %g", body.inertia);
  const InertiaMatrix& J = *body.inertia_matrix;
  return format("J = [[%g, %g], ", J.J11, J.J12) + format("[%g, %g]]", J.J21, J.J22);
}

}  // namespace

std::vector<std::string> readout_lines(const Scene& scene, const Readout& readout) {
  static_assert(kSurfaceReadoutLine == 3, "the surface's line is the fourth below");
  return {
      format("t = %.3f", readout.t),
      // With friction the energy falls by design (dE/dt = −2R): the line names what it shows.
      scene.friction ? format("energy change = %.2e (friction)", readout.energy_error)
                     : format("energy error = %.2e", readout.energy_error),
      "integrator: " + std::string(readout.integrator) + (readout.status == Status::ok ? "" : "  [stopped]"),
      std::string(enum_name(scene.surface.kind)) +
          (chart_free(scene.surface) ? format("  K = %.4f", readout.curvature.value_or(0.0))
                                     : format("  R = %g", scene.surface.radius)),
      format("m = %g  ", scene.body.mass) + inertia_text(scene.body) + "  " +
          std::string(enum_name(scene.body.model)),
      format("spin = %.4f  det L = %.4f", readout.spin, readout.det_L),
  };
}

std::vector<std::string> plain_readout_lines(const Scene& scene, const Readout& readout) {
  const std::vector<std::string> full = readout_lines(scene, readout);
  static_assert(kPlainSurfaceLine == 1, "the surface's line is the second below");
  return {full.front() + (readout.status == Status::ok ? "" : "  (stopped)"), full[kSurfaceReadoutLine],
          format("spin = %.4f", readout.spin)};
}

std::vector<std::string> action_lines(const Readout& readout) {
  if (!readout.actions) return {"no action variables: " + readout.actions_unsupported};
  const ActionVariables& a = *readout.actions;
  const auto value = [](const char* name, const std::optional<double>& v) {
    return std::string(name) + " = " + (v ? format("%.6g", *v) : std::string("-"));
  };
  return {value("J_r", a.J_r) + "  " + value("J_phi", a.J_phi) + "  " + value("J_alpha", a.J_alpha),
          value("J_beta", a.J_beta) + "  " + value("J_x", a.J_x) + "  " + value("J_y", a.J_y),
          value("nu_r", a.nu_r) + "  " + value("nu_phi", a.nu_phi) + "  " + value("nu_x", a.nu_x) + "  " +
              value("nu_y", a.nu_y)};
}

std::string companion_readout_line(std::string_view label, const Readout& readout) {
  // A fan's label already names the spin ("spin = 0.25"): the line does not say it twice.
  const std::string spin = label.starts_with("spin = ") ? "" : format("spin = %.4f  ", readout.spin);
  std::string line = std::string(label) + ": " + spin + format("energy error = %.2e", readout.energy_error);
  if (readout.status != Status::ok) line += "  [stopped: " + std::string(readout.status_name) + "]";
  return line;
}

}  // namespace spinfold
