#include "render/implicit_mesh.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "engine/surface_geodesics.h"

namespace spinfold::render {

namespace {

// Samples of F beyond float's range, or not finite, are the grid's background: no surface there.
constexpr float kBackground = 1e30f;

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// The triangles cut at the box's six faces (Sutherland–Hodgman, one face after another): a triangle
// inside is kept, one outside dropped, one across a face cut into the polygon inside, fanned into
// triangles. A point where an edge crosses a face is made once per edge and face (so neighbouring
// triangles share it: no crack), on the face and on F = 0 (Newton within the face's plane).
void cut_at_box(ImplicitMesh& mesh, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                const SurfaceBounds& box, const SurfaceModel& shape, double d) {
  struct Plane {
    int axis;
    double at, sign;  // inside: sign·(X[axis] − at) ≥ 0
  };
  std::vector<Plane> planes;
  for (int k = 0; k < 3; ++k) planes.push_back({k, box[k][0], 1.0}), planes.push_back({k, box[k][1], -1.0});
  std::map<std::tuple<std::uint32_t, std::uint32_t, int>, std::uint32_t> crossings;
  const auto crossing = [&](std::uint32_t a, std::uint32_t b, int plane) {
    const auto key = std::tuple{std::min(a, b), std::max(a, b), plane};
    if (const auto it = crossings.find(key); it != crossings.end()) return it->second;
    const Plane& p = planes[static_cast<std::size_t>(plane)];
    const Vec3 &A = mesh.points[std::get<0>(key)], &B = mesh.points[std::get<1>(key)];
    const double s = (p.at - A[p.axis]) / (B[p.axis] - A[p.axis]);
    // Onto F = 0 by Newton within the face's plane (∇F's part along it), so the cut is on both.
    Vec3 X = A + s * (B - A);
    X[p.axis] = p.at;
    for (int i = 0; i < 16; ++i) {
      const ImplicitPoint q = shape.implicit->at(X);
      Vec3 g = q.gradient;
      g[p.axis] = 0.0;
      const double g2 = g.squaredNorm();
      if (!(g2 > 0.0) || !std::isfinite(q.F)) break;
      const Vec3 step = (q.F / g2) * g;
      if (!(step.norm() < d)) break;  // the surface is tangent to the face here: keep the chord's point
      X -= step;
      if (step.norm() <= 1e-15 * (1.0 + X.norm())) break;
    }
    mesh.points.push_back(X);
    const ImplicitPoint at = shape.implicit->at(X);
    const double g = at.gradient.norm();
    mesh.normals.push_back(g > 0.0 && std::isfinite(g) ? Vec3(at.gradient / g) : mesh.normals[a]);
    const double K = bordered_hessian_curvature(at);
    mesh.K.push_back(std::isfinite(K) ? K : mesh.K[a]);
    const auto index = static_cast<std::uint32_t>(mesh.points.size() - 1);
    crossings.emplace(key, index);
    return index;
  };
  const auto inside = [&](std::uint32_t v, const Plane& p) {
    return p.sign * (mesh.points[v][p.axis] - p.at) >= 0.0;
  };
  for (const auto& t : triangles) {
    std::vector<std::uint32_t> polygon(t.begin(), t.end());
    for (int plane = 0; plane < 6 && !polygon.empty(); ++plane) {
      const Plane& p = planes[static_cast<std::size_t>(plane)];
      if (std::all_of(polygon.begin(), polygon.end(), [&](std::uint32_t v) { return inside(v, p); }))
        continue;
      std::vector<std::uint32_t> next;
      for (std::size_t i = 0; i < polygon.size(); ++i) {
        const std::uint32_t a = polygon[i], b = polygon[(i + 1) % polygon.size()];
        if (inside(a, p)) next.push_back(a);
        if (inside(a, p) != inside(b, p)) next.push_back(crossing(a, b, plane));
      }
      polygon = std::move(next);
    }
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
      if (polygon[0] != polygon[i] && polygon[i] != polygon[i + 1] && polygon[0] != polygon[i + 1])
        mesh.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
  }
}

}  // namespace

int mesh_cells(const SurfaceModel& shape) {
  double longest = 0.0;
  for (const auto& side : shape.box) longest = std::max(longest, side[1] - side[0]);
  const double cells = std::ceil(kCubesPerFeature * longest / shape.feature);
  return std::isfinite(cells)
             ? static_cast<int>(std::clamp(cells, double{kLeastMeshCells}, double{kMostMeshCells}))
             : kMeshCells;
}

ImplicitMesh mesh_implicit_surface(const SurfaceModel& shape, const SurfaceBounds& box, int cells,
                                   double adaptivity) {
  initialize_openvdb();
  cells = std::clamp(cells, 2, kMaxMeshCells);
  ImplicitMesh mesh;
  double longest = 0.0;
  for (const auto& side : box) longest = std::max(longest, side[1] - side[0]);
  if (!(longest > 0.0) || !std::isfinite(longest)) return mesh;
  const double d = longest / cells;
  mesh.cell = d;
  // The grid reaches a cube beyond the box on every side, so that the mesh covers the box whole and
  // is cut at its faces (below) instead of ending in the ragged row of its last cubes.
  std::array<int, 3> n{};
  for (int k = 0; k < 3; ++k)
    n[k] = std::clamp(static_cast<int>(std::ceil((box[k][1] - box[k][0]) / d - 1e-9)), 1, kMaxMeshCells) + 2;
  const Vec3 origin = Vec3(box[0][0], box[1][0], box[2][0]) - Vec3::Constant(d);
  const auto world = [&](double i, double j, double k) -> Vec3 { return origin + d * Vec3(i, j, k); };

  const openvdb::CoordBBox bounds(openvdb::Coord(0, 0, 0), openvdb::Coord(n[0], n[1], n[2]));
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(bounds);
  for (int i = 0; i <= n[0]; ++i)
    for (int j = 0; j <= n[1]; ++j)
      for (int k = 0; k <= n[2]; ++k) {
        const double F = shape.value(world(i, j, k));
        dense.setValue(i, j, k,
                       std::isfinite(F) && std::abs(F) < kBackground ? static_cast<float>(F) : kBackground);
      }
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  // All of OpenVDB's work, the grid's life included (its tree is cleared in parallel), on the calling
  // thread alone (an arena of one slot, the copy serial): a frame is drawn on one of the server's
  // render threads, each already a core's work, and no TBB worker touches what this function owns
  // (ThreadSanitizer cannot see TBB's own synchronisation, and reported its workers as races).
  tbb::task_arena one_thread(1);
  one_thread.execute([&] {
    const openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(kBackground);
    openvdb::tools::copyFromDense(dense, *grid, 0.0f, /*serial=*/true);
    openvdb::tools::volumeToMesh(*grid, points, triangles, quads, 0.0, adaptivity, true);
  });

  // Each vertex onto F = 0; those Newton cannot bring there within a cube, or that land more than a
  // cube outside the box (the caps on the grid's faces), are dropped.
  constexpr std::uint32_t kDropped = ~0u;
  std::vector<std::uint32_t> index(points.size(), kDropped);
  const auto add_point = [&](const Vec3& X) -> std::uint32_t {
    const ImplicitPoint p = shape.implicit->at(X);
    const double g = p.gradient.norm();
    if (!X.allFinite() || !(g > 0.0) || !std::isfinite(g) || !(std::abs(p.F) / g <= 1e-6 * d))
      return kDropped;
    mesh.points.push_back(X);
    mesh.normals.push_back(p.gradient / g);
    mesh.K.push_back(bordered_hessian_curvature(p));
    return static_cast<std::uint32_t>(mesh.points.size() - 1);
  };
  for (std::size_t v = 0; v < points.size(); ++v) {
    const Vec3 guess = world(points[v].x(), points[v].y(), points[v].z());
    const Vec3 X = project_onto_surface(*shape.implicit, guess);
    if (!X.allFinite() || (X - guess).norm() > d) continue;
    bool near = true;
    for (int k = 0; k < 3; ++k) near = near && X[k] >= box[k][0] - d && X[k] <= box[k][1] + d;
    if (near) index[v] = add_point(X);
  }
  std::vector<std::array<std::uint32_t, 3>> uncut;
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    a = index[a], b = index[b], c = index[c];
    if (a == kDropped || b == kDropped || c == kDropped || a == b || b == c || a == c) return;
    const Vec3 face = (mesh.points[b] - mesh.points[a]).cross(mesh.points[c] - mesh.points[a]);
    if (face.dot(mesh.normals[a] + mesh.normals[b] + mesh.normals[c]) < 0.0) std::swap(b, c);
    uncut.push_back({a, b, c});
  };
  for (const openvdb::Vec3I& t : triangles) add(t[0], t[1], t[2]);
  // A quad split along its shorter diagonal: the two triangles are the less skinny pair.
  for (const openvdb::Vec4I& q : quads) {
    const auto length = [&](std::uint32_t a, std::uint32_t b) {
      return index[a] == kDropped || index[b] == kDropped
                 ? 0.0
                 : (mesh.points[index[a]] - mesh.points[index[b]]).squaredNorm();
    };
    if (length(q[0], q[2]) <= length(q[1], q[3]))
      add(q[0], q[1], q[2]), add(q[0], q[2], q[3]);
    else
      add(q[0], q[1], q[3]), add(q[1], q[2], q[3]);
  }
  cut_at_box(mesh, uncut, box, shape, d);
  return mesh;
}

}  // namespace spinfold::render
