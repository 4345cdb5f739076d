// Snapshots and checks the view tests share (tests/render/views/*_test.cpp, view_table_test.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/chart.h"
#include "engine/revolution.h"
#include "engine/timeline.h"
#include "render/scene_builder.h"
#include "render/snapshot.h"

namespace spinfold::render::testing {

// A body that leaves a surface's drawn piece: the catenoid preset's start spinning slowly (s = 0.5,
// alone), which curls off the neck and winds beyond |z| = 2c from t ≈ 4.5 on (the preset's own main
// body, spinning fast, stays at the neck).
inline Scene escaping_catenoid() {
  std::string text(find_preset("spin_vs_geodesic_catenoid")->json);
  const std::string spin = "\"spin\": 4.0";
  text.replace(text.find(spin), spin.size(), "\"spin\": 0.5");  // through the text: spin sets the rates
  Scene scene = *parse_scene_text(text).scene;
  scene.companions.clear();
  return scene;
}

// The preset's run at t with, when asked, every body's trail sampled at t·k/64.
inline Snapshot preset_snapshot(std::string_view name, double t, bool with_trail) {
  const Scene scene = *parse_scene_text(find_preset(name)->json).scene;
  Simulation run = start_simulation(scene);
  Trail trail;
  trail.spacing = t / 64;
  if (with_trail)
    advance_sampling_trail(run, trail, t);
  else
    advance_to(run, t);
  return make_snapshot(run, trail, -1.0);
}

// A view of `kind` at w×h pixels aimed at the snapshot as the server aims it.
inline ViewOptions aimed_view(ViewKind kind, int w, int h, const Snapshot& s) {
  ViewOptions view;
  view.kind = kind;
  view.width = w;
  view.height = h;
  aim_camera_at_body(view, s);
  return view;
}

// A body at X whose frame is e₁ = λE₁, e₂ = μE₂ (L = diag(λ, μ) in the frame (E₁, E₂)).
inline void add_body(Snapshot& s, const Vec3& X, const Vec3& E1, const Vec3& E2, double lambda, double mu) {
  BodySnapshot& b = s.bodies.emplace_back();
  b.X = X;
  b.e[0] = lambda * E1;
  b.e[1] = mu * E2;
  b.gram << lambda * lambda, 0.0, 0.0, mu * mu;
}

// A body at chart point (r, φ) [radii, rad] with L = diag(λ, μ) in the paper's frame.
inline Snapshot body_at(SurfaceKind kind, double R, double r, double phi, double lambda = 1.0,
                        double mu = 1.0) {
  Snapshot s;
  s.surface = {kind, R};
  s.model = surface_model_of(s.surface);
  const ChartPoint p = chart_point(s.surface, r * R, phi);
  add_body(s, p.X, p.E1, p.E2, lambda, mu);
  return s;
}

// A body on a surface whose curvature varies (each kind's default shape, Surface's in-class
// parameters) at profile point (u, φ), L = diag(λ, μ) in the frame E₁ = X_u/f, E₂ = X_φ/ρ.
inline Snapshot body_on(SurfaceKind kind, double u, double phi, double lambda = 1.0, double mu = 1.0) {
  Snapshot s;
  s.surface.kind = kind;
  s.model = surface_model_of(s.surface);
  const RevolutionFrame f = revolution_frame(revolution_surface(s.surface), u, phi);
  add_body(s, f.X, f.E1, f.E2, lambda, mu);
  return s;
}

// The pixel an embedded point lands on in a built frame, if in front of the camera.
inline std::optional<glm::dvec2> pixel_of(const FrameScene& scene, const ViewOptions& view,
                                          const Surface& surface, const Vec3& X) {
  return pixel_position(scene, view, world_position(surface, view.kind, X));
}

inline bool in_frame(const std::optional<glm::dvec2>& px, const ViewOptions& view) {
  return px && px->x >= 0.0 && px->x <= view.width && px->y >= 0.0 && px->y <= view.height;
}

// Geodesic distance on the sphere or H² from the embedding's inner product.
inline double geodesic_distance(const Surface& surface, const Vec3& a, const Vec3& b) {
  const double R = surface.radius, c = dot(surface, a, b) / (R * R);
  return offers(surface, Offer::positive_curvature) ? R * std::acos(std::clamp(c, -1.0, 1.0))
                                                    : R * std::acosh(std::max(1.0, -c));
}

}  // namespace spinfold::render::testing
