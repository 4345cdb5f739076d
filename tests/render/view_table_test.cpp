// The view table: one row per view, its metadata and implementation consistent, and every view
// through the ViewModel interface drawing and aiming at a body on each surface it shows.
#include "render/view_table.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "engine/surface_geodesics.h"
#include "engine/surface_model.h"
#include "render/scene_builder.h"
#include "render/views/view_model.h"
#include "views/view_test_support.h"

namespace spinfold::render {
namespace {

using testing::body_at;
using testing::body_on;
using testing::in_frame;
using testing::pixel_of;

constexpr ViewKind kAllKinds[] = {ViewKind::sphere,      ViewKind::hyperboloid, ViewKind::disk,
                                  ViewKind::plane,       ViewKind::klein,       ViewKind::halfplane,
                                  ViewKind::tractricoid, ViewKind::conformal,   ViewKind::revolution,
                                  ViewKind::chart,       ViewKind::formula};
constexpr SurfaceKind kSurfaces[] = {SurfaceKind::sphere,   SurfaceKind::pseudosphere, SurfaceKind::plane,
                                     SurfaceKind::torus,    SurfaceKind::spheroid,     SurfaceKind::bump,
                                     SurfaceKind::catenoid, SurfaceKind::implicit,     SurfaceKind::graph};

// A body off every special point of the surface, with a deformed frame (on a formula surface, the
// default formula's: the unit sphere, the plane z = 0).
Snapshot sample_body(SurfaceKind surface) {
  if (offers(surface, Offer::formula)) {
    Snapshot s;
    s.surface.kind = surface;
    s.model = surface_model_of(s.surface);
    const auto& shape = s.model;
    const Vec3 X = project_onto_surface(*shape->implicit, Vec3(0.5, 0.3, 0.6));
    const Vec3 n = embedded_normal(*shape->implicit, X);
    const Vec3 E1 = (Vec3::UnitX() - Vec3::UnitX().dot(n) * n).normalized();
    testing::add_body(s, X, E1, n.cross(E1), 1.2, 0.8);
    return s;
  }
  return offers(surface, Offer::implicit_equation) ? body_on(surface, 0.7, 0.7, 1.2, 0.8)
                                                   : body_at(surface, 2.0, 0.4, 0.7, 1.2, 0.8);
}

// The first surface a view shows.
SurfaceKind first_shown(const ViewInfo& v) {
  for (const SurfaceKind s : kSurfaces)
    if (shows(v, s)) return s;
  return SurfaceKind::sphere;
}

TEST(ViewTable, EveryKindHasExactlyOneRowAndViewsListsTheRowsInOrder) {
  const auto table = view_table();
  ASSERT_EQ(table.size(), std::size(kAllKinds));
  ASSERT_EQ(views().size(), table.size());
  for (const ViewKind kind : kAllKinds) {
    int rows = 0;
    for (const ViewRow& row : table) rows += row.info.kind == kind;
    EXPECT_EQ(rows, 1) << view_name(kind);
  }
  for (std::size_t i = 0; i < table.size(); ++i) {
    EXPECT_EQ(views()[i].name, table[i].info.name);
    EXPECT_EQ(views()[i].kind, table[i].info.kind);
    EXPECT_EQ(&view_info(table[i].info.kind), &views()[i]);
  }
}

TEST(ViewTable, NamesAreUniqueAndParseBackToTheirKind) {
  std::set<std::string> names;
  for (const ViewRow& row : view_table()) {
    EXPECT_TRUE(names.insert(std::string(row.info.name)).second) << row.info.name;
    EXPECT_EQ(parse_view(row.info.name), row.info.kind);
    EXPECT_FALSE(row.info.title.empty()) << row.info.name;
    EXPECT_FALSE(row.info.description.empty()) << row.info.name;
  }
  EXPECT_FALSE(parse_view("mercator"));
}

TEST(ViewTable, EachRowNamesItsOwnImplementationOnceAndViewModelFindsIt) {
  std::set<const ViewModel*> models;
  for (const ViewRow& row : view_table()) {
    ASSERT_NE(row.model, nullptr) << row.info.name;
    const ViewModel* model = &row.model();
    EXPECT_EQ(model, &row.model()) << "one instance per view: " << row.info.name;
    EXPECT_EQ(model, &view_model(row.info.kind)) << row.info.name;
    EXPECT_TRUE(models.insert(model).second) << "shared with another row: " << row.info.name;
  }
}

TEST(ViewTable, ThreeDViewsArePerspectiveAndDepthTestedTheFlatOnesOrthographic) {
  for (const ViewRow& row : view_table()) {
    ViewOptions view;
    view.kind = row.info.kind;
    const glm::mat4 m = row.model().camera(view);
    // An orthographic projection keeps w = 1: its last row is (0, 0, 0, 1) (glm indexes [column][row]).
    const bool keeps_w = m[0][3] == 0.0f && m[1][3] == 0.0f && m[2][3] == 0.0f && m[3][3] == 1.0f;
    EXPECT_EQ(keeps_w, !row.info.three_d) << row.info.name;
    const FrameScene scene = build_scene(sample_body(first_shown(row.info)), view);
    EXPECT_EQ(scene.depth_test, row.info.three_d) << row.info.name;
    if (!row.info.three_d) {
      EXPECT_EQ(scene.depth_bias, 0.0f) << row.info.name;
      EXPECT_EQ(row.model().normal(Surface{}, {0.3, 0.2, 0.0}), glm::dvec3(0, 0, 1)) << row.info.name;
      EXPECT_EQ(row.model().lift(), 0.0) << row.info.name;
    }
  }
}

TEST(ViewTable, EveryViewDrawsAndAimsAtABodyOnEachSurfaceItShows) {
  for (const ViewRow& row : view_table())
    for (const SurfaceKind surface : kSurfaces) {
      if (!shows(row.info, surface)) {
        EXPECT_TRUE(view_unsupported_reason(row.info.kind, surface)) << row.info.name;
        continue;
      }
      EXPECT_FALSE(view_unsupported_reason(row.info.kind, surface)) << row.info.name;
      const Snapshot s = sample_body(surface);
      ViewOptions view;
      view.kind = row.info.kind;
      view.scale = 0.25 * body_scale_length(view.kind, s.surface);
      aim_camera_at_body(view, s);
      const FrameScene scene = build_scene(s, view);
      const std::string what = std::string(row.info.name) + " of surface " + std::to_string(int(surface));
      EXPECT_FALSE(scene.fills.empty()) << what;
      EXPECT_FALSE(scene.lines.empty()) << what;
      EXPECT_EQ(scene.statics != nullptr, row.model().uses_static()) << what;
      for (const Vertex& v : scene.lines)
        ASSERT_TRUE(std::isfinite(v.position.x + v.position.y + v.position.z)) << what;
      EXPECT_TRUE(in_frame(pixel_of(scene, view, s.surface, s.bodies[0].X), view)) << what;
      // The ellipse's outline is in the frame too: the camera shows the body, not just its centre.
      for (const Vec3& P : ellipse_points(s.surface, s.bodies[0], view.scale, 8))
        EXPECT_TRUE(in_frame(pixel_of(scene, view, s.surface, P), view)) << what;
    }
}

TEST(ViewTable, AViewThatUsesStaticGeometryHasASurfaceAndAGridForEachSurfaceItShows) {
  for (const ViewRow& row : view_table())
    for (const SurfaceKind surface : kSurfaces) {
      if (!shows(row.info, surface) || !row.model().uses_static()) continue;
      Surface shape;
      shape.kind = surface;
      const std::shared_ptr<const StaticGeometry> kept = static_geometry(shape, row.info.kind);
      const StaticGeometry& g = *kept;
      EXPECT_EQ(&g, static_geometry(shape, row.info.kind).get()) << "built once: " << row.info.name;
      if (row.info.kind == ViewKind::plane) {  // the whole frame: cleared to its colour, a grid per frame
        EXPECT_TRUE(g.surface.empty() && g.grid.empty());
        continue;
      }
      EXPECT_FALSE(g.surface.empty()) << row.info.name;
      EXPECT_FALSE(g.grid.empty()) << row.info.name;
      EXPECT_FALSE(g.edges.empty()) << row.info.name;
      EXPECT_EQ(g.surface.size() % 3, 0u) << row.info.name;  // triangles
      EXPECT_EQ(g.grid.size() % 2, 0u) << row.info.name;     // segments
    }
}

TEST(ViewTable, BodyScaleIsInRadiiButInLengthsInTheConformalViewAndTheSmallestFeatureOnRevolutions) {
  const Surface sphere{SurfaceKind::sphere, 3.0};
  for (const ViewRow& row : view_table()) {
    if (!shows(row.info, SurfaceKind::sphere)) continue;
    EXPECT_EQ(body_scale_length(row.info.kind, sphere), row.info.kind == ViewKind::conformal ? 1.0 : 3.0)
        << row.info.name;
  }
  Surface torus;
  torus.kind = SurfaceKind::torus;
  torus.tube_radius = 0.7;
  EXPECT_EQ(body_scale_length(ViewKind::revolution, torus), 0.7);  // the tube, not the ring
  Surface bump;
  bump.kind = SurfaceKind::bump;
  bump.width = 2.5;
  EXPECT_EQ(body_scale_length(ViewKind::revolution, bump), 2.5);
}

}  // namespace
}  // namespace spinfold::render
