#include "render/drag.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string_view>

#include "engine/implicit_start.h"
#include "engine/revolution.h"
#include "engine/surface_model.h"
#include "render/view_table.h"
#include "render/views/camera.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

constexpr double kPi = std::numbers::pi;

// The chart point (q, φ) with the orthonormal frame E₁, E₂ there and ρ (= S(r), or the profile's
// ρ(u)), for either family of surfaces.
struct PlaceFrame {
  Vec3 X, E1, E2;
  double rho = 0.0;
  double f = 1.0;     // |∂X/∂q| [length per unit q]: 1 for r, the profile's f for u
  bool pole = false;  // S = 0 or an axis point: E₂'s rate undefined (engine/initial_rates.cpp)
};

// The chart's range of q and whether it wraps, and the length a picture of it is measured in.
struct ChartRange {
  double lo = 0.0, hi = 1.0;
  bool periodic = false;
  double length = 1.0;  // R, or the profile's smallest feature [length]
};

class Chart {
 public:
  explicit Chart(const Surface& surface) : surface_(surface), varies_(chart_free(surface)) {
    if (varies_) {
      revolution_ = revolution_surface(surface);
      const RevolutionEntry& e = revolution_entry(revolution_.kind);
      const ProfileDomain d = e.domain(revolution_);
      const ProfilePicture p = e.picture(revolution_);
      range_ = {std::max(d.u_min, p.u_min), std::min(d.u_max, p.u_max), d.periodic, p.feature};
      domain_ = d;
    } else {
      const double R = surface.radius;
      range_ = {0.0, offers(surface, Offer::positive_curvature) ? kPi * R : 8.0 * R, false, R};
    }
  }

  PlaceFrame at(double q, double phi) const {
    if (varies_) {
      const RevolutionFrame fr = revolution_frame(revolution_, q, phi);
      const ProfilePlace p = profile_place(revolution_, q);
      return {fr.X, fr.E1, fr.E2, p.rho, p.f, p.axis};
    }
    const ChartPoint c = chart_point(surface_, q, phi);
    const bool pole = q == 0.0 || (offers(surface_, Offer::positive_curvature) && q == kPi * surface_.radius);
    return {c.X, c.E1, c.E2, polar_S(surface_, q), 1.0, pole};
  }

  // (q, φ) as the scene gives them: q ≥ 0 on a polar chart (r < 0 is (|r|, φ + π)), u in its domain
  // (wrapped where periodic), φ in (−π, π].
  std::pair<double, double> canonical(double q, double phi) const {
    if (!varies_ && q < 0.0) q = -q, phi += kPi;
    if (varies_ && domain_.periodic) q = wrapped(q);
    if (varies_) q = std::clamp(q, domain_.u_min, domain_.u_max);
    return {q, wrapped(phi)};
  }
  // Keeps a search inside the chart: a profile's u within its domain (the polar chart is valid for
  // any real r).
  double inside(double q) const {
    if (!varies_ || domain_.periodic) return q;
    return std::clamp(q, domain_.u_min, domain_.u_max);
  }

  const ChartRange& range() const { return range_; }

 private:
  static double wrapped(double a) {
    a = std::remainder(a, 2.0 * kPi);
    return a <= -kPi ? a + 2.0 * kPi : a;
  }

  Surface surface_;
  bool varies_;
  RevolutionSurface revolution_;
  ProfileDomain domain_;
  ChartRange range_;
};

// A frame's projection: surface point → pixel, with the depth and whether the frame shows it.
class Projection {
 public:
  Projection(const Snapshot& snapshot, const ViewOptions& view)
      : surface_(snapshot.surface), view_(view), model_(view_model(view.kind)) {
    scene_.view_projection = model_.camera(view);
    matrix_ = glm::dmat4(scene_.view_projection);
  }

