#include "render/overlay.h"

#include <imgui.h>

#include <algorithm>
#include <mutex>

#include "imgui_impl_opengl3.h"

namespace spinfold::render {

namespace {

// Dear ImGui's current context is one global (Debian's library has no thread-local GImGui), so
// overlays on several render threads (server/render_pool.h) take turns; drawing one costs ~0.3 ms.
std::mutex& imgui_turn() {
  static std::mutex turn;
  return turn;
}

}  // namespace

HudOverlay::HudOverlay() {
  const std::lock_guard lock(imgui_turn());
  ImGuiContext* previous = ImGui::GetCurrentContext();
  context_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(context_));
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // headless: no settings file
  io.LogFilename = nullptr;
  ImGui::StyleColorsLight();
  ImGui_ImplOpenGL3_Init("#version 330 core");
  ImGui::SetCurrentContext(previous);
}

HudOverlay::~HudOverlay() {
  const std::lock_guard lock(imgui_turn());
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(context_));
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(static_cast<ImGuiContext*>(context_));
}

namespace {

constexpr ImGuiWindowFlags kBoxFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs |
                                       ImGuiWindowFlags_NoSavedSettings |
                                       ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;

ImU32 color_u32(const glm::vec4& c) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a));
}

// The legend's box at the top-right corner: per body a swatch (a stretch of its trail, dashed for
// the geodesic companion, with a dot of its fill) and its label.
void draw_legend(const std::vector<LegendEntry>& legend, int width) {
  constexpr float kSwatch = 30.0f;  // [pixels]
  const ImGuiStyle& style = ImGui::GetStyle();
  float text_width = 0.0f;
  for (const LegendEntry& entry : legend)
    text_width = std::max(text_width, ImGui::CalcTextSize(entry.label.c_str()).x);
  const float line = ImGui::GetTextLineHeightWithSpacing();
  const ImVec2 size(kSwatch + style.ItemSpacing.x + text_width + 2 * style.WindowPadding.x,
                    static_cast<float>(legend.size()) * line + 2 * style.WindowPadding.y);
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - 8 - size.x, 8));
  ImGui::SetNextWindowSize(size);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("legend", nullptr, kBoxFlags);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (const LegendEntry& entry : legend) {
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const float y = at.y + 0.5f * ImGui::GetTextLineHeight();
    const ImU32 trail = color_u32(entry.trail_color);
    if (entry.dashed)
      for (float x = 0.0f; x < kSwatch; x += 8.0f)
        draw->AddLine(ImVec2(at.x + x, y), ImVec2(at.x + std::min(x + 5.0f, kSwatch), y), trail, 2.5f);
    else
      draw->AddLine(ImVec2(at.x, y), ImVec2(at.x + kSwatch, y), trail, 2.5f);
    draw->AddCircleFilled(ImVec2(at.x + 0.5f * kSwatch, y), 5.0f, color_u32(entry.color));
    ImGui::Dummy(ImVec2(kSwatch, ImGui::GetTextLineHeight()));
    ImGui::SameLine();
    ImGui::TextUnformatted(entry.label.c_str());
  }
  ImGui::End();
}

// The HUD's box at the top-left corner.
void draw_hud(const std::vector<std::string>& lines) {
  // Size the box from the text itself so that one pass suffices (auto-resize needs two frames).
  const ImGuiStyle& style = ImGui::GetStyle();
  float text_width = 0.0f;
  for (const std::string& line : lines)
    text_width = std::max(text_width, ImGui::CalcTextSize(line.c_str()).x);
  const float text_height = static_cast<float>(lines.size()) * ImGui::GetTextLineHeightWithSpacing();
  ImGui::SetNextWindowPos(ImVec2(8, 8));
  ImGui::SetNextWindowSize(
      ImVec2(text_width + 2 * style.WindowPadding.x, text_height + 2 * style.WindowPadding.y));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("hud", nullptr, kBoxFlags);
  for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
  ImGui::End();
}

}  // namespace

void HudOverlay::draw(const std::vector<std::string>& lines, const std::vector<LegendEntry>& legend,
                      int width, int height) {
  const std::lock_guard lock(imgui_turn());
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(context_));
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = 1.0f / 60.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  if (!lines.empty()) draw_hud(lines);
  if (!legend.empty()) draw_legend(legend, width);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace spinfold::render
