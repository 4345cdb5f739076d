// The mesh of a formula surface (render/implicit_mesh.h): on the surface, with its topology (no crack:
// the Euler characteristic of a closed surface of genus g is 2 − 2g, each edge bounds two triangles),
// no slivers to speak of, exact normals, nothing where F is undefined, and no cap on the box's faces.
#include "render/implicit_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "engine/formula_surface.h"
#include "tests/engine/formula_surfaces.h"

namespace spinfold::render {
namespace {

Surface implicit(const std::string& F) {
  return test::implicit_surface(F);
}

struct Topology {
  long vertices = 0, edges = 0, faces = 0;
  long open_edges = 0, crowded_edges = 0;  // bounding one triangle, or three or more
  long euler() const { return vertices - edges + faces; }
};
Topology topology_of(const ImplicitMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  std::set<std::uint32_t> used;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      ++edges[std::minmax(t[k], t[(k + 1) % 3])];
      used.insert(t[k]);
    }
  Topology top;
  top.vertices = static_cast<long>(used.size());
  top.edges = static_cast<long>(edges.size());
  top.faces = static_cast<long>(mesh.triangles.size());
  for (const auto& [edge, count] : edges) top.open_edges += count == 1, top.crowded_edges += count > 2;
  return top;
}

// The smallest angle of a triangle [degrees].
double smallest_angle(const ImplicitMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  double least = 180.0;
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = mesh.points[t[(k + 1) % 3]] - mesh.points[t[k]];
    const Vec3 b = mesh.points[t[(k + 2) % 3]] - mesh.points[t[k]];
    least =
        std::min(least, std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI);
  }
  return least;
}

void expect_on_the_surface(const SurfaceModel& shape, const ImplicitMesh& mesh) {
  ASSERT_FALSE(mesh.triangles.empty());
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    const ImplicitPoint p = shape.implicit->at(mesh.points[i]);
    ASSERT_LT(std::abs(p.F) / p.gradient.norm(), 1e-10 * shape.length) << i;
    ASSERT_NEAR(mesh.normals[i].dot(p.gradient.normalized()), 1.0, 1e-12) << i;
    ASSERT_NEAR(mesh.K[i], bordered_hessian_curvature(p), 1e-12 * std::max(1.0, std::abs(mesh.K[i])));
  }
  // Every face turned as the normals are.
  for (const auto& t : mesh.triangles) {
    const Vec3 face = (mesh.points[t[1]] - mesh.points[t[0]]).cross(mesh.points[t[2]] - mesh.points[t[0]]);
    ASSERT_GE(face.dot(mesh.normals[t[0]] + mesh.normals[t[1]] + mesh.normals[t[2]]), 0.0);
  }
}

// Closed surfaces of genus 0, 1 and 2 at the default resolution and the view's: no crack, the right
// topology, and fewer than 1% of the triangles with an angle under 10° (none under 1°).
TEST(ImplicitMesh, ClosedSurfacesHaveNoCrackAndTheirGenus) {
  struct Case {
    const char* F;
    long euler;
  };
  const Case cases[] = {
      {"x^2/4 + y^2/1.96 + z^2/0.81 - 1", 2},                         // triaxial ellipsoid
      {"(x^2 + y^2 + z^2 + 2.5^2 - 1)^2 - 4*2.5^2*(x^2 + y^2)", 0},   // torus c = 2.5, a = 1
      {"((x^2 + y^2)^2 - 2*(x^2 - y^2))^2 + (z/0.5)^2 - 0.6^2", -2},  // genus 2 (§7)
      {"x^4 + y^4 + z^4 - 1", 2},                                     // a rounded cube
  };
  for (const Case& c : cases) {
    const auto shape = surface_model_of(implicit(c.F));
    ASSERT_TRUE(shape->closed) << c.F;
    // At the view's resolution too (mesh_cells: 6 cubes a feature).
    for (const int cells : {kMeshCells, mesh_cells(*shape)}) {
      const Topology top = topology_of(mesh_implicit_surface(*shape, shape->box, cells));
      EXPECT_EQ(top.open_edges, 0) << c.F << " at " << cells;
      EXPECT_EQ(top.crowded_edges, 0) << c.F << " at " << cells;
      EXPECT_EQ(top.euler(), c.euler) << c.F << " at " << cells;
    }
    const ImplicitMesh mesh = mesh_implicit_surface(*shape, shape->box);
    expect_on_the_surface(*shape, mesh);
    long thin = 0;
    double least = 180.0;
    for (const auto& t : mesh.triangles) {
      const double a = smallest_angle(mesh, t);
      thin += a < 10.0, least = std::min(least, a);
    }
    EXPECT_LT(static_cast<double>(thin), 0.01 * static_cast<double>(mesh.triangles.size())) << c.F;
    EXPECT_GT(least, 1.0) << c.F;
  }
}