  struct Image {
    glm::dvec2 pixel;
    double depth;  // clip w: the distance along the camera's axis (1 in a 2-D view)
  };
  // The pixel of a surface point, or nullopt where the view does not draw it or it is behind the camera.
  std::optional<Image> of(const Vec3& X) const {
    if (!model_.draws(surface_, X)) return std::nullopt;
    const glm::dvec3 w = model_.world_position(surface_, X);
    const glm::dvec4 clip = matrix_ * glm::dvec4(w, 1.0);
    if (!(clip.w > 0.0) || !std::isfinite(clip.x) || !std::isfinite(clip.y)) return std::nullopt;
    const std::optional<glm::dvec2> px = pixel_position(scene_, view_, w);
    if (!px) return std::nullopt;
    return Image{*px, clip.w};
  }
  // d pixel / d s along the unit tangent vectors E₁, E₂ at X (columns) [pixels per length]: a
  // central difference of the view's map along the ambient directions, off the surface by O(h²).
  std::optional<glm::dmat2> jacobian(const Vec3& X, const Vec3& E1, const Vec3& E2, double length) const {
    const double h = 1e-6 * length;
    glm::dmat2 J(0.0);
    const Vec3 E[2] = {E1, E2};
    for (int c = 0; c < 2; ++c) {
      const auto a = of(X + h * E[c]), b = of(X - h * E[c]);
      if (!a || !b) return std::nullopt;
      J[c] = (a->pixel - b->pixel) / (2.0 * h);
    }
    return J;
  }

 private:
  Surface surface_;
  ViewOptions view_;
  const ViewModel& model_;
  FrameScene scene_;
  glm::dmat4 matrix_;
};

// The place a drag works with on either kind of surface: the chart's point (q, φ) where there is a
// chart, else the body's X with the start convention's frame there (engine/implicit_start.h), the
// frame its heading is read in.
struct DragPlace {
  PlaceFrame frame;
  double length = 1.0;  // the picture's length for differences [length]
};
DragPlace drag_place(const Surface& surface, const BodyPlace& body) {
  if (drags_by_point(surface)) {
    const auto shape = surface_model_of(surface);
    const StartFrame f = start_frame(*shape->implicit, body.X);
    return {{body.X, f.E1, f.E2, 1.0, 1.0, false}, shape->feature};
  }
  const Chart chart(surface);
  return {chart.at(body.q, body.phi), chart.range().length};
}

// The pixel's ray in the world of the view (near and far planes).
std::pair<glm::dvec3, glm::dvec3> pixel_ray(const ViewModel& model, const ViewOptions& view,
                                            glm::dvec2 pixel) {
  const glm::dmat4 inverse = glm::inverse(glm::dmat4(model.camera(view)));
  const double x = 2.0 * pixel.x / view.width - 1.0, y = 1.0 - 2.0 * pixel.y / view.height;
  const glm::dvec4 a = inverse * glm::dvec4(x, y, -1.0, 1.0), b = inverse * glm::dvec4(x, y, 1.0, 1.0);
  return {glm::dvec3(a) / a.w, glm::dvec3(b) / b.w};
}

// The view's map from space to its world as X ↦ A X + c, when it is one (probed, and checked at a
// point off the probes to 1e-9 of the picture's length).
struct AffineMap {
  Mat3 A;
  Vec3 c;
};
std::optional<AffineMap> affine_world(const ViewModel& model, const Surface& surface,
                                      const SurfaceModel& shape) {
  const auto world = [&](const Vec3& X) {
    const glm::dvec3 w = model.world_position(surface, X);
    return Vec3(w.x, w.y, w.z);
  };
  const double L = shape.length;
  AffineMap m;
  m.c = world(shape.centre);
  for (int k = 0; k < 3; ++k) m.A.col(k) = (world(shape.centre + L * Vec3::Unit(k)) - m.c) / L;
  const Vec3 probe = shape.centre + L * Vec3(0.37, -0.61, 0.23);
  const Vec3 expected = m.A * (probe - shape.centre) + m.c;
  if (!m.A.allFinite() || !(std::abs(m.A.determinant()) > 0.0) ||
      !((world(probe) - expected).norm() <= 1e-9 * std::max(1.0, expected.norm())))
    return std::nullopt;
  return m;
}

// The interval of s in [0, 1] where a + s (b − a) lies inside the box, or nullopt (the slab method).
std::optional<std::pair<double, double>> inside_box(const SurfaceBounds& box, const Vec3& a, const Vec3& b) {
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    if (d == 0.0) {
      if (a[k] < box[k][0] || a[k] > box[k][1]) return std::nullopt;
      continue;
    }
    double s0 = (box[k][0] - a[k]) / d, s1 = (box[k][1] - a[k]) / d;
    if (s0 > s1) std::swap(s0, s1);
    lo = std::max(lo, s0), hi = std::min(hi, s1);
  }
  if (!(lo <= hi)) return std::nullopt;
  return std::pair{lo, hi};
}

