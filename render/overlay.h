// The HUD and the legend: text drawn with Dear ImGui's OpenGL 3 backend into the same frame. Costs
// nothing when neither is shown (no ImGui frame is started).
#pragma once

#include <string>
#include <vector>

#include "render/scene_builder.h"

namespace spinfold::render {

class HudOverlay {
 public:
  // Creates the ImGui context and the backend's GL objects; a context must be current.
  HudOverlay();
  ~HudOverlay();
  HudOverlay(const HudOverlay&) = delete;
  HudOverlay& operator=(const HudOverlay&) = delete;

  // Draws the lines in a box at the top-left corner and the legend (when not empty) in a box at the
  // top-right corner, where and as large as `layout` (hud_layout()) says; deterministic (one pass,
  // fixed sizes).
  void draw(const std::vector<std::string>& lines, const std::vector<LegendEntry>& legend,
            const HudLayout& layout, int width, int height);

 private:
  void* context_ = nullptr;  // ImGuiContext
};

}  // namespace spinfold::render
