// The shared cameras and the aiming search (render/views/camera.cpp).
#include "render/views/camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "render/snapshot.h"
#include "render/view_table.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

TEST(Camera, AWindowKeepsItsShorterSideAndStretchesTheLongerToTheAspect) {
  ViewOptions wide;  // 640×480
  const Window2d w = window_around(wide, {1.0, 2.0}, 3.0);
  EXPECT_EQ(w.centre, glm::dvec2(1.0, 2.0));
  EXPECT_DOUBLE_EQ(w.hy, 3.0);
  EXPECT_DOUBLE_EQ(w.hx, 4.0);
  ViewOptions tall;
  tall.width = 300, tall.height = 600;
  const Window2d t = window_around(tall, {0.0, 0.0}, 3.0);
  EXPECT_DOUBLE_EQ(t.hx, 3.0);
  EXPECT_DOUBLE_EQ(t.hy, 6.0);
  // The window camera maps its corners to the frame's.
  FrameScene scene;
  scene.view_projection = window_camera(w);
  const glm::dvec2 top_left = *pixel_position(scene, wide, {1.0 - 4.0, 2.0 + 3.0, 0.0});
  EXPECT_NEAR(top_left.x, 0.0, 1e-4);
  EXPECT_NEAR(top_left.y, 0.0, 1e-4);
}

TEST(Camera, TheTargetIsTheViewsOrTheFallback) {
  ViewOptions view;
  EXPECT_EQ(target_or(view, {0.0, 1.0}), glm::dvec2(0.0, 1.0));
  view.target = std::array<double, 3>{4.0, 5.0, 6.0};
  EXPECT_EQ(target_or(view, {0.0, 1.0}), glm::dvec2(4.0, 5.0));
}

TEST(Camera, AnOrbitingCameraLooksAtItsTargetFromItsDistance) {
  ViewOptions view;
  view.yaw = 0.3, view.pitch = 0.2, view.distance = 5.0;
  for (const auto& target :
       {std::optional<std::array<double, 3>>{}, std::optional(std::array<double, 3>{1, 2, 3})}) {
    view.target = target;
    const glm::dvec3 at =
        target ? glm::dvec3((*target)[0], (*target)[1], (*target)[2]) : glm::dvec3(0, 0, 1.6);
    FrameScene scene;
    scene.view_projection = orbit_camera(view, glm::dvec3(0, 0, 1.6));
    const glm::dvec2 px = *pixel_position(scene, view, at);
    EXPECT_NEAR(px.x, 320.0, 1e-3);
    EXPECT_NEAR(px.y, 240.0, 1e-3);
    const glm::dvec4 h = glm::inverse(glm::dmat4(scene.view_projection)) * glm::dvec4(0, 0, 1, 0);
    EXPECT_NEAR(glm::length(glm::dvec3(h) / h.w - at), 5.0, 1e-3);
  }
}

TEST(Camera, BadnessWeighsTheSightsOutOfTheFrameBehindTheCameraOrUnderTheHud) {
  const ViewModel& plane = view_model(ViewKind::plane);
  const Surface flat(SurfaceKind::plane, 1.0);
  ViewOptions view;
  view.kind = ViewKind::plane;
  HudLayout hud;
  const std::vector<Sight> sights{
      {{0.0, 0.0, 0.0}, 1000.0}, {{3.97, 0.0, 0.0}, 5.0}, {{9.0, 0.0, 0.0}, 50.0}};
  EXPECT_DOUBLE_EQ(badness(plane, flat, view, sights, hud), 5.0 + 50.0);  // by the edge, beyond it
  hud.hud = {300.0, 220.0, 40.0, 40.0};                                   // over the frame's centre
  EXPECT_DOUBLE_EQ(badness(plane, flat, view, sights, hud), 1000.0 + 5.0 + 50.0);
  // A search's bound: the sum stops once it reaches `enough`, after the sight that reached it.
  EXPECT_DOUBLE_EQ(badness(plane, flat, view, sights, hud, 1000.0), 1000.0);
  EXPECT_DOUBLE_EQ(badness(plane, flat, view, sights, hud, 1004.0), 1000.0 + 5.0);
  EXPECT_DOUBLE_EQ(badness(plane, flat, view, sights, hud, 2000.0), 1000.0 + 5.0 + 50.0);
}

// The ray casts are the cost of a camera search: a sight out of the frame or under a box, and the
// sights after the bound is reached, cast none.
TEST(Camera, BadnessCastsNoRayForASightAlreadyCountedOrPastTheBound) {
  struct CountingPlane final : ViewModel {
    const ViewModel& plane = view_model(ViewKind::plane);
    mutable int casts = 0;
    glm::dvec3 world_position(const Surface& s, const Vec3& X) const override {
      return plane.world_position(s, X);
    }
    glm::mat4 camera(const ViewOptions& v) const override { return plane.camera(v); }
    bool hidden(const Surface&, const glm::dvec3&, const glm::dvec3&) const override {
      return ++casts, false;
    }
  } model;
  const Surface flat(SurfaceKind::plane, 1.0);
  ViewOptions view;
  view.kind = ViewKind::plane;
  HudLayout hud;
  hud.hud = {300.0, 220.0, 40.0, 40.0};  // over the main body
  const std::vector<Sight> sights{
      {{0.0, 0.0, 0.0}, 1000.0}, {{0.5, 0.0, 0.0}, 5.0}, {{9.0, 0.0, 0.0}, 50.0}, {{-0.5, 0.0, 0.0}, 5.0}};
  EXPECT_DOUBLE_EQ(badness(model, flat, view, sights, hud), 1050.0);
  EXPECT_EQ(model.casts, 2);  // the two in the frame and clear of the box
  model.casts = 0;
  EXPECT_DOUBLE_EQ(badness(model, flat, view, sights, hud, 500.0), 1000.0);
  EXPECT_EQ(model.casts, 0);
}

