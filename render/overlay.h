// The HUD: text drawn with Dear ImGui's OpenGL 3 backend into the same frame. Costs nothing when
// the HUD layer is off (no ImGui frame is started).
#pragma once

#include <string>
#include <vector>

namespace spinfold::render {

class HudOverlay {
 public:
  // Creates the ImGui context and the backend's GL objects; a context must be current.
  HudOverlay();
  ~HudOverlay();
  HudOverlay(const HudOverlay&) = delete;
  HudOverlay& operator=(const HudOverlay&) = delete;

  // Draws the lines in a box at the top-left corner; deterministic (one pass, fixed sizes).
  void draw(const std::vector<std::string>& lines, int width, int height);

 private:
  void* context_ = nullptr;  // ImGuiContext
};

}  // namespace spinfold::render