// Levenberg–Marquardt on the pixel's residual over (q, φ) from a seed: the place whose image is
// nearest `target`, and that distance [pixels].
struct Fit {
  double q, phi, miss, depth;
};
std::optional<Fit> refine(const Chart& chart, const Projection& projection, glm::dvec2 target, double q,
                          double phi) {
  const double length = chart.range().length;
  const auto residual = [&](double a, double b) -> std::optional<Projection::Image> {
    return projection.of(chart.at(chart.inside(a), b).X);
  };
  std::optional<Projection::Image> here = residual(q, phi);
  if (!here) return std::nullopt;
  double miss = glm::length(here->pixel - target), damping = 1e-3;
  for (int iteration = 0; iteration < 60 && miss > 1e-6; ++iteration) {
    // Columns: d pixel / dq and d pixel / dφ, by central differences.
    const double hq = 1e-7 * std::max(length, std::abs(q)), hp = 1e-7;
    const auto qa = residual(q + hq, phi), qb = residual(q - hq, phi);
    const auto pa = residual(q, phi + hp), pb = residual(q, phi - hp);
    if (!qa || !qb || !pa || !pb) return std::nullopt;
    const glm::dvec2 Jq = (qa->pixel - qb->pixel) / (2 * hq), Jp = (pa->pixel - pb->pixel) / (2 * hp);
    const glm::dvec2 r = here->pixel - target;
    // (JᵀJ + λ diag(JᵀJ)) δ = −Jᵀr
    const double a = glm::dot(Jq, Jq), b = glm::dot(Jq, Jp), c = glm::dot(Jp, Jp);
    const double gq = glm::dot(Jq, r), gp = glm::dot(Jp, r);
    bool improved = false;
    for (int tries = 0; tries < 12 && !improved; ++tries) {
      const double A = a * (1 + damping) + 1e-300, C = c * (1 + damping) + 1e-300;
      const double det = A * C - b * b;
      if (!(std::abs(det) > 0.0)) {
        damping *= 10;
        continue;
      }
      const double dq = -(C * gq - b * gp) / det, dp = -(A * gp - b * gq) / det;
      const auto next = residual(q + dq, phi + dp);
      const double next_miss =
          next ? glm::length(next->pixel - target) : std::numeric_limits<double>::infinity();
      if (next_miss < miss) {
        q = chart.inside(q + dq), phi += dp, here = next, miss = next_miss;
        damping = std::max(damping / 10, 1e-9);
        improved = true;
      } else {
        damping *= 10;
      }
    }
    if (!improved) break;
  }
  return Fit{q, phi, miss, here->depth};
}

}  // namespace

BodyPlace body_place(const Readout& readout) {
  // φ is undefined at a pole (any will do there) and listed as such far out on H², where the
  // embedding's own angle still places the body to the pixel.
  const PaperCoordinates& c = readout.coordinates;
  return {c.r, c.phi.value_or(std::atan2(c.X.y(), c.X.x())), readout.speed.value_or(0.0), readout.heading,
          c.X};
}

double arrow_pixels_per_speed(const ViewOptions& view, const Surface& surface) {
  return 0.25 * std::min(view.width, view.height) / body_scale_length(view.kind, surface);
}

bool drags_by_point(const Surface& surface) {
  return chart_free(surface) && !offers(surface, Offer::profile_chart);
}

std::optional<std::string> drag_unsupported_reason(const Surface& /*surface*/) {
  return std::nullopt;  // every surface: a chart's search, or a ray cast against F
}

std::optional<DragHandles> drag_handles(const Snapshot& snapshot, const ViewOptions& view,
                                        const BodyPlace& body) {
  const DragPlace place = drag_place(snapshot.surface, body);
  const PlaceFrame& at = place.frame;
  const Projection projection(snapshot, view);
  const auto image = projection.of(at.X);
  if (!image) return std::nullopt;
  // In 3-D, a body behind a nearer part of the surface (the sphere's far side, the torus's tube):
  // the pixel belongs to that part.
  if (view_info(view.kind).three_d) {
    std::optional<Vec3> seen;
    if (drags_by_point(snapshot.surface)) {
      seen = point_at_pixel(snapshot, view, image->pixel, body);
    } else if (const auto q = place_at_pixel(snapshot, view, image->pixel, body)) {
      seen = Chart(snapshot.surface).at(q->first, q->second).X;
    }
    if (!seen || (*seen - at.X).norm() > 1e-4 * std::max(place.length, at.X.norm())) return std::nullopt;
  }
  DragHandles handles{image->pixel, std::nullopt};
  if (!body.heading) return handles;
  const auto J = projection.jacobian(at.X, at.E1, at.E2, place.length);
  if (!J) return handles;
  const glm::dvec2 d = *J * glm::dvec2(std::cos(*body.heading), std::sin(*body.heading));
  const double n = glm::length(d);
  // The direction on screen; a tangent direction the view draws edge-on has none.
  if (!(n > 1e-6 * glm::length((*J)[0]) + 1e-300)) return handles;
  handles.arrow =
      image->pixel + (kArrowBasePixels + arrow_pixels_per_speed(view, snapshot.surface) * body.speed) * d / n;
  return handles;
}

