#include "app/gui/view_panel.hpp"

#include "app/gui/fitted_field.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/gui/ui_settings.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/theme.hpp"
#include "app/render/world_view.hpp"
#include "sim/core/draw.hpp"
#include "sim/core/number_format.hpp"
#include "sim/session/session.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

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

// What the rows offer: the overlays, the themes.
std::vector<std::string> OverlayNames(const AppUi&) {
  std::vector<std::string> out = {"all", "none", "default"};
  for (const sim::OverlayInfo& o : sim::Overlays()) out.push_back(o.name);
  return out;
}

std::vector<std::string> ThemeList() {
  std::vector<std::string> out;
  for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint, ThemeId::kHighContrast})
    out.push_back(GetTheme(id).name);
  return out;
}

}  // namespace

void ViewPanel::SaveSettings() {
  const std::string err = SaveUiSettings(ctx_.state->settings);
  if (!err.empty()) ctx_.SetStatus(err, true);
}

std::string ViewPanel::CmdOverlay(const std::string& list) {
  const std::string err = ParseSceneOverlays(list, &ctx_.state->overlays);
  if (!err.empty()) {
    ctx_.SetStatus("overlay: " + err, true);
    return err;
  }
  ctx_.SetStatus("overlays: " + list);
  return "";
}

std::string ViewPanel::CmdLegend(bool on) {
  ctx_.state->legend = on;
  return "";
}

std::string ViewPanel::CmdHelp(bool on) {
  ctx_.state->help = on;
  return "";
}

std::string ViewPanel::CmdPresent(bool on) {
  ctx_.state->present = on;
  ctx_.state->fit_now = true;
  ctx_.SetStatus(on ? "presentation mode (p or Esc leaves it)" : "presentation mode off");
  return "";
}

std::string ViewPanel::CmdUiScale(double scale) {
  if (!(scale >= kMinUiScale && scale <= kMaxUiScale)) {
    return ctx_.Refuse("ui-scale must lie in [1, 3], got " + sim::FormatDouble(scale));
  }
  ctx_.state->settings.ui_scale = static_cast<float>(scale);
  ctx_.state->fit_now = true;
  SaveSettings();
  return "";
}

std::string ViewPanel::CmdAngleUnit(const std::string& unit) {
  if (unit != "deg" && unit != "rad") {
    return ctx_.Refuse("angle-unit must be deg or rad, got '" + unit + "'");
  }
  ctx_.state->settings.degrees = unit == "deg";
  SaveSettings();
  return "";
}

void ViewPanel::Draw(const Fonts&) {
  if (ImGui::Button("Fit all (f)")) {
    ctx_.state->fit_now = true;
    ctx_.state->follow = -1;
  }
  ImGui::SameLine();
  ImGui::Checkbox("auto-fit", &ctx_.state->auto_fit);
  ImGui::SameLine();
  ImGui::Checkbox("whole run", &ctx_.state->whole_run);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "auto-fit keeps everything seen since the start in view\n(off: follows the robots)");
  const auto& robots = ctx_.session().exp().world().robots();
  std::string preview =
      ctx_.state->follow >= 0 && ctx_.state->follow < static_cast<int>(robots.size())
          ? robots[ctx_.state->follow]->name()
          : "nobody";
  ImGui::SetNextItemWidth(140);
  if (FittedCombo("follow", preview)) {
    if (ImGui::Selectable("nobody", ctx_.state->follow < 0)) ctx_.state->follow = -1;
    for (std::size_t i = 0; i < robots.size(); ++i)
      if (ImGui::Selectable(robots[i]->name().c_str(), ctx_.state->follow == static_cast<int>(i))) {
        ctx_.state->follow = static_cast<int>(i);
        ctx_.state->auto_fit = false;
      }
    ImGui::EndCombo();
  }
  float zoom = static_cast<float>(ctx_.state->view.scale);
  ImGui::SetNextItemWidth(140);
  if (ImGui::SliderFloat("px per m", &zoom, 2.0f, 2000.0f, "%.0f", ImGuiSliderFlags_Logarithmic)) {
    ctx_.state->view.scale = std::max(0.5f, zoom);
    ctx_.state->auto_fit = false;
  }
  ImGui::Checkbox("grid", &ctx_.state->grid);
  ImGui::SameLine();
  ImGui::Checkbox("coordinates", &ctx_.state->coordinates);
  ImGui::SetNextItemWidth(140);
  if (ImGui::BeginCombo("theme", GetTheme(ctx_.state->theme).name)) {
    for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint, ThemeId::kHighContrast})
      if (ImGui::Selectable(GetTheme(id).name, id == ctx_.state->theme)) {
        ctx_.state->theme = id;
        ApplyImGuiTheme(GetTheme(id));
      }
    ImGui::EndCombo();
  }
  if (ImGui::Button("Screenshot (s)")) ctx_.state->screenshot_requested = true;
  ImGui::TextDisabled("wheel: zoom, right-drag: pan,\nleft-drag a robot or obstacle while paused");
  ImGui::Separator();
  DrawOverlayToggles();
}

