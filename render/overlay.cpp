#include "render/overlay.h"

#include <imgui.h>

#include "imgui_impl_opengl3.h"

namespace spinfold::render {

HudOverlay::HudOverlay() {
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
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(context_));
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(static_cast<ImGuiContext*>(context_));
}

void HudOverlay::draw(const std::vector<std::string>& lines, int width, int height) {
  ImGui::SetCurrentContext(static_cast<ImGuiContext*>(context_));
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = 1.0f / 60.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
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
  ImGui::Begin("hud", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
  ImGui::End();
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace spinfold::render
