// What render and record share: the scene, the picture options (cli/view_options.h) and --out,
// and the view they make for a scene.
#pragma once

#include <string>

#include "cli/commands/scene_options.h"
#include "cli/view_options.h"
#include "render/view.h"

namespace spinfold::cli {

struct RenderOptions {
  SceneOptions scene;
  double t = 0.0;
  ViewArgs view;  // --width … --trail, --camera (cli/view_options.h)
  std::string out;
};

// The view options as the table reads them (BadInput for a bad one).
render::ViewRequest view_request(const RenderOptions& opt);
// The view for the scene, checked against its surface.
render::ViewOptions view_options(const render::ViewRequest& request, const Scene& scene);

}  // namespace spinfold::cli