void ViewPanel::DrawOverlayToggles() {
  ImGui::TextDisabled("What the law sees");
  for (const sim::OverlayInfo& o : sim::Overlays()) {
    bool on = ctx_.state->overlays.count(o.name) > 0;
    if (ImGui::Checkbox(o.label.c_str(), &on)) CmdOverlay(on ? o.name : "-" + o.name);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("--overlay %s", o.name.c_str());
  }
  ImGui::Checkbox("legend (l)", &ctx_.state->legend);
  ImGui::SameLine();
  if (ImGui::Button("Help (F1)")) CmdHelp(!ctx_.state->help);
  int unit = ctx_.state->settings.degrees ? 0 : 1;
  ImGui::TextUnformatted("angles");
  ImGui::SameLine();
  if (ImGui::RadioButton("degrees", &unit, 0)) CmdAngleUnit("deg");
  ImGui::SameLine();
  if (ImGui::RadioButton("radians", &unit, 1)) CmdAngleUnit("rad");
  float scale = ctx_.state->settings.ui_scale;
  ImGui::SetNextItemWidth(140);
  if (ImGui::SliderFloat("UI scale", &scale, kMinUiScale, kMaxUiScale, "%.2fx"))
    ctx_.state->settings.ui_scale = std::clamp(scale, kMinUiScale, kMaxUiScale);
  // Written when the slider is let go, not for every frame of the drag.
  if (ImGui::IsItemDeactivatedAfterEdit()) CmdUiScale(ctx_.state->settings.ui_scale);
  if (ImGui::Button("Presentation mode (p)")) CmdPresent(true);
}

void ViewPanel::DrawHelpOverlay(ImVec2 min, ImVec2 max) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const Theme& th = GetTheme(ctx_.state->theme);
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

void ViewPanel::DrawPresentationBar(ImVec2 min, ImVec2 max) {
  (void)max;
  ImGui::SetNextWindowPos(ImVec2(max.x - 10, min.y + 10), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##present", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);
  if (ImGui::Button(ctx_.state->playing ? "Pause" : "Play")) ctx_.run("play-pause");
  ImGui::SameLine();
  if (ImGui::Button("Reset")) ctx_.run("reset");
  ImGui::SameLine();
  if (ImGui::Button("Legend")) ctx_.state->legend = !ctx_.state->legend;
  ImGui::SameLine();
  if (ImGui::Button("Help")) ctx_.state->help = !ctx_.state->help;
  ImGui::SameLine();
  if (ImGui::Button("Exit presentation")) CmdPresent(false);
  ctx_.Find<RunPanel>()->DrawAchievedSpeed();
  ctx_.state->present_bar_bottom = ImGui::GetWindowPos().y + ImGui::GetWindowSize().y;
  ctx_.state->present_bar = ImVec4(ImGui::GetWindowPos().x, ImGui::GetWindowPos().y,
                                   ImGui::GetWindowPos().x + ImGui::GetWindowSize().x,
                                   ctx_.state->present_bar_bottom);
  ImGui::End();
}

namespace {

ViewPanel* ViewPanelOf(AppUi& ui) {
  return ui.Find<ViewPanel>();
}

// screenshot, present, frame-formation: the window as a whole (its picture, presentation mode,
// the camera framing the formation).
void AddViewWindowRows(std::vector<Command>& t) {
  using namespace rows;
  using Src = CommandSource;
  auto panel = ViewPanelOf;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "screenshot",
       .args = {Optional(Text("PATH", "a PNG file to write"))},
       .keys = {"s"},
       .menu = "File/Screenshot",
       .help = "Write the window as a PNG (to PATH, else a numbered name)",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return ui.CmdScreenshot(a.Has(0) ? a.Text(0) : "");
       }});
  row({.name = "present",
       .args = {OnOff()},
       .keys = {"p"},
       .key_args = "toggle",
       .menu = "View/Presentation mode",
       .help = "The world view fills the window, for a lecture room (Esc leaves)",
       .checked = [](const AppUi& ui) { return ui.state().present; },
       .run = [panel](AppUi& ui, const CommandArgs& a,
                      Src) { return panel(ui)->CmdPresent(a.On(0)); }});
  row({.name = "frame-formation",
       .args = {OnOff()},
       .key_args = "toggle",
       .menu = "View/Frame the formation",
       .help = "The camera frames the robots and their recent trails and follows them (always on "
               "in presentation mode; zooming by hand pauses it until fit)",
       .checked = [](const AppUi& ui) { return ui.state().frame_formation; },
       .run =
           [](AppUi& ui, const CommandArgs& a, Src) {
             ui.state().frame_formation = a.On(0);
             ui.state().camera.Fit();
             return std::string();
           }});
}