TEST(ImplicitMesh, NothingIsDrawnWhereTheFormulaIsUndefinedNorOnTheBoxFaces) {
  // The upper hemisphere as a graph: z = √(1 − x² − y²) is undefined beyond the unit disk.
  Surface hemisphere;
  hemisphere.kind = SurfaceKind::graph;
  hemisphere.z = "sqrt(1 - x^2 - y^2)";
  const auto shape = surface_model_of(hemisphere);
  const ImplicitMesh mesh = mesh_implicit_surface(*shape, shape->box);
  expect_on_the_surface(*shape, mesh);
  for (const Vec3& X : mesh.points) EXPECT_LE(std::hypot(X.x(), X.y()), 1.0 + 1e-9);
  // The plane z = 0.3 cut by its box: no vertex off the plane (a cap on the box's faces, where F < 0,
  // would put some there), and the sheet spans the box.
  Surface plane;
  plane.kind = SurfaceKind::graph;
  plane.z = "0.3";
  const auto flat = surface_model_of(plane);
  const ImplicitMesh sheet = mesh_implicit_surface(*flat, flat->box);
  double reach = 0.0;
  for (const auto& t : sheet.triangles)
    for (const std::uint32_t v : t) {
      const Vec3& X = sheet.points[v];
      EXPECT_NEAR(X.z(), 0.3, 1e-12);
      reach = std::max(reach, std::max(std::abs(X.x()), std::abs(X.y())));
    }
  EXPECT_NEAR(reach, 2.0, 1e-12);            // cut at the box's faces, not ragged short of them
  EXPECT_EQ(topology_of(sheet).euler(), 1);  // a disk
  EXPECT_EQ(topology_of(sheet).crowded_edges, 0);
  // Its border is the square's: every open edge lies on a face of the box.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (const auto& t : sheet.triangles)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
  for (const auto& [edge, n] : count) {
    if (n != 1) continue;
    for (const std::uint32_t v : {edge.first, edge.second}) {
      EXPECT_NEAR(std::max(std::abs(sheet.points[v].x()), std::abs(sheet.points[v].y())), 2.0, 1e-12);
    }
  }
}

TEST(ImplicitMesh, TheResolutionIsBoundedAndAnEmptyBoxMeshesNothing) {
  const auto shape = surface_model_of(implicit("x^2 + y^2 + z^2 - 1"));
  const ImplicitMesh coarse = mesh_implicit_surface(*shape, shape->box, 8);
  const ImplicitMesh capped = mesh_implicit_surface(*shape, shape->box, 100000);
  EXPECT_GT(coarse.triangles.size(), 0u);
  EXPECT_NEAR(capped.cell, 2.0 * shape->length / kMaxMeshCells, 1e-12);
  const SurfaceBounds far{{{5.0, 6.0}, {5.0, 6.0}, {5.0, 6.0}}};
  EXPECT_TRUE(mesh_implicit_surface(*shape, far).triangles.empty());
  const SurfaceBounds flat{{{0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}}};
  EXPECT_TRUE(mesh_implicit_surface(*shape, flat).triangles.empty());
}

}  // namespace
}  // namespace spinfold::render
