#include "app/gui/flow_layout.hpp"

#include <imgui.h>

namespace formsim::app {

float TextWidth(const char* text) { return ImGui::CalcTextSize(text, nullptr, true).x; }

float ButtonWidth(const char* label) {
  return TextWidth(label) + 2 * ImGui::GetStyle().FramePadding.x;
}

float CheckboxWidth(const char* label) {
  const float text = TextWidth(label);
  return ImGui::GetFrameHeight() + (text > 0 ? ImGui::GetStyle().ItemInnerSpacing.x + text : 0);
}

bool SameLineIfFits(float width) {
  // The right edge of the last item and of the window's content region, in screen space.
  const float last_right = ImGui::GetItemRectMax().x;
  const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (last_right + ImGui::GetStyle().ItemSpacing.x + width <= right + 0.5f) {
    ImGui::SameLine();
    return true;
  }
  return false;
}

}  // namespace formsim::app
