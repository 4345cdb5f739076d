// The formula view (render/views/formula.cpp): formula surfaces open in it; its mesh and grid lie on
// the surface; the level curves are where x, y or z is a multiple of the step and the K = 0 curves
// where K changes sign; the curvature tint has K's sign; the camera shows a main body at random places
// of every example surface; a body beyond the box gets a patch under it; the body's ellipse lies on
// the surface; the mesh cache is bounded.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <set>

#include "engine/formula_examples.h"
#include "engine/formula_surface.h"
#include "engine/surface_geodesics.h"
#include "engine/surface_model.h"
#include "render/implicit_mesh.h"
#include "render/view_table.h"
#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/profile_drawing.h"
#include "render/views/view_model.h"
#include "tests/engine/formula_surfaces.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

using testing::in_frame;
using testing::pixel_of;

const ViewModel& formula() {
  return view_model(ViewKind::formula);
}

Surface implicit(const std::string& F, SurfaceParameters parameters = {}) {
  return test::implicit_surface(F, std::move(parameters));
}
Surface graph(const std::string& z, SurfaceParameters parameters = {}) {
  return test::graph_surface(z, std::move(parameters));
}

// The examples of the page's menu (engine/formula_examples.h): every one.
std::vector<Surface> examples() {
  std::vector<Surface> out;
  for (const FormulaExample& example : formula_examples()) out.push_back(example_surface(example));
  return out;
}

Vec3 embedded(const Surface& surface, const glm::vec3& w) {
  const auto shape = surface_model_of(surface);
  return Vec3(w.x, w.y, w.z) * shape->length + shape->centre;
}

double off_surface(const Surface& surface, const Vec3& X) {
  const ImplicitPoint p = surface_model_of(surface)->implicit->at(X);
  return std::abs(p.F) / p.gradient.norm();
}

// A body at X (brought onto the surface) with L = diag(λ, μ) in the convention's frame there.
Snapshot body_at(const Surface& surface, const Vec3& guess, double lambda = 1.0, double mu = 0.7) {
  Snapshot s;
  s.surface = surface;
  s.model = surface_model_of(surface);
  const auto& shape = s.model;
  const Vec3 X = project_onto_surface(*shape->implicit, guess);
  const Vec3 n = embedded_normal(*shape->implicit, X);
  Vec3 E1 = Vec3::UnitX() - Vec3::UnitX().dot(n) * n;
  if (E1.norm() < 0.1) E1 = Vec3::UnitY() - Vec3::UnitY().dot(n) * n;
  E1.normalize();
  testing::add_body(s, X, E1, n.cross(E1), lambda, mu);
  return s;
}

TEST(FormulaView, FormulaSurfacesOpenInItAndNoOtherViewShowsThem) {
  for (const SurfaceKind kind : {SurfaceKind::implicit, SurfaceKind::graph}) {
    EXPECT_EQ(default_view(kind), ViewKind::formula);
    EXPECT_FALSE(view_unsupported_reason(ViewKind::formula, kind));
    EXPECT_EQ(*view_unsupported_reason(ViewKind::revolution, kind),
              "the " + std::string(enum_name(kind)) + " is shown in these views: formula");
  }
  EXPECT_TRUE(view_unsupported_reason(ViewKind::formula, SurfaceKind::torus));
}

TEST(FormulaView, TheMeshAndTheGridLieOnTheSurface) {
  for (const Surface& surface : examples()) {
    const auto g = static_geometry(surface, ViewKind::formula);
    const std::string what = formula_text(surface);
    ASSERT_GT(g->surface.size(), 3000u) << what;
    ASSERT_FALSE(g->grid.empty()) << what;
    ASSERT_FALSE(g->edges.empty()) << what;
    const double l = surface_model_of(surface)->length;
    double worst = 0.0;
    for (const LitVertex& v : g->surface)
      worst = std::max(worst, off_surface(surface, embedded(surface, v.position)));
    EXPECT_LT(worst / l, 1e-5) << what;  // float vertices: rounding of ~1e-7 of the length
    // The grid's points are on the mesh's faces: within their sagitta of the surface, a quarter of a
    // cube where the genus-2 surface's tube is thinnest (its radius ~2 cubes).
    double longest = 0.0;
    for (const auto& side : surface_model_of(surface)->box) longest = std::max(longest, side[1] - side[0]);
    const double cell = longest / mesh_cells(*surface_model_of(surface));
    worst = 0.0;
    for (const Vertex& v : g->grid)
      worst = std::max(worst, off_surface(surface, embedded(surface, v.position)));
    EXPECT_LT(worst, 0.25 * cell) << what;
  }
}

