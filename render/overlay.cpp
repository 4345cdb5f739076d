#include "render/overlay.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>

#include "imgui_impl_opengl3.h"

namespace spinfold::render {

namespace {

// The font made for a scale: the nearest of kHudScales.
int font_for(double scale) {
  const auto nearest = std::min_element(kHudScales.begin(), kHudScales.end(), [&](double a, double b) {
    return std::abs(a - scale) < std::abs(b - scale);
  });
  return static_cast<int>(nearest - kHudScales.begin());
}

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
  // The built-in font at each scale hud_layout() may ask for (0.625, 0.75, 1, 1.25, …, 4): a font of its
  // own per size keeps the glyphs as sharp as the pixel font allows (scaling one would blur it).
  for (const double scale : kHudScales) {
    ImFontConfig config;
    config.SizePixels = static_cast<float>(13.0 * scale);
    // Advances snapped to whole pixels, as hud_layout() counts them (AddFontDefault snaps only
    // when given no config: without this the 0.75 font's 5.25 px advance outran the box).
    config.PixelSnapH = true;
    io.Fonts->AddFontDefault(&config);
  }
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

// A translucent box at hud_layout()'s place: one pass suffices (auto-resize would need two frames).
void begin_box(const char* name, const PixelBox& box) {
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(box.x), static_cast<float>(box.y)));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(box.w), static_cast<float>(box.h)));
  ImGui::SetNextWindowBgAlpha(0.72f);
  ImGui::Begin(name, nullptr, kBoxFlags);
}

ImU32 color_u32(const glm::vec4& c) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a));
}

// The legend's box at the top-right corner: per body a swatch (a stretch of its trail, dashed for
// the geodesic companion, with a dot of its fill) and its label; the bending layer's two colours as
// one stretch of trail, half each.
void draw_legend(const std::vector<LegendEntry>& legend, const HudLayout& layout) {
  const float kSwatch = static_cast<float>(layout.swatch), s = static_cast<float>(layout.scale);
  begin_box("legend", layout.legend);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (const LegendEntry& entry : legend) {
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const float y = at.y + 0.5f * ImGui::GetTextLineHeight();
    const ImU32 trail = color_u32(entry.trail_color);
    if (entry.dashed)
      for (float x = 0.0f; x < kSwatch; x += 8.0f * s)
        draw->AddLine(ImVec2(at.x + x, y), ImVec2(at.x + std::min(x + 5.0f * s, kSwatch), y), trail,
                      2.5f * s);
    else if (entry.right_half) {
      draw->AddLine(ImVec2(at.x, y), ImVec2(at.x + 0.5f * kSwatch, y), trail, 2.5f * s);
      draw->AddLine(ImVec2(at.x + 0.5f * kSwatch, y), ImVec2(at.x + kSwatch, y), color_u32(*entry.right_half),
                    2.5f * s);
    } else
      draw->AddLine(ImVec2(at.x, y), ImVec2(at.x + kSwatch, y), trail, 2.5f * s);
    if (entry.dot) draw->AddCircleFilled(ImVec2(at.x + 0.5f * kSwatch, y), 5.0f * s, color_u32(entry.color));
    ImGui::Dummy(ImVec2(kSwatch, ImGui::GetTextLineHeight()));
    ImGui::SameLine();
    ImGui::TextUnformatted(entry.label.c_str());
  }
  ImGui::End();
}

// The HUD's box at the top-left corner.
void draw_hud(const std::vector<std::string>& lines, const HudLayout& layout) {
  begin_box("hud", layout.hud);
  for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
  ImGui::End();
}

}  // namespace

void HudOverlay::draw(const std::vector<std::string>& lines, const std::vector<LegendEntry>& legend,
                      const HudLayout& layout, int width, int height) {
  const std::lock_guard lock(imgui_turn());
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(context_));
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = 1.0f / 60.0f;
  // The font and the lengths at the layout's scale (hud_layout(): 1, 1.25, 1.5, …).
  const float s = static_cast<float>(layout.scale);
  io.FontDefault = io.Fonts->Fonts[font_for(layout.scale)];
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowPadding = ImVec2(static_cast<float>(layout.padding), static_cast<float>(layout.padding));
  style.ItemSpacing = ImVec2(static_cast<float>(layout.advance), 2.0f * s);
  style.WindowBorderSize = 1.0f;
  style.WindowRounding = 0.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  if (!lines.empty()) draw_hud(lines, layout);
  if (!legend.empty()) draw_legend(legend, layout);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace spinfold::render
