#include "engine/path_circle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "engine/readout.h"

namespace spinfold {

PredictedCircle predicted_circle(const Scene& scene, double spin, double speed) {
  PredictedCircle out;
  const Surface& surface = scene.surface;
  if (chart_free(surface)) {
    out.why_none = "the curvature varies along the path";
    return out;
  }
  if (offers(surface, Offer::zero_curvature)) {
    out.why_none = "a straight line: no curvature (K = 0)";
    return out;
  }
  if (scene.potential.radial && scene.potential.radial->gamma != 0.0) {
    out.why_none = "the radial potential bends the path";
    return out;
  }
  if (scene.friction && scene.friction->any()) {
    out.why_none = "friction slows the body";
    return out;
  }
  if (!(speed > 0.0)) {
    out.why_none = "the body is at rest";
    return out;
  }
  const double R = surface.radius, p = scene.body.mass * speed * R, s = std::abs(spin);
  double rho = 0.0, circumference = 0.0;
  if (offers(surface, Offer::positive_curvature)) {
    rho = R * std::atan2(p, s);  // cos(ρ/R) = s/|M|, |M| = √(s² + m²v²R²)
    circumference = 2.0 * std::numbers::pi * R * std::sin(rho / R);
  } else {
    if (s <= 1e-12 * p) {  // a hypercycle at distance 0 from its axis
      out.why_none = "a geodesic: no spin (s = 0)";
      return out;
    }
    if (s < p) {
      out.why_none = "a hypercycle: |s| < m v R";
      return out;
    }
    if (s == p) {
      out.why_none = "a horocycle: |s| = m v R";
      return out;
    }
    rho = R * std::atanh(p / s);  // tanh(ρ/R) = m v R/|s|
    circumference = 2.0 * std::numbers::pi * R * std::sinh(rho / R);
  }
  out.radius = rho;
  out.period = circumference / speed;
  return out;
}

std::optional<double> circle_through(const Surface& surface, std::span<const Vec3> points, double* off) {
  if (points.size() < 3 || chart_free(surface) || offers(surface, Offer::zero_curvature)) return std::nullopt;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& X : points) centroid += X;
  centroid /= static_cast<double>(points.size());
  Mat3 scatter = Mat3::Zero();
  for (const Vec3& X : points) scatter += (X - centroid) * (X - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(scatter);
  if (eigen.info() != Eigen::Success) return std::nullopt;
  const Vec3 n = eigen.eigenvectors().col(0);  // the least spread: the plane's normal (Euclidean)
  // Points on one line (or one point) fit no plane. (Far out on H² a circle's Euclidean picture is
  // an ellipse e^{2r/R} times longer than wide: only a spread lost to round-off is refused.)
  if (!(eigen.eigenvalues()(1) > 1e-24 * eigen.eigenvalues()(2))) return std::nullopt;
  const double b = n.dot(centroid);
  if (off) {
    double sum = 0.0;
    for (const Vec3& X : points) sum += (n.dot(X) - b) * (n.dot(X) - b);
    *off = std::sqrt(sum / static_cast<double>(points.size()));
  }
  const double R = surface.radius;
  double rho = 0.0;
  if (offers(surface, Offer::positive_curvature)) {
    // Each point's distance from the axis n and its height along it: ρ = R atan2(|X − (n·X)n|, |n·X|),
    // well-conditioned at any radius (acos of the height alone loses digits near a pole).
    for (const Vec3& X : points) rho += R * std::atan2((X - n.dot(X) * n).norm(), std::abs(n.dot(X)));
  } else {
    // ⟨c, X⟩ = n·X with c = ηn: the section is a circle where c is timelike, centred on R c/|c|;
    // R sinh(ρ/R) is the Minkowski length of X's part orthogonal to c.
    const Vec3 c(n.x(), n.y(), -n.z());
    const double cc = dot(surface, c, c);
    if (!(cc < 0.0)) return std::nullopt;
    const Vec3 u = c / std::sqrt(-cc);
    for (const Vec3& X : points) {
      const Vec3 side = X + dot(surface, u, X) * u;  // ⟨u, u⟩ = −1
      rho += R * std::asinh(std::sqrt(std::max(0.0, dot(surface, side, side))) / R);
    }
  }
  return rho / static_cast<double>(points.size());
}

CircleReadout circle_readout(const Simulation& run, const Trail& trail) {
  const Readout now = readout(run);
  CircleReadout out;
  out.predicted = predicted_circle(run.scene, now.spin, now.speed.value_or(0.0));
  if (!out.predicted.radius) return out;
  const double t = run.state.t, from = std::max(now.energy_reference_t, t - out.predicted.period);
  std::vector<Vec3> lap;
  double first = t;
  for (const TrailPoint& p : trail.points)
    if (p.t >= from && p.t <= t) {
      lap.push_back(p.X);
      first = std::min(first, p.t);
    }
  if (lap.size() < 8 || t - first < out.predicted.period / 8.0) return out;
  out.measured = circle_through(run.scene.surface, lap);
  return out;
}

std::string circle_line(const Scene& scene, const CircleReadout& circle) {
  if (chart_free(scene.surface)) return "";
  char text[96];
  if (!circle.predicted.radius)
    std::snprintf(text, sizeof text, "no circle: %s", circle.predicted.why_none.c_str());
  else if (circle.measured)
    std::snprintf(text, sizeof text, "circle radius = %.4f (predicted %.4f)", *circle.measured,
                  *circle.predicted.radius);
  else
    std::snprintf(text, sizeof text, "circle radius: predicted %.4f (measuring)", *circle.predicted.radius);
  return text;
}

}  // namespace spinfold