TEST(FormulaView, TheGridIsTheLevelCurvesOfXYZAndTheZeroCurvatureCurves) {
  // On the egg crate z = a sin x sin y, K changes sign; each grid point has x, y or z on the step's
  // lattice, or K = 0 near it (to the mesh's resolution).
  const Surface crate = graph("a*sin(x)*sin(y)", {{"a", 0.4}});
  const auto shape = surface_model_of(crate);
  const auto g = static_geometry(crate, ViewKind::formula);
  int levels = 0, zeros = 0;
  for (const Vertex& v : g->grid) {
    const Vec3 X = embedded(crate, v.position);
    if (v.color == kZeroCurvatureColor) {
      const double K =
          bordered_hessian_curvature(shape->implicit->at(project_onto_surface(*shape->implicit, X)));
      EXPECT_LT(std::abs(K), 0.05) << X.transpose();  // |K| ≤ a² = 0.16 on the crate
      ++zeros;
      continue;
    }
    const double step = 0.5;  // a quarter of the box's half-size 2, rounded to 1, 2 or 5 × 10^k
    double nearest = 1.0;
    for (int k = 0; k < 3; ++k) nearest = std::min(nearest, std::abs(std::remainder(X[k], step)));
    EXPECT_LT(nearest, 1e-5) << X.transpose();
    ++levels;
  }
  EXPECT_GT(levels, 500);
  EXPECT_GT(zeros, 100);
}

TEST(FormulaView, TheCurvatureTintHasTheSignOfK) {
  const Surface crate = graph("a*sin(x)*sin(y)", {{"a", 0.4}});
  const auto shape = surface_model_of(crate);
  int warm = 0, cool = 0;
  for (const LitVertex& v : static_geometry(crate, ViewKind::formula)->surface) {
    const double K = bordered_hessian_curvature(shape->implicit->at(embedded(crate, v.position)));
    if (std::abs(K) < 0.02) continue;
    if (K > 0) {
      EXPECT_GT(v.tint.r, v.tint.b);
      ++warm;
    } else {
      EXPECT_GT(v.tint.b, v.tint.r);
      ++cool;
    }
  }
  // The crate's K > 0 and K < 0 parts are alike in area (each sign on a good share of the vertices).
  EXPECT_GT(warm, 100);
  EXPECT_GT(cool, 100);
  EXPECT_GT(warm, 0.2 * (warm + cool));
  EXPECT_GT(cool, 0.2 * (warm + cool));
}

// A property over random places on every example: the aimed camera puts the main body in the frame,
// unhidden by the surface, at the three frame sizes the UI uses.
TEST(FormulaView, TheCameraShowsABodyAnywhereOnEverySurface) {
  std::mt19937_64 random(49);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (const Surface& surface : examples()) {
    const auto shape = surface_model_of(surface);
    for (int trial = 0; trial < 12; ++trial) {
      const Vec3 guess = shape->centre + 0.8 * shape->length * Vec3(uni(random), uni(random), uni(random));
      const Snapshot s = body_at(surface, guess);
      if (!s.bodies[0].X.allFinite() || !formula().on_view(surface, s.bodies[0].X)) continue;
      for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1280, 720}, std::pair{390, 520}}) {
        ViewOptions view;
        view.kind = ViewKind::formula;
        view.width = w, view.height = h;
        view.scale = 0.25 * body_scale_length(view.kind, s.surface);
        aim_camera_at_body(view, s);
        const FrameScene scene = build_scene(s, view);
        const std::string what = formula_text(surface) + " at " + std::to_string(s.bodies[0].X.x()) + ", " +
                                 std::to_string(s.bodies[0].X.y()) + ", " + std::to_string(s.bodies[0].X.z());
        EXPECT_TRUE(in_frame(pixel_of(scene, view, s.surface, s.bodies[0].X), view)) << what;
        EXPECT_TRUE(shows_main_body(view, s)) << what << " " << w << "x" << h;
      }
    }
  }
}