std::optional<std::pair<double, double>> place_at_pixel(const Snapshot& snapshot, const ViewOptions& view,
                                                        glm::dvec2 pixel, const BodyPlace& near) {
  if (!(pixel.x >= 0 && pixel.y >= 0 && pixel.x <= view.width && pixel.y <= view.height)) return std::nullopt;
  const Chart chart(snapshot.surface);
  const Projection projection(snapshot, view);
  const ChartRange& range = chart.range();

  // Seeds: the chart's range on a grid, and grids of three sizes round the body (a drop is usually
  // near where the drag began; a close-up shows a small piece of a large range).
  struct Seed {
    double q, phi, miss;
  };
  std::vector<Seed> seeds;
  const auto add = [&](double q, double phi) {
    q = chart.inside(q);
    if (const auto image = projection.of(chart.at(q, phi).X))
      seeds.push_back({q, phi, glm::length(image->pixel - pixel)});
  };
  const double hi = std::max(range.hi, near.q + 3.0 * range.length);
  for (int i = 0; i <= 96; ++i)
    for (int j = 0; j < 96; ++j) add(range.lo + (hi - range.lo) * i / 96.0, -kPi + 2.0 * kPi * j / 96.0);
  const PlaceFrame body = chart.at(near.q, near.phi);
  for (const double size : {0.03, 0.3, 1.5}) {
    const double L = size * range.length;
    const double dphi = std::min(kPi, L / std::max(body.rho, L));
    for (int i = -12; i <= 12; ++i)
      for (int j = -12; j <= 12; ++j) add(near.q + L * i / 12.0, near.phi + dphi * j / 12.0);
  }
  if (seeds.empty()) return std::nullopt;
  std::sort(seeds.begin(), seeds.end(), [](const Seed& a, const Seed& b) { return a.miss < b.miss; });
  // The 24 nearest the pixel, one per cluster (a seed within 2% of the picture's length of a kept
  // one adds nothing): in 3-D the far side's seeds must not crowd out the near side's.
  std::vector<std::pair<Seed, Vec3>> kept;
  for (const Seed& seed : seeds) {
    if (kept.size() == 24) break;
    const Vec3 X = chart.at(seed.q, seed.phi).X;
    if (std::ranges::none_of(kept,
                             [&](const auto& k) { return (k.second - X).norm() < 0.02 * range.length; }))
      kept.emplace_back(seed, X);
  }

  // The fit nearest the camera among those that land on the pixel (in a 3-D view a ray can meet the
  // surface more than once: the nearest is the one drawn); of fits at one point (the tractricoid
  // wraps H²'s strip round its axis), the place nearest the body.
  constexpr double kLanded = 0.05;  // [pixels]
  std::optional<Fit> best;
  double best_apart = 0.0;
  const ViewModel& model = view_model(view.kind);
  for (const auto& [seed, X] : kept) {
    const auto fit = refine(chart, projection, pixel, seed.q, seed.phi);
    if (!fit || fit->miss > kLanded) continue;
    // Only where the frame paints the surface: beyond the drawn piece of an unbounded surface the
    // pixel shows background, and a drop there is refused (docs/architecture.md, "Drag handles").
    if (!model.paints_surface_at(snapshot, chart.at(fit->q, fit->phi).X)) continue;
    const double apart = (chart.at(fit->q, fit->phi).X - body.X).norm();
    const double tie = 1e-6 * std::abs(fit->depth) + 1e-12;
    if (best && (fit->depth > best->depth + tie || (fit->depth > best->depth - tie && apart >= best_apart)))
      continue;
    best = fit, best_apart = apart;
  }
  if (!best) return std::nullopt;
  return chart.canonical(best->q, best->phi);
}

