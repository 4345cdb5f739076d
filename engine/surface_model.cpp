#include "engine/surface_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <list>
#include <mutex>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "engine/formula_surface.h"
#include "engine/surface_geodesics.h"

namespace spinfold {

double SurfaceModel::value(const Vec3& X) const {
  return formula ? formula->value(X) : implicit->at(X).F;
}

namespace {

// The box search's samples per side, the cubes' half-sides tried and the unbounded surface's cube.
constexpr int kSamples = 24;
constexpr double kFirstHalfSide = 1.0, kLastHalfSide = 64.0, kUnboundedHalfSide = 2.0;
// At most this many points of the zero set are projected onto it to find the largest |K|.
constexpr std::size_t kCurvatureProbes = 512;

SurfaceBounds cube(const Vec3& centre, double half) {
  SurfaceBounds b;
  for (int k = 0; k < 3; ++k) b[k] = {centre[k] - half, centre[k] + half};
  return b;
}

// What the samples of F in [−h, h]³ say: the box of the points beside a sign change, whether it
// touches the cube's faces, and those points (to probe K at).
struct ZeroSet {
  bool found = false, touches = false;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  std::vector<Vec3> near;
};
ZeroSet sample_zero_set(const SurfaceModel& shape, double h) {
  const int n = kSamples + 1;
  const double step = 2.0 * h / kSamples;
  const auto point = [&](int i, int j, int k) { return Vec3(-h + i * step, -h + j * step, -h + k * step); };
  std::vector<double> F(static_cast<std::size_t>(n) * n * n);
  const auto at = [&](int i, int j, int k) -> double& {
    return F[(static_cast<std::size_t>(i) * n + j) * n + static_cast<std::size_t>(k)];
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) at(i, j, k) = shape.value(point(i, j, k));
  ZeroSet z;
  const auto mark = [&](int i, int j, int k) {
    const Vec3 p = point(i, j, k);
    z.found = true;
    z.lo = z.lo.cwiseMin(p), z.hi = z.hi.cwiseMax(p);
    z.touches = z.touches || std::min({i, j, k}) == 0 || std::max({i, j, k}) == kSamples;
    z.near.push_back(p);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double a = at(i, j, k);
        if (!std::isfinite(a)) continue;
        const std::tuple<int, int, int> next[] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (const auto& [p, q, r] : next) {
          if (p >= n || q >= n || r >= n) continue;
          const double b = at(p, q, r);
          if (std::isfinite(b) && (a > 0.0) != (b > 0.0)) mark(i, j, k), mark(p, q, r);
        }
      }
  return z;
}

// 1/√max|K| at points of the zero set near `near` (projected onto it), within [lo, hi].
double curvature_feature(const SurfaceModel& shape, const std::vector<Vec3>& near, double lo, double hi) {
  double largest = 0.0;
  const std::size_t stride = std::max<std::size_t>(1, near.size() / kCurvatureProbes);
  for (std::size_t i = 0; i < near.size(); i += stride) {
    const Vec3 X = project_onto_surface(*shape.implicit, near[i]);
    const ImplicitPoint p = shape.implicit->at(X);
    if (!X.allFinite() || !(std::abs(p.F) <= 1e-9 * (1.0 + X.norm()))) continue;
    const double K = std::abs(bordered_hessian_curvature(p));
    if (std::isfinite(K)) largest = std::max(largest, K);
  }
  return largest > 0.0 ? std::clamp(1.0 / std::sqrt(largest), lo, hi) : hi;
}

void set_box(SurfaceModel& shape, const SurfaceBounds& box) {
  shape.box = box;
  shape.length = 0.0;
  for (int k = 0; k < 3; ++k) {
    shape.centre[k] = 0.5 * (box[k][0] + box[k][1]);
    shape.length = std::max(shape.length, 0.5 * (box[k][1] - box[k][0]));
  }
}

SurfaceModel formula_shape(const Surface& surface) {
  SurfaceModel shape;
  const std::shared_ptr<const FormulaSurface> formula = formula_surface_of(surface);
  shape.implicit = formula;
  shape.formula = formula;
  ZeroSet zero;
  double h = kFirstHalfSide;
  for (; h <= kLastHalfSide; h *= 2.0) {
    zero = sample_zero_set(shape, h);
    if (zero.found && !zero.touches) break;
  }
  const bool closed = zero.found && !zero.touches;
  if (!closed) {
    // Unbounded (or not found): the cube of the first half-side with a zero, at least kUnboundedHalfSide.
    h = kUnboundedHalfSide;
    for (double t = kFirstHalfSide; t <= kLastHalfSide; t *= 2.0)
      if ((zero = sample_zero_set(shape, t)).found) {
        h = std::max(t, kUnboundedHalfSide);
        break;
      }
    zero = sample_zero_set(shape, h);
  }
  SurfaceBounds box = cube(Vec3::Zero(), h);
  if (closed) {
    const double spare = (zero.hi - zero.lo).maxCoeff() / 8.0;
    for (int k = 0; k < 3; ++k) box[k] = {zero.lo[k] - spare, zero.hi[k] + spare};
  } else if (formula->form() == FormulaSurfaceForm::graph) {
    // A graph: z over the range its height takes on the square. A steep one (the range more than
    // twice the square's side, as a monkey saddle's 4h³) on a smaller square, down to h/8, so that
    // the picture is not its walls; z within the cube still.
    const auto range = [&](double half) {
      double z0 = std::numeric_limits<double>::infinity(), z1 = -z0;
      for (int i = 0; i <= kSamples; ++i)
        for (int j = 0; j <= kSamples; ++j) {
          const double z =
              formula->height(-half + 2.0 * half * i / kSamples, -half + 2.0 * half * j / kSamples);
          if (std::isfinite(z)) z0 = std::min(z0, z), z1 = std::max(z1, z);
        }
      return std::pair{z0, z1};
    };
    auto [z0, z1] = range(h);
    for (const double least = h / 8; z1 - z0 > 4.0 * h && h > least;) std::tie(z0, z1) = range(h /= 2);
    box = cube(Vec3::Zero(), h);
    if (z0 <= z1) {
      const double spare = std::max(0.125 * (z1 - z0), 0.05 * h);
      box[2] = {std::max(-h, z0 - spare), std::min(h, z1 + spare)};
    }
  }
  if (surface.bounds) box = *surface.bounds;
  set_box(shape, box);
  shape.closed = closed && !surface.bounds;
  // At most a third of the box's half-size (a gently curved surface's 1/√max|K| would make a body
  // the size of the picture), and of a closed surface's least half-extent.
  double smallest = shape.length / 3.0;
  if (closed) smallest = std::min(smallest, 0.5 * (zero.hi - zero.lo).minCoeff());
  shape.feature =
      curvature_feature(shape, zero.near, shape.length / 32.0, std::max(smallest, shape.length / 32.0));
  return shape;
}

SurfaceModel profile_shape_of(const Surface& surface) {
  const RevolutionSurface s = revolution_surface(surface);
  const RevolutionEntry& entry = revolution_entry(s.kind);
  const ProfilePicture picture = entry.picture(s);
  const ProfileDomain domain = entry.domain(s);
  SurfaceModel shape;
  shape.profile = s;
  shape.implicit = std::make_shared<const RevolutionImplicit>(s);
  set_box(shape, cube(Vec3::Zero(), picture.length));
  shape.feature = picture.feature;
  shape.closed = domain.periodic || (domain.axis_at_min && domain.axis_at_max);
  return shape;
}

// S², H², the plane: K = σ/R², drawn as the ball of radius R.
SurfaceModel constant_curvature_model(const Surface& surface) {
  SurfaceModel model;
  model.curvature = curvature(surface);
  set_box(model, cube(Vec3::Zero(), surface.radius));
  model.feature = surface.radius;
  model.closed = offers(surface, Offer::positive_curvature);
  return model;
}

// The model of a surface, before it is shared.
SurfaceModel resolve(const Surface& surface) {
  SurfaceModel model = offers(surface, Offer::formula)         ? formula_shape(surface)
                       : offers(surface, Offer::profile_chart) ? profile_shape_of(surface)
                                                               : constant_curvature_model(surface);
  model.surface = surface;
  model.offered = offers_of(surface.kind);
  if (model.implicit) model.curvature = std::numeric_limits<double>::quiet_NaN();
  return model;
}

}  // namespace

// Compared in place (a frame asks for its model at every point of a body's
// ellipse: copying the formula's text for a key was a third of a formula frame's building).
bool same_model(const Surface& a, const Surface& b) {
  const auto profile = [](const Surface& s) {
    return std::tie(s.kind, s.radius, s.tube_radius, s.center_radius, s.equatorial_radius, s.polar_radius,
                    s.height, s.width, s.neck_radius);
  };
  if (profile(a) != profile(b)) return false;
  return !offers(a, Offer::formula) ||
         (a.F == b.F && a.z == b.z && a.parameters == b.parameters && a.bounds == b.bounds);
}

std::shared_ptr<const SurfaceModel> surface_model_of(const Surface& surface) {
  if (static_cast<unsigned>(surface.kind) >= std::size(kSurfaceCatalog))
    throw std::logic_error("surface_model_of: a kind outside the catalog");
  static std::mutex mutex;
  static std::list<std::shared_ptr<const SurfaceModel>> cache;  // most recent first
  {
    const std::lock_guard lock(mutex);
    for (auto it = cache.begin(); it != cache.end(); ++it)
      if (same_model((*it)->surface, surface)) {
        cache.splice(cache.begin(), cache, it);
        return cache.front();
      }
  }
  auto shape = std::make_shared<const SurfaceModel>(resolve(surface));
  const std::lock_guard lock(mutex);
  cache.push_front(shape);
  if (cache.size() > kSurfaceModelCacheSize) cache.pop_back();
  return shape;
}

}  // namespace spinfold
