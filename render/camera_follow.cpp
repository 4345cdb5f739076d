#include "render/camera_follow.h"

#include <algorithm>
#include <cmath>

#include "render/view_table.h"
#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

glm::dvec3 target_of(const ViewOptions& view, const glm::dvec3& home) {
  return view.target ? glm::dvec3((*view.target)[0], (*view.target)[1], (*view.target)[2]) : home;
}

// b.yaw − a.yaw the shorter way round, in (−π, π].
double yaw_turn(const ViewOptions& a, const ViewOptions& b) {
  const double d = std::remainder(b.yaw - a.yaw, 2 * kPi);
  return d == -kPi ? kPi : d;
}

}  // namespace

double camera_gap(const ViewOptions& a, const ViewOptions& b, const glm::dvec3& home) {
  const double turn = std::hypot(yaw_turn(a, b), b.pitch - a.pitch);
  const double pull = std::abs(std::log(b.distance / a.distance));
  const double move = glm::length(target_of(b, home) - target_of(a, home)) / std::min(a.distance, b.distance);
  return std::max({turn, pull, move});
}

double follow_step(double gap, double seconds) {
  const double dt = std::clamp(seconds, 0.0, kFollowMaxSeconds);
  if (gap <= kFollowPassRate * dt) return gap;
  const double glide = std::max(gap * -std::expm1(-dt / kFollowGlideTime), kFollowPassRate * dt);
  return std::min({glide, kFollowMaxRate * dt, gap});
}

CameraPlaced CameraFollower::place(ViewOptions& view, const ViewRequest& request, const Snapshot& snapshot,
                                   double seconds) {
  place_camera(view, request, snapshot);
  const ViewModel& model = view_model(view.kind);
  const bool aimed = !request.yaw && !request.pitch && !request.distance;
  const bool follows = aimed && view_info(view.kind).three_d && last_ && last_->kind == view.kind &&
                       last_->width == view.width && last_->height == view.height &&
                       last_->layers == view.layers && last_->scale == view.scale;
  const auto arrive = [&] {
    last_ = view;
    recentring_ = false;
    given_ = !aimed;
    return CameraPlaced::aimed;
  };
  if (!follows) return arrive();
  const bool steady = request.motion == CameraMotion::steady;
  if (given_) recentring_ = true;  // the viewer's own camera let go: back to the aim, all the way
  given_ = false;
  // Steady: the last camera stays while it shows the body (a still frame, no time passing, too), in
  // sight or drawn through the surface: always on a surface seen only from above (the torus: the
  // scene does not turn under the class each time the body passes under the tube or behind it), and
  // elsewhere (a closed surface seen from any side) only where the aim cannot show it in sight either.
  const bool through = model.lowest_pitch(snapshot.surface) > -kPi / 2 || !shows_main_body(view, snapshot);
  if (steady && !recentring_ && shows_main_body(*last_, snapshot, through) &&
      model.on_lit_side(eye_of(model.camera(*last_)))) {
    view = *last_;
    return CameraPlaced::held;
  }
  const glm::dvec3 home = model.orbit_home();
  const double gap = camera_gap(*last_, view, home);
  const double step = follow_step(gap, seconds);
  if (step >= gap) return arrive();
  // The camera a share s of the way from the last frame's to the aimed one.
  const glm::dvec3 from = target_of(*last_, home), to = target_of(view, home);
  const auto on_way = [&](double s) {
    ViewOptions v = view;
    v.yaw = last_->yaw + s * yaw_turn(*last_, view);
    v.pitch = last_->pitch + s * (view.pitch - last_->pitch);
    v.distance = last_->distance * std::pow(view.distance / last_->distance, s);
    const glm::dvec3 at = from + s * (to - from);
    v.target = std::array<double, 3>{at.x, at.y, at.z};
    return v;
  };
  const double base = step / gap,
               most = std::min(1.0, kFollowCatchUpRate * std::clamp(seconds, 0.0, kFollowMaxSeconds) / gap);
  double s = base;
  ViewOptions next = on_way(s);
  // (On its way a camera that shows the body through the surface shows it: the view draws it there.)
  const auto shows = [&](const ViewOptions& v) { return shows_main_body(v, snapshot, true); };
  if (base > 0.0 && !shows(next) && shows(view)) {
    for (int k = 2; k * base <= most && !shows(next); ++k) next = on_way(s = k * base);
    if (!shows(next)) s = 1.0;  // no glide shows it: cut to the aimed camera
  }
  if (s >= 1.0 || !model.on_lit_side(eye_of(model.camera(next)))) return arrive();
  view = next;
  last_ = view;
  recentring_ = steady;
  return CameraPlaced::on_way;
}

}  // namespace spinfold::render