// theme, ui-scale, angle-unit, overlay, legend: how things are drawn.
void AddViewLookRows(std::vector<Command>& t) {
  using namespace rows;
  using Src = CommandSource;
  auto panel = ViewPanelOf;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "theme",
       .args = {Initial(
           Choice("NAME", ThemeList()),
           [](const AppUi& ui) { return std::string(GetTheme(ui.state().theme).name); })},
       .menu = "View/Theme",
       .help = "Colours of the panels, the world view and the plots",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         ui.state().theme = ParseTheme(a.Text(0));
         if (ImGui::GetCurrentContext() != nullptr) ApplyImGuiTheme(GetTheme(ui.state().theme));
         return std::string();
       }});
  row({.name = "ui-scale",
       .args = {Initial(
           Offer(Real("SCALE", kMinUiScale, kMaxUiScale),
                 [](const AppUi&) {
                   return std::vector<std::string>{"1", "1.25", "1.5", "2", "2.5", "3"};
                 }),
           [](const AppUi& ui) { return sim::FormatDouble(ui.state().settings.ui_scale); })},
       .menu = "View/UI scale",
       .help = "Fonts and line widths, kept between runs",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         return panel(ui)->CmdUiScale(a.Real(0));
       }});
  row({.name = "angle-unit",
       .args = {Initial(Choice("UNIT", {"deg", "rad"}),
                        [](const AppUi& ui) {
                          return std::string(ui.state().settings.degrees ? "deg" : "rad");
                        })},
       .menu = "View/Angle unit",
       .help = "Show angles in degrees or radians (stored values stay radians)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         return panel(ui)->CmdAngleUnit(a.Text(0));
       }});
  row({.name = "overlay",
       .args = {Offer(Text("LIST", "overlay names, comma-separated (all, none, default, -NAME)"),
                      OverlayNames)},
       .menu = "View/Overlays",
       .help = "What the law sees, drawn over the scene: applied to the overlays shown now",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         return panel(ui)->CmdOverlay(a.Text(0));
       }});
  row({.name = "legend",
       .args = {OnOff()},
       .keys = {"l"},
       .key_args = "toggle",
       .menu = "View/Legend",
       .help = "A legend of every mark in the world view",
       .checked = [](const AppUi& ui) { return ui.state().legend; },
       .run = [panel](AppUi& ui, const CommandArgs& a,
                      Src) { return panel(ui)->CmdLegend(a.On(0)); }});
}

// follow, fit: where the camera looks.
void AddViewCameraRows(std::vector<Command>& t) {
  using namespace rows;
  using Src = CommandSource;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "follow",
       .args = {Initial(
           Offer(Text("ROBOT", "a robot's name, or nobody", ArgType::kChoice), RobotNames),
           [](const AppUi& ui) {
             const auto names = RobotNames(ui);
             const int f = ui.state().follow;
             return f >= 0 && f + 1 < static_cast<int>(names.size()) ? names[f + 1] : names[0];
           })},
       .menu = "View/Follow",
       .help = "Keep a robot in the middle of the world view (nobody: fit)",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         const auto names = RobotNames(ui);
         for (std::size_t i = 0; i < names.size(); ++i)
           if (names[i] == a.Text(0)) ui.state().follow = static_cast<int>(i) - 1;
         ui.state().auto_fit = ui.state().follow < 0;
         ui.state().fit_now = ui.state().follow < 0;
         return std::string();
       }});
  row({.name = "fit",
       .keys = {"f"},
       .menu = "View/Fit everything",
       .help = "Fit everything in view (and stop following)",
       .run = [](AppUi& ui, const CommandArgs&, Src) {
         ui.state().fit_now = true;
         ui.state().camera.Fit();
         ui.state().follow = -1;
         return std::string();
       }});
}

// tab, help: which tab is in front, the keys' overlay.
void AddViewNavigationRows(std::vector<Command>& t) {
  using namespace rows;
  using Src = CommandSource;
  auto panel = ViewPanelOf;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "tab",
       .args = {Choice("NAME", {"controls", "lesson", "plots", "tables", "history", "summary"})},
       .menu = "View/Show tab",
       .help = "Bring a tab to the front, in every layout (presentation mode is left for it; "
               "controls: the control panel, a tab in the narrow layout)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         const std::string name = a.Text(0);
         if (name == "lesson" && !ui.session().lesson().present)
           return std::string("this scenario is no lesson: it has no Lesson tab (open one: lesson NAME)");
         // Presentation mode shows the world view alone: the tabs come back with the panels.
         if (ui.state().present) panel(ui)->CmdPresent(false);
         ui.state().select_tab = name;
         return std::string();
       }});
  row({.name = "help",
       .args = {OnOff()},
       .keys = {"F1", "?"},
       .key_args = "toggle",
       .menu = "Help/Keys and mouse",
       .help = "The help overlay: every key and mouse gesture",
       .checked = [](const AppUi& ui) { return ui.state().help; },
       .run = [panel](AppUi& ui, const CommandArgs& a,
                      Src) { return panel(ui)->CmdHelp(a.On(0)); }});
}

}  // namespace

std::vector<Command> ViewPanel::Rows() {
  std::vector<Command> t;
  AddViewWindowRows(t);
  AddViewLookRows(t);
  AddViewCameraRows(t);
  AddViewNavigationRows(t);
  return t;
}

}  // namespace formsim::app