TEST(FormulaView, BeyondTheBoxAPatchOfTheSurfaceIsDrawnUnderTheBody) {
  Surface plane = graph("0.1*x");
  plane.bounds = SurfaceBounds{{{-1.0, 1.0}, {-1.0, 1.0}, {-1.0, 1.0}}};
  const Snapshot inside = body_at(plane, Vec3(0.2, 0.3, 0.0));
  EXPECT_FALSE(formula().patch_at(inside));
  const Snapshot outside = body_at(plane, Vec3(6.0, 0.3, 0.0));
  ASSERT_FALSE(formula().on_view(plane, outside.bodies[0].X));
  const auto at = formula().patch_at(outside);
  ASSERT_TRUE(at);
  EXPECT_TRUE(formula().paints_surface_at(outside, outside.bodies[0].X));
  ViewOptions view;
  view.kind = ViewKind::formula;
  aim_camera_at_body(view, outside);
  const FrameScene scene = build_scene(outside, view);
  const auto piece = static_geometry(plane, ViewKind::formula);
  ASSERT_GT(scene.statics->surface.size(), piece->surface.size());
  double nearest = std::numeric_limits<double>::infinity(), worst = 0.0;
  for (std::size_t i = piece->surface.size(); i < scene.statics->surface.size(); ++i) {
    const Vec3 X = embedded(plane, scene.statics->surface[i].position);
    worst = std::max(worst, off_surface(plane, X));
    nearest = std::min(nearest, (X - outside.bodies[0].X).norm());
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_LT(nearest, surface_model_of(plane)->feature);
  EXPECT_TRUE(in_frame(pixel_of(scene, view, plane, outside.bodies[0].X), view));
  // The HUD says where the body is.
  const auto lines = readout_lines(outside, view);
  EXPECT_NE(std::find(lines.begin(), lines.end(), "body 1 is beyond the box drawn whole (surface.bounds)"),
            lines.end());
}

TEST(FormulaView, TheBodysEllipseLiesOnTheSurface) {
  for (const Surface& surface : examples()) {
    const auto shape = surface_model_of(surface);
    const Snapshot s = body_at(surface, shape->centre + Vec3(0.3, 0.2, 0.4) * shape->length, 1.3, 0.6);
    for (const Vec3& P : ellipse_points(s.surface, s.bodies[0], 0.3 * shape->feature, 32))
      EXPECT_LT(off_surface(s.surface, P), 1e-12) << formula_text(surface);
  }
}

TEST(FormulaView, TheMeshCacheIsBoundedInEntriesAndBytes) {
  std::vector<std::weak_ptr<const StaticGeometry>> built;
  std::size_t bytes = 0;
  for (int i = 0; i < 12; ++i) {
    const auto g =
        static_geometry(implicit("x^2 + y^2 + z^2 - r^2", {{"r", 1.0 + 0.1 * i}}), ViewKind::formula);
    bytes = std::max(bytes, g->surface.size() * sizeof(LitVertex));
    built.push_back(g);
  }
  int alive = 0;
  for (const auto& w : built) alive += !w.expired();
  EXPECT_LE(alive, static_cast<int>(kStaticGeometryCache));
  EXPECT_LE(static_cast<double>(alive) * static_cast<double>(bytes),
            1.5 * static_cast<double>(kStaticGeometryBytes));
  EXPECT_FALSE(built.back().expired());
}

}  // namespace
}  // namespace spinfold::render