TEST(Camera, ClearingTheBoxesNeverLeavesTheCameraWorseThanItFoundIt) {
  const Snapshot s = testing::body_at(SurfaceKind::sphere, 1.0, 1.2, 0.5);
  const ViewModel& sphere = view_model(ViewKind::sphere);
  ViewOptions view;
  view.yaw = 0.5, view.pitch = 0.2;  // over the body, which the HUD's box below covers
  const std::vector<Sight> points = sights(sphere, s, view, false);
  ASSERT_EQ(points.front().weight, 1000.0);
  HudLayout hud;
  const glm::dvec2 body = *testing::pixel_of(build_scene(s, view), view, s.surface, s.bodies[0].X);
  hud.hud = {body.x - 30.0, body.y - 30.0, 60.0, 60.0};
  const double before = badness(sphere, s.surface, view, points, hud);
  EXPECT_GE(before, 1000.0);
  clear_the_boxes(sphere, s.surface, view, points, hud, {1.0, 1.2});
  EXPECT_LT(badness(sphere, s.surface, view, points, hud), 1000.0);
}

TEST(Camera, AimingAtTheBodiesCentreTakesTheMiddleOfTheirBoundingBox) {
  Snapshot s = testing::body_at(SurfaceKind::plane, 1.0, 0.0, 0.0);
  s.bodies.push_back(s.bodies[0]);
  s.bodies[0].X = Vec3(1.0, 1.0, 0.0);
  s.bodies[1].X = Vec3(3.0, -5.0, 0.0);
  ViewOptions view;
  view.kind = ViewKind::plane;
  aim_at_bodies_centre(view_model(ViewKind::plane), view, s);
  ASSERT_TRUE(view.target);
  EXPECT_EQ(*view.target, (std::array<double, 3>{2.0, -2.0, 0.0}));
}

// Whether some direction has every body of a sphere snapshot within 60° of it (what the sphere view
// shows face-on): searched over 20000 directions spread evenly (a Fibonacci sphere).
bool in_one_cap(const Snapshot& s) {
  constexpr int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, rho = std::sqrt(1.0 - z * z);
    const double a = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
    const Vec3 d(rho * std::cos(a), rho * std::sin(a), z);
    if (std::ranges::all_of(s.bodies, [&](const BodySnapshot& b) { return b.X.normalized().dot(d) >= 0.5; }))
      return true;
  }
  return false;
}

