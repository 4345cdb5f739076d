#include "engine/orbit_bound.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <variant>

#include "engine/readout.h"
#include "engine/revolution.h"
#include "engine/surface.h"

namespace spinfold {

namespace {

constexpr double kScanFeatures = 40.0;  // how far the turning points are searched, in features
// The scan's step, in features: V_eff varies on the feature's scale, and each frame's HUD asks
// (bisection and a golden section then take the found points to the last bits).
constexpr int kStepsPerFeature = 64;

}  // namespace

OrbitBound orbit_bound(const Simulation& run) {
  OrbitBound b;
  const Scene& scene = run.scene;
  if (!offers(scene.surface.kind, Offer::profile_chart)) {
    b.why_none = "not a surface of revolution";
    return b;
  }
  if (scene.friction || !std::holds_alternative<std::monostate>(scene.potential.height)) {
    b.why_none = "friction or a height potential: the orbit's energy alone is not a constant of it";
    return b;
  }
  const RevolutionSurface rs = revolution_surface(scene.surface);
  const RevolutionEntry& entry = revolution_entry(rs.kind);
  const ProfileDomain domain = entry.domain(rs);
  const bool open_low = !domain.periodic && std::isinf(domain.u_min);
  const bool open_high = !domain.periodic && std::isinf(domain.u_max);
  if (!open_low && !open_high) {
    b.why_none = "a closed surface: every orbit stays on it";
    return b;
  }
  const Readout r = readout(run);
  const double m = scene.body.mass, s = r.spin, p_phi = r.coordinates.p_phi, E = r.energy_orbital;
  const double u0 = r.coordinates.r;
  const auto point = [&](double u) {
    const ProfilePoint p = entry.profile(rs, u);
    return std::pair{p.rho, profile_metric(p).C};
  };
  // V_eff − E_orb, > 0 where the body cannot go (at an axis point, where ρ = 0, only p_φ = s C lets it).
  const auto excess = [&](double u) {
    const auto [rho, C] = point(u);
    const double q = p_phi - s * C;
    if (rho <= 0.0) return q == 0.0 ? -E : std::numeric_limits<double>::infinity();
    return q * q / (2.0 * m * rho * rho) - E;
  };
  const double feature = entry.picture(rs).feature, h = feature / kStepsPerFeature;
  // The nearest turning point from u0 towards `dir`, or none (escapes) within the scan; an axis end
  // or a closed end of the domain is a bound.
  const auto turning = [&](double dir) -> std::optional<double> {
    const double end = dir > 0 ? domain.u_max : domain.u_min;
    const bool open = dir > 0 ? open_high : open_low;
    double a = u0;
    for (int k = 1; k <= kScanFeatures * kStepsPerFeature; ++k) {
      double u = u0 + dir * k * h;
      if (!open && dir * (u - end) >= 0.0) return end;
      if (excess(u) > 0.0) {
        for (int i = 0; i < 60; ++i) {  // bisected to the last bit
          const double mid = 0.5 * (a + u);
          if (mid == a || mid == u) break;
          (excess(mid) > 0.0 ? u : a) = mid;
        }
        return a;
      }
      a = u;
    }
    if (!open) return end;
    return std::nullopt;
  };
  const std::optional<double> low = turning(-1.0), high = turning(+1.0);
  b.verdict = low && high ? OrbitBound::Verdict::held : OrbitBound::Verdict::escapes;
  b.u_low = low.value_or(-std::numeric_limits<double>::infinity());
  b.u_high = high.value_or(std::numeric_limits<double>::infinity());
  // A start on an axis point: p_φ = s C_axis, V_eff = s² (C_axis − C)²/(2 m ρ²) and E = m v²/2.
  const double u_start = scene.initial.u;  // where the run began: its critical spin
  const bool axis_start =
      (domain.axis_at_min && u_start == domain.u_min) || (domain.axis_at_max && u_start == domain.u_max);
  if (axis_start) {
    const double C_axis = point(u_start).second, dir = u_start == domain.u_min ? 1.0 : -1.0;
    const auto ratio = [&](double k) {  // |C_axis − C|/ρ at u = u_start + dir k h
      const auto [rho, C] = point(u_start + dir * k * h);
      return rho > 0.0 ? std::abs(C_axis - C) / rho : 0.0;
    };
    int best = 1;
    double most = ratio(1.0);
    for (int k = 2; k <= kScanFeatures * kStepsPerFeature; ++k)
      if (const double r_k = ratio(k); r_k > most) best = k, most = r_k;
    // The grid's best refined by golden section within its neighbours (the grid alone erred 7e-6).
    constexpr double g = 0.6180339887498949;
    double a = best - 1.0, c = best + 1.0;
    double x1 = c - g * (c - a), x2 = a + g * (c - a), f1 = ratio(x1), f2 = ratio(x2);
    for (int i = 0; i < 80; ++i) {
      if (f1 > f2) {
        c = x2, x2 = x1, f2 = f1, x1 = c - g * (c - a), f1 = ratio(x1);
      } else {
        a = x1, x1 = x2, f1 = f2, x2 = a + g * (c - a), f2 = ratio(x2);
      }
    }
    most = std::max(most, ratio(0.5 * (a + c)));
    // (The start's speed: E_orb is a constant of the run, m v²/2.)
    if (most > 0.0) b.critical_spin = m * std::sqrt(2.0 * E / m) / most;
  }
  return b;
}

std::string orbit_bound_note(const OrbitBound& bound) {
  if (bound.verdict == OrbitBound::Verdict::none) return "";
  const bool held = bound.verdict == OrbitBound::Verdict::held;
  std::string note = held ? "  trapped" : "  escapes";
  if (bound.critical_spin) {
    char text[64];
    std::snprintf(text, sizeof text, held ? " (|s| > s_crit = %.4g)" : " (|s| < s_crit = %.4g)",
                  *bound.critical_spin);
    note += text;
  }
  return note;
}

}  // namespace spinfold
