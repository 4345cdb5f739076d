// Frames in sequence (the live view, a recording): a 3-D camera aimed at the bodies stays put while
// the body is in sight (steady, the default) or glides from one frame's camera to the next frame's
// aim (follow), instead of jumping. Aiming is a search over discrete
// candidates (render/views/camera.h), so where two candidates trade places the aimed camera turns by
// up to 160° between frames 1/25 s apart (measured on the torus and the spin-vs-geodesic sphere).
// A frame is still a function of its state and its camera: a camera on its way says so, and once
// there the frame is the aimed frame to the byte.
#pragma once

#include <glm/glm.hpp>
#include <optional>

#include "render/snapshot.h"
#include "render/view.h"
#include "render/view_parameters.h"

namespace spinfold::render {

// The gap between two cameras of a 3-D view [rad]: the largest of the turn √(Δyaw² + Δpitch²) (yaw
// the shorter way round), |ln(distance ratio)| and the target's move over the nearer distance (the
// angle it subtends). Each part of the camera moves by at most its share of a step this long.
double camera_gap(const ViewOptions& a, const ViewOptions& b, const glm::dvec3& home);

// How a followed camera moves toward the aim in a frame `seconds` after the last [rad of gap]:
// the whole gap when it is at most kFollowPassRate·seconds (a camera that follows a moving body
// stays on it, with no lag), else kFollowGlideTime's exponential share of it, at least that much and
// at most kFollowMaxRate·seconds (a glide that starts gently and ends at the aim).
inline constexpr double kFollowPassRate = 2.5;      // [rad/s] ~143°/s: the aim round a bump's top is ~85°/s
inline constexpr double kFollowGlideTime = 0.25;    // [s] the glide's time constant
inline constexpr double kFollowMaxRate = 5.0;       // [rad/s] ~290°/s, the fastest glide
inline constexpr double kFollowCatchUpRate = 10.0;  // [rad/s] the fastest glide that finds a lost body
// A frame later than this after the last one [s] moves as if this long had passed: a stream that
// falls behind glides on, it does not jump.
inline constexpr double kFollowMaxSeconds = 0.1;
double follow_step(double gap, double seconds);

// Where place() put the frame's camera: the aimed one to the bit (the frame is the aimed frame),
// held where it was (steady: settled, but not the aim's), or on its way (ask again to move on).
enum class CameraPlaced { aimed, held, on_way };

class CameraFollower {
 public:
  // Places the camera of the sequence's next frame, `seconds` [s] after the last one (the file's
  // 1/fps, the stream's clock): as place_camera (render/view_parameters.h) places it; then, in a 3-D
  // view aimed at the bodies (the request gives no part of the camera) whose last frame had the same
  // view, size, layers and scale:
  // - steady (request.motion, the default): the last frame's camera is held while it shows the main
  //   body (shows_main_body) from the lit side, in sight, or drawn through the surface (a view that
  //   shows through) where the view has a floor (ViewModel::lowest_pitch) or the aimed camera does
  //   not show it in sight either; once it does not, or the
  //   viewer's own camera is let go, the camera glides to the aim as follow does, all the way, and is held
  //   there;
  // - follow: moved from the last frame's camera toward the aimed one by follow_step (yaw, pitch,
  //   ln distance and target each by the same share of their gap).
  // Where a glide's camera would lose the main body and the aimed one does not, the glide goes on to
  // the first of twice, three times … the step that shows it, up to kFollowCatchUpRate, and else
  // cuts to the aimed camera (a body lost is worse than a fast turn, and worse than a cut); a camera
  // that would see the surface from its dark side (the hyperboloid from under the sheet) is not
  // taken: the aimed one is.
  CameraPlaced place(ViewOptions& view, const ViewRequest& request, const Snapshot& snapshot, double seconds);
  // The next frame starts afresh (aimed).
  void forget() { last_.reset(); }

 private:
  std::optional<ViewOptions> last_;
  bool recentring_ = false;  // steady: gliding to the aim, until there
  bool given_ = false;       // the last frame's camera was the request's (the viewer's own)
};

}  // namespace spinfold::render