std::optional<Vec3> point_at_pixel(const Snapshot& snapshot, const ViewOptions& view, glm::dvec2 pixel,
                                   const BodyPlace& near) {
  if (!(pixel.x >= 0 && pixel.y >= 0 && pixel.x <= view.width && pixel.y <= view.height)) return std::nullopt;
  const SurfaceModel* shape = &surface_model(snapshot);
  const ViewModel& model = view_model(view.kind);
  const std::optional<AffineMap> map = affine_world(model, snapshot.surface, *shape);
  if (!map) return std::nullopt;
  const auto [wa, wb] = pixel_ray(model, view, pixel);
  const Mat3 back = map->A.inverse();
  const Vec3 a = back * (Vec3(wa.x, wa.y, wa.z) - map->c) + shape->centre;
  const Vec3 b = back * (Vec3(wb.x, wb.y, wb.z) - map->c) + shape->centre;
  // Where the frame may paint the surface: the drawn box, and the patch round a body beyond it.
  SurfaceBounds patch{};
  const double half = 4.0 * shape->feature;
  for (int k = 0; k < 3; ++k) patch[k] = {near.X[k] - half, near.X[k] + half};
  const Projection projection(snapshot, view);
  std::optional<std::pair<double, Vec3>> best;  // the ray's parameter and the point
  for (const SurfaceBounds& box : {shape->box, patch}) {
    const auto span = inside_box(box, a, b);
    if (!span) continue;
    constexpr int kSamples = 1024;
    const auto at = [&](double s) { return Vec3(a + s * (b - a)); };
    double s0 = span->first, f0 = shape->value(at(s0));
    for (int i = 1; i <= kSamples && !(best && s0 >= best->first); ++i) {
      const double s1 = span->first + (span->second - span->first) * i / kSamples, f1 = shape->value(at(s1));
      if (std::isfinite(f0) && std::isfinite(f1) && (f0 < 0.0) != (f1 < 0.0)) {
        double lo = s0, hi = s1, flo = f0;
        for (int k = 0; k < 80 && hi - lo > 1e-16 * std::max(1.0, hi); ++k) {
          const double mid = 0.5 * (lo + hi), fm = shape->value(at(mid));
          if ((fm < 0.0) == (flo < 0.0))
            lo = mid, flo = fm;
          else
            hi = mid;
        }
        const SurfaceFoot foot =
            project_onto_surface(*shape->implicit, at(0.5 * (lo + hi)), shape->length, 1e-3 * shape->feature);
        const auto image = foot.X ? projection.of(*foot.X) : std::nullopt;
        if (image && glm::length(image->pixel - pixel) <= 0.05 &&
            model.paints_surface_at(snapshot, *foot.X)) {
          best = std::pair{lo, *foot.X};
          break;
        }
      }
      s0 = s1, f0 = f1;
    }
  }
  if (!best) return std::nullopt;
  return best->second;
}

std::optional<std::pair<double, double>> velocity_at_pixel(const Snapshot& snapshot, const ViewOptions& view,
                                                           glm::dvec2 tip, const BodyPlace& body) {
  const DragPlace place = drag_place(snapshot.surface, body);
  const PlaceFrame& at = place.frame;
  const Projection projection(snapshot, view);
  const auto image = projection.of(at.X);
  const auto J = projection.jacobian(at.X, at.E1, at.E2, place.length);
  if (!image || !J) return std::nullopt;
  const glm::dvec2 d = tip - image->pixel;
  const double scale = std::max(glm::length((*J)[0]), glm::length((*J)[1]));
  const double det = glm::determinant(*J);
  // Edge-on (the sphere's limb): the screen does not say which way along the surface.
  if (!(std::abs(det) > 1e-3 * scale * scale)) return std::nullopt;
  const glm::dvec2 c = glm::inverse(*J) * d;
  const double length = glm::length(d);
  const double speed =
      std::max(0.0, length - kArrowBasePixels) / arrow_pixels_per_speed(view, snapshot.surface);
  // An arrow drawn along E₁ reads back a heading of a few ulps (5.6e-17): 0, as the panel shows it.
  double heading = std::atan2(c.y, c.x);
  if (std::abs(heading) < 1e-12) heading = 0.0;
  return std::pair{speed, heading};
}

InitialFields place_fields(const Surface& surface, double q, double phi) {
  return {{chart_free(surface) ? "u" : "r", q}, {"phi", phi}};
}

