/// \file Teaching aids of the interface: the scene's overlays ("what the law sees") and the
/// legend in the View panel, the help overlay (F1), presentation mode, the UI scale and the
/// angle unit (kept between runs in the settings file), and the script actions of all of them
/// and of the formation editor.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "app/render/imgui_canvas.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

// Mouse gestures, which are not commands; the keys come from the command table.
const char* const kMouseHelp[][2] = {
    {"wheel", "zoom about the mouse"},
    {"right or middle drag", "pan"},
    {"left drag (paused)", "move a robot or obstacle"},
    {"left click (editing)", "pick leaders / follower, place a new follower"},
    {"left drag (Drag slots)", "move a follower's desired slot: it converges live"},
};

}  // namespace

void AppUi::SaveSettings() {
  const std::string err = SaveUiSettings(state_.settings);
  if (!err.empty()) SetStatus(err, true);
}

std::string AppUi::CmdOverlay(const std::string& list) {
  const std::string err = ParseSceneOverlays(list, &state_.overlays);
  if (!err.empty()) {
    SetStatus("overlay: " + err, true);
    return err;
  }
  SetStatus("overlays: " + list);
  return "";
}

std::string AppUi::CmdLegend(bool on) {
  state_.legend = on;
  return "";
}

std::string AppUi::CmdHelp(bool on) {
  state_.help = on;
  return "";
}

std::string AppUi::CmdPresent(bool on) {
  state_.present = on;
  state_.fit_now = true;
  SetStatus(on ? "presentation mode (p or Esc leaves it)" : "presentation mode off");
  return "";
}

std::string AppUi::CmdUiScale(double scale) {
  if (!(scale >= kMinUiScale && scale <= kMaxUiScale)) {
    const std::string why = "ui-scale must lie in [1, 3], got " + sim::FormatDouble(scale);
    SetStatus(why, true);
    return why;
  }
  state_.settings.ui_scale = static_cast<float>(scale);
  state_.fit_now = true;
  SaveSettings();
  return "";
}

std::string AppUi::CmdAngleUnit(const std::string& unit) {
  if (unit != "deg" && unit != "rad") {
    const std::string why = "angle-unit must be deg or rad, got '" + unit + "'";
    SetStatus(why, true);
    return why;
  }
  state_.settings.degrees = unit == "deg";
  SaveSettings();
  return "";
}

void AppUi::DrawOverlayToggles() {
  ImGui::TextDisabled("What the law sees");
  for (const sim::OverlayInfo& o : sim::Overlays()) {
    bool on = state_.overlays.count(o.name) > 0;
    if (ImGui::Checkbox(o.label.c_str(), &on)) CmdOverlay(on ? o.name : "-" + o.name);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("--overlay %s", o.name.c_str());
  }
  ImGui::Checkbox("legend (l)", &state_.legend);
  ImGui::SameLine();
  if (ImGui::Button("Help (F1)")) CmdHelp(!state_.help);
  int unit = state_.settings.degrees ? 0 : 1;
  ImGui::TextUnformatted("angles");
  ImGui::SameLine();
  if (ImGui::RadioButton("degrees", &unit, 0)) CmdAngleUnit("deg");
  ImGui::SameLine();
  if (ImGui::RadioButton("radians", &unit, 1)) CmdAngleUnit("rad");
  float scale = state_.settings.ui_scale;
  ImGui::SetNextItemWidth(140);
  if (ImGui::SliderFloat("UI scale", &scale, kMinUiScale, kMaxUiScale, "%.2fx"))
    state_.settings.ui_scale = std::clamp(scale, kMinUiScale, kMaxUiScale);
  // Written when the slider is let go, not for every frame of the drag.
  if (ImGui::IsItemDeactivatedAfterEdit()) CmdUiScale(state_.settings.ui_scale);
  if (ImGui::Button("Presentation mode (p)")) CmdPresent(true);
}

void AppUi::DrawHelpOverlay(ImVec2 min, ImVec2 max) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const Theme& th = GetTheme(state_.theme);
  const float row = ImGui::GetFontSize() + 6;
  std::vector<std::pair<std::string, std::string>> rows = KeyHelpRows();
  for (const auto& m : kMouseHelp) rows.emplace_back(m[0], m[1]);
  float key_w = 0, text_w = 0;
  for (const auto& h : rows) {
    key_w = std::max(key_w, ImGui::CalcTextSize(h.first.c_str()).x);
    text_w = std::max(text_w, ImGui::CalcTextSize(h.second.c_str()).x);
  }
  const int n = static_cast<int>(rows.size());
  const float w = key_w + text_w + 60, h = row * (n + 2) + 20;
  const ImVec2 c(0.5f * (min.x + max.x), 0.5f * (min.y + max.y));
  const ImVec2 lo(std::max(min.x, c.x - w / 2), std::max(min.y, c.y - h / 2));
  const ImVec2 hi(lo.x + w, lo.y + h);
  dl->AddRectFilled(lo, hi, ToImColor(th.backdrop.WithAlpha(0.96f)), 6.0f);
  dl->AddRect(lo, hi, ToImColor(th.legend_border), 6.0f, 0, 1.5f);
  float y = lo.y + 12;
  dl->AddText(ImVec2(lo.x + 20, y), ToImColor(th.text),
              "Keys and mouse (F1 or Esc closes; Ctrl+K finds any command)");
  y += 1.5f * row;
  for (const auto& hrow : rows) {
    dl->AddText(ImVec2(lo.x + 20, y), ToImColor(th.axis), hrow.first.c_str());
    dl->AddText(ImVec2(lo.x + 40 + key_w, y), ToImColor(th.text), hrow.second.c_str());
    y += row;
  }
}

void AppUi::DrawPresentationBar(ImVec2 min, ImVec2 max) {
  (void)max;
  ImGui::SetNextWindowPos(ImVec2(max.x - 10, min.y + 10), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##present", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);
  if (ImGui::Button(state_.playing ? "Pause" : "Play")) RunScriptAction("play-pause");
  ImGui::SameLine();
  if (ImGui::Button("Reset")) RunScriptAction("reset");
  ImGui::SameLine();
  if (ImGui::Button("Legend")) state_.legend = !state_.legend;
  ImGui::SameLine();
  if (ImGui::Button("Help")) state_.help = !state_.help;
  ImGui::SameLine();
  if (ImGui::Button("Exit presentation")) CmdPresent(false);
  run_->DrawAchievedSpeed();
  ImGui::End();
}

}  // namespace formsim::app
