#include "render/views/profile_drawing.h"

#include <algorithm>
#include <cmath>

namespace spinfold::render {

ProfileShape profile_shape(const Surface& surface) {
  const RevolutionSurface s = revolution_surface(surface);
  const RevolutionEntry& entry = revolution_entry(s.kind);
  return {s, &entry, entry.picture(s)};
}

bool on_drawn_piece(const Surface& surface, const Vec3& X) {
  const ProfileShape shape = profile_shape(surface);
  const double u = shape.entry->u_of(shape.surface, X);
  const double margin = 1e-9 * (shape.picture.u_max - shape.picture.u_min);
  return u >= shape.picture.u_min - margin && u <= shape.picture.u_max + margin;
}

bool within_drawing_range(const Surface& surface, const Vec3& X) {
  return X.allFinite() && X.norm() <= kMaxDrawnDistance * profile_shape(surface).picture.length;
}

std::string_view off_drawn_piece_note(const Surface& surface, const Vec3& X) {
  return within_drawing_range(surface, X) ? kOffDrawnPieceNote : kBeyondDrawingNote;
}

std::vector<double> zero_curvature_parallels(const ProfileShape& shape) {
  std::vector<double> zeros;
  const int n = 1024;
  const double lo = shape.picture.u_min, hi = shape.picture.u_max;
  for (int i = 0; i < n; ++i) {
    double a = lo + (hi - lo) * i / n, b = lo + (hi - lo) * (i + 1) / n;
    if ((shape.K(a) > 0.0) == (shape.K(b) > 0.0)) continue;
    for (int k = 0; k < 60; ++k) {
      const double m = 0.5 * (a + b);
      ((shape.K(a) > 0.0) == (shape.K(m) > 0.0) ? a : b) = m;
    }
    zeros.push_back(0.5 * (a + b));
  }
  return zeros;
}

std::vector<double> grid_parallels(const ProfileShape& shape) {
  const double lo = shape.picture.u_min, hi = shape.picture.u_max, step = shape.picture.grid_step;
  std::vector<double> us;
  const double first = std::ceil(lo / step - 1e-9) * step;
  // Counted, not stepped: a step below the rounding of u would never move it.
  const double count = std::floor((hi + 1e-9 * step - first) / step) + 1.0;
  for (int k = 0; k < std::min(count, 1024.0); ++k) {
    const double u = first + k * step;
    if (shape.entry->profile(shape.surface, u).rho > 1e-9 * shape.picture.length) us.push_back(u);
  }
  return us;
}

double largest_curvature(const ProfileShape& shape, int samples) {
  double full = 0.0;
  for (int i = 0; i <= samples; ++i)
    full = std::max(full, std::abs(shape.K(shape.picture.u_min +
                                           (shape.picture.u_max - shape.picture.u_min) * i / samples)));
  return full > 0.0 ? full : 1.0;
}

}  // namespace spinfold::render
