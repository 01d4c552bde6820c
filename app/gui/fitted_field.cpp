#include "app/gui/fitted_field.hpp"

#include <imgui.h>
#include <imgui_internal.h>

#include "app/render/long_text.hpp"

namespace formsim::app {
namespace {

bool IsUtf8Continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

float FittedTextWidth(const std::string& s) { return ImGui::CalcTextSize(s.c_str(), s.c_str() + s.size()).x; }

}  // namespace

float WidthBeside(const char* button) {
  const ImGuiStyle& st = ImGui::GetStyle();
  return -(ImGui::CalcTextSize(button, nullptr, true).x + 2 * st.FramePadding.x + st.ItemSpacing.x);
}

std::string FitText(const std::string& text, float width, bool keep_end) {
  if (FittedTextWidth(text) <= width) return text;
  const std::string dots = "…";
  // The most characters that fit with the dots, counted from the kept end.
  std::size_t lo = 0, hi = text.size();
  auto cut = [&](std::size_t n) {
    if (keep_end) {
      std::size_t from = text.size() - n;
      while (from < text.size() && IsUtf8Continuation(static_cast<unsigned char>(text[from]))) ++from;
      return dots + text.substr(from);
    }
    std::size_t to = n;
    while (to > 0 && to < text.size() && IsUtf8Continuation(static_cast<unsigned char>(text[to]))) --to;
    return text.substr(0, to) + dots;
  };
  while (lo < hi) {
    const std::size_t mid = (lo + hi + 1) / 2;
    if (FittedTextWidth(cut(mid)) <= width) lo = mid;
    else hi = mid - 1;
  }
  return cut(lo);
}

bool FittedInputText(const char* id, char* buf, std::size_t size) {
  ImGuiStorage* storage = ImGui::GetStateStorage();
  const ImGuiID key = ImGui::GetID(id);
  const float width = ImGui::CalcItemWidth();
  const float pad = ImGui::GetStyle().FramePadding.x;
  const std::string text = buf;
  // The frame a click asked for the field (0: none): it takes the keyboard on the next frame
  // and stays a field while it is edited.
  const int asked = storage->GetInt(key, 0);
  const int frame = ImGui::GetFrameCount();
  if (asked == 0 && FittedTextWidth(text) > width - 2 * pad) {
    const std::string shown = FitText(text, width - 2 * pad, true);
    ImGui::PushID(id);
    ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_FrameBg));
    ImGui::PushStyleColor(ImGuiCol_ButtonHovered, ImGui::GetStyleColorVec4(ImGuiCol_FrameBgHovered));
    ImGui::PushStyleColor(ImGuiCol_ButtonActive, ImGui::GetStyleColorVec4(ImGuiCol_FrameBgActive));
    const bool clicked = ImGui::Button("##fitted", ImVec2(width, 0));
    ImGui::PopStyleColor(3);
    ImGui::PopID();
    // The text drawn apart from the label: a path may hold "##", which a label would hide.
    const ImVec2 at(ImGui::GetItemRectMin().x + pad, ImGui::GetItemRectMin().y + ImGui::GetStyle().FramePadding.y);
    ImGui::GetWindowDrawList()->AddText(at, ImGui::GetColorU32(ImGuiCol_Text), shown.c_str(),
                                        shown.c_str() + shown.size());
    if (ImGui::IsItemHovered()) SafeTooltip(text);
    if (clicked) storage->SetInt(key, frame);
    return false;
  }
  if (asked != 0 && frame == asked + 1) ImGui::SetKeyboardFocusHere();
  ImGui::SetNextItemWidth(width);
  const bool changed = ImGui::InputText(id, buf, size);
  if (asked != 0 && frame > asked + 3 && !ImGui::IsItemActive()) storage->SetInt(key, 0);
  if (ImGui::IsItemHovered() && !ImGui::IsItemActive() && FittedTextWidth(text) > width - 2 * pad) SafeTooltip(text);
  return changed;
}

bool FittedCombo(const char* id, const std::string& preview) {
  const float width = ImGui::CalcItemWidth();
  const ImGuiStyle& st = ImGui::GetStyle();
  // The preview's room: the width less the arrow button (a frame's height) and the padding.
  const float room = width - ImGui::GetFrameHeight() - 2 * st.FramePadding.x;
  const std::string shown = FitText(preview, room, false);
  ImGui::SetNextItemWidth(width);
  const bool open = ImGui::BeginCombo(id, shown.c_str());
  if (!open && shown != preview && ImGui::IsItemHovered()) SafeTooltip(preview);
  return open;
}

}  // namespace formsim::app