// Framing is a property: every preset, in every view that shows its surface, at several times and
// at the pictures of a 1366- and a 1920-wide page, aimed as the server aims it, shows each body's
// centre in the frame, clear of the HUD and the legend, and not behind the surface (or, where the view
// draws through it, ghosted there: a torus's underside seen from above); and at the
// small pictures of a phone (390×290) and a thumbnail (320×240), whose overlay is compact. Two kinds of
// companion are outside what one camera can do: one beyond the drawn piece of an unbounded surface,
// or any when the main body is beyond it (the revolution view then follows the main body alone:
// RevolutionView::aim), left out; and one on the sphere where the bodies are spread too far for
// any camera to have them all within the 60° of its direction that the sphere view shows face-on
// (SphereView::hidden): drawn faintly through the sphere instead, which is checked and counted.
TEST(Camera, EveryPresetInEveryViewItOffersShowsItsBodiesClearOfTheBoxes) {
  int cases = 0, apart = 0, through = 0;
  std::vector<std::string> failures;
  for (const PresetSource& preset : preset_sources())
    for (const double t : {0.0, 1.0, 2.5, 5.0, 10.0}) {
      const Snapshot s = testing::preset_snapshot(preset.name, t, t > 0.0);
      for (const ViewRow& row : view_table()) {
        if (!shows(row.info, s.surface.kind)) continue;
        for (const auto& [w, h] : {std::pair{795, 515}, {1280, 757}, {320, 240}, {390, 290}}) {
          const ViewOptions view = testing::aimed_view(row.info.kind, w, h, s);
          const FrameScene scene = build_scene(s, view);
          const ViewModel& model = row.model();
          const glm::dvec3 eye = eye_of(scene.view_projection);
          for (std::size_t b = 0; b < s.bodies.size(); ++b) {
            const Vec3& X = s.bodies[b].X;
            if (!model.draws(s.surface, X)) continue;  // off the view: the HUD says so (tested apart)
            // Beyond the drawn piece, or the main body is (the view then follows it alone).
            if (b > 0 && !(model.on_view(s.surface, X) && model.on_view(s.surface, s.bodies[0].X))) continue;
            const glm::dvec3 world = model.world_position(s.surface, X);
            const std::optional<glm::dvec2> px = pixel_position(scene, view, world);
            std::string why;
            if (!px || px->x < 0 || px->y < 0 || px->x > w || px->y > h)
              why = "out of the frame";
            else if (scene.hud.hud.contains(*px))
              why = "under the HUD";
            else if (scene.hud.legend.contains(*px))
              why = "under the legend";
            else if (model.hidden(s.surface, world, eye))
              why = "behind the surface";
            // Where no camera has every body face-on, a companion behind the sphere is drawn faintly
            // through it (add_ghosts); so is any body behind a surface seen only from above
            // (ViewModel::shows_through, kLowestSpacePitch): its ghost must be there, near its centre.
            const bool spread = b > 0 && view.kind == ViewKind::sphere && !in_one_cap(s);
            if (why == "behind the surface" && (spread || model.shows_through())) {
              const bool ghost = std::ranges::any_of(scene.ghost_fills, [&](const Vertex& v) {
                return glm::distance(glm::dvec3(v.position), world) < 0.5;
              });
              if (ghost) {
                ++(spread ? apart : through);
                continue;
              }
              why += " (and not drawn through it)";
            }
            ++cases;
            if (!why.empty())
              failures.push_back(std::string(preset.name) + " t=" + std::to_string(t) + " " +
                                 std::string(row.info.name) + " " + std::to_string(w) + "x" +
                                 std::to_string(h) + " body " + std::to_string(b + 1) + ": " + why);
          }
        }
      }
    }
  std::string all;
  for (const std::string& f : failures) all += f + "\n";
  EXPECT_GT(cases, 1000);
  EXPECT_TRUE(failures.empty()) << failures.size() << " of " << cases << ":\n" << all;
  // The companions drawn through the sphere: spin_vs_geodesic_sphere and spin_fan_sphere at t = 5
  // (159° apart), at all four sizes; counted so that a change in them is seen.
  EXPECT_EQ(apart, 16);
  // The main bodies on a torus's underside, which no camera from above sees: spin_vs_geodesic_torus
  // at t = 2.5 and 5 (u = 1.74 and 2.4, below the tube's equator), at all four sizes.
  EXPECT_EQ(through, 8);
}

// The teacher's dial: the default scene playing while K is dragged from 1 to −1 (a step every 1.5
// time units), then on at K = −1, shown in the conformal view as the page shows it: the main body
// in the frame, clear of the HUD, and never a speck (at least 12 px across: before the close-ups,
// at r ≈ 4–5 it was 2–3 px on the rim of a fixed window).
TEST(Camera, TheCurvatureDialKeepsTheBodyInThePictureAndLargeEnough) {
  Scene scene = *parse_scene_text(find_preset(kDefaultPreset)->json).scene;
  Simulation run = start_simulation(scene);
  std::vector<double> far_out;
  const auto check = [&](const std::string& when) {
    const Snapshot s = make_snapshot(run, Trail{}, -1.0);
    if (offers(s.surface, Offer::negative_curvature))  // R = 1 at K = −1: X₃ = cosh r
      far_out.push_back(std::acosh(std::max(1.0, s.bodies[0].X.z() / s.surface.radius)));
    for (const auto& [w, h] : {std::pair{795, 515}, {1280, 757}}) {
      const ViewOptions view = testing::aimed_view(ViewKind::conformal, w, h, s);
      const FrameScene frame = build_scene(s, view);
      const auto at = [&](const Vec3& X) {
        return *pixel_position(frame, view, world_position(s.surface, view.kind, X));
      };
      const glm::dvec2 body = at(s.bodies[0].X);
      const std::string where = when + " " + std::to_string(w) + "x" + std::to_string(h);
      EXPECT_TRUE(body.x > 0 && body.x < w && body.y > 0 && body.y < h) << where;
      EXPECT_FALSE(frame.hud.hud.contains(body)) << where;
      double across = 0.0;
      for (const Vec3& P : ellipse_points(s.surface, s.bodies[0], view.scale, 16))
        across = std::max(across, 2.0 * glm::distance(at(P), body));
      EXPECT_GE(across, 12.0) << where << ": zoom " << view.zoom;
    }
  };
  for (const double K : {1.0, 0.5, 0.25, 0.0, -0.25, -0.5, -0.75, -1.0}) {
    advance_to(run, run.state.t + 1.5);
    scene.surface.curvature_given = K;
    resolve_curvature(scene.surface);
    retune(run, scene);
    check("K = " + std::to_string(K) + " at t = " + std::to_string(run.state.t));
  }
  for (int k = 0; k < 12; ++k) {
    advance_to(run, run.state.t + 1.5);
    check("K = -1 at t = " + std::to_string(run.state.t));
  }
  EXPECT_GT(*std::ranges::max_element(far_out), 3.0);  // the run does reach far out
}

}  // namespace
}  // namespace spinfold::render