InitialFields place_fields(const Surface& surface, const BodyPlace& body) {
  if (drags_by_point(surface)) return {{"X.0", body.X.x()}, {"X.1", body.X.y()}, {"X.2", body.X.z()}};
  return place_fields(surface, body.q, body.phi);
}

StartMotion start_motion(const Readout& start) {
  return {start.spin, start.heading ? start.speed : std::nullopt, start.heading};
}

InitialFields point_drop_fields(const Vec3& X, const StartMotion& start) {
  InitialFields fields{{"X.0", X.x()}, {"X.1", X.y()}, {"X.2", X.z()}};
  if (start.speed && start.heading) {
    fields.emplace_back("speed", *start.speed);
    fields.emplace_back("heading", *start.heading);
  }
  fields.emplace_back("spin", start.spin);
  return fields;
}

std::optional<InitialFields> body_drop_at_pixel(const Snapshot& snapshot, const ViewOptions& view,
                                                glm::dvec2 pixel, const BodyPlace& near,
                                                const StartMotion& start) {
  if (drags_by_point(snapshot.surface)) {
    const std::optional<Vec3> X = point_at_pixel(snapshot, view, pixel, near);
    if (!X) return std::nullopt;
    return point_drop_fields(*X, start);
  }
  const auto place = place_at_pixel(snapshot, view, pixel, near);
  if (!place) return std::nullopt;
  return body_drop_fields(snapshot.surface, place->first, place->second, start);
}

InitialFields body_drop_fields(const Surface& surface, double q, double phi, const StartMotion& start) {
  InitialFields fields = place_fields(surface, q, phi);
  if (start.speed && start.heading) {
    fields.emplace_back("speed", *start.speed);
    fields.emplace_back("heading", *start.heading);
  }
  fields.emplace_back("spin", start.spin);
  return fields;
}

InitialFields arrow_drop_fields(const Surface& surface, const BodyPlace& body, double speed, double heading,
                                const StartMotion& start) {
  if (drags_by_point(surface)) {  // no pole off a chart: the place and the velocity as drawn
    InitialFields fields = point_drop_fields(body.X, {start.spin, speed, heading});
    return fields;
  }
  const Chart chart(surface);
  const PlaceFrame at = chart.at(body.q, body.phi);
  double phi = body.phi;
  if (at.pole && speed != 0.0) {
    // E₁ at the pole points along φ: the φ whose E₁ is the velocity's direction (φ + h or φ − h,
    // as the chart's orientation there says), with heading 0.
    const Vec3 want = std::cos(heading) * at.E1 + std::sin(heading) * at.E2;
    const double plus = chart.at(body.q, body.phi + heading).E1.dot(want);
    const double minus = chart.at(body.q, body.phi - heading).E1.dot(want);
    phi = chart.canonical(body.q, plus >= minus ? body.phi + heading : body.phi - heading).second;
    heading = 0.0;
  }
  InitialFields fields = place_fields(surface, body.q, phi);
  fields.emplace_back("speed", speed);
  fields.emplace_back("heading", heading);
  fields.emplace_back("spin", start.spin);
  return fields;
}

std::string drop_text(const InitialFields& fields, bool arrow) {
  std::string text;
  for (const auto& [name, value] : fields) {
    const bool velocity = name == "speed" || name == "heading";
    if (name == "spin" || velocity != arrow) continue;
    char v[48];
    if (name == "heading")
      std::snprintf(v, sizeof v, "%.1f°", value * 180.0 / kPi);
    else
      std::snprintf(v, sizeof v, "%.4g", value);
    if (!text.empty()) text += ", ";
    text.append(name).append(" = ").append(v);
  }
  return text;
}

std::string drop_plain_text(const InitialFields& fields, bool arrow) {
  const auto value = [&](std::string_view name) -> std::optional<double> {
    for (const auto& [n, v] : fields)
      if (n == name) return v;
    return std::nullopt;
  };
  char text[96];
  if (!arrow) {
    const std::optional<double> r = value("r");
    if (!r) return "start here";
    std::snprintf(text, sizeof text, "start here, %.3g from the pole", *r);
    return text;
  }
  const std::optional<double> speed = value("speed"), heading = value("heading");
  if (!speed || !heading) return "start with this velocity";
  std::snprintf(text, sizeof text, "start at speed %.3g, %.0f° from outwards", *speed,
                *heading * 180.0 / kPi);
  return text;
}

}  // namespace spinfold::render
