/// \file The menu bar, generated from the command table (app/gui/command_rows.cpp): one menu per
/// first part of the rows' menu paths, each item showing its keys, greyed out with the reason
/// when the command cannot run now; the argument dialog of commands that take arguments; the
/// About box; exporting the figures of the current run.
#include <algorithm>

#include "app/export/figure_data.hpp"
#include "app/export/figure_export.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"

namespace formsim::app {
namespace {

std::string TopOf(const std::string& menu) {
  return menu.substr(0, menu.find('/'));
}
std::string LabelOf(const std::string& menu) {
  const auto slash = menu.find('/');
  return slash == std::string::npos ? menu : menu.substr(slash + 1);
}

// The command's only required argument when the menu can offer its values as a submenu.
const CommandArg* SubmenuArg(const Command& cmd) {
  if (cmd.args.empty() || cmd.args[0].optional) return nullptr;
  for (std::size_t i = 1; i < cmd.args.size(); ++i)
    if (!cmd.args[i].optional) return nullptr;
  const CommandArg& a = cmd.args[0];
  return a.type == ArgType::kChoice || a.offer ? &a : nullptr;
}

bool HasRequiredArgs(const Command& cmd) {
  for (const CommandArg& a : cmd.args)
    if (!a.optional) return true;
  return false;
}

}  // namespace

float AppUi::DrawMenuBar() {
  if (!ImGui::BeginMainMenuBar()) return 0;
  const float height = ImGui::GetWindowSize().y;
  std::vector<std::string> tops;
  for (const Command& c : Commands())
    if (!c.menu.empty() && std::find(tops.begin(), tops.end(), TopOf(c.menu)) == tops.end())
      tops.push_back(TopOf(c.menu));
  for (const std::string& top : tops) {
    // A kind's own menu shows only where some of it can run (Formation on formation scenarios).
    bool any = false, all_disabled = true;
    for (const Command& c : Commands()) {
      if (c.menu.empty() || TopOf(c.menu) != top) continue;
      any = true;
      if (!c.disabled || c.disabled(*this).empty()) all_disabled = false;
    }
    if (!any || all_disabled) continue;
    if (state_.open_menu == top) {
      ImGui::OpenPopup(top.c_str());  // the id BeginMenu gives its popup in the menu bar
      state_.open_menu.clear();
    }
    if (ImGui::BeginMenu(top.c_str())) {
      for (const Command& c : Commands())
        if (!c.menu.empty() && TopOf(c.menu) == top) DrawMenuItem(c);
      ImGui::EndMenu();
    }
  }
  // The status on the right of the bar: where the window stands, readable at a glance.
  const sim::Experiment& exp = session_->exp();
  const char* state = state_.playing              ? "playing"
                      : !run_->HeldText().empty() ? "paused for the prediction"
                                                  : "paused";
  const std::string where = std::string(state) + "  " + sim::FormatSimTime(exp.time());
  const float w = ImGui::CalcTextSize(where.c_str()).x;
  if (ImGui::GetContentRegionAvail().x > w + 20) {
    ImGui::SetCursorPosX(ImGui::GetWindowWidth() - w - 12);
    ImGui::TextDisabled("%s", where.c_str());
  }
  ImGui::EndMainMenuBar();
  return height;
}

void AppUi::DrawMenuItem(const Command& cmd) {
  const std::string why = cmd.disabled ? cmd.disabled(*this) : std::string();
  const bool enabled = why.empty();
  const std::string label = LabelOf(cmd.menu);
  const std::string keys = cmd.KeysText();
  auto hover = [&] {
    menu_items_[cmd.name] = {ImGui::GetItemRectMin(), ImGui::GetItemRectMax()};
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("%s\n%s", cmd.help.c_str(),
                        enabled ? cmd.Usage().c_str() : ("not now: " + why).c_str());
  };
  if (cmd.name == "open" && pick_file_hook_) {
    if (ImGui::MenuItem(label.c_str(), keys.c_str(), false, enabled)) pick_file_hook_();
    hover();
    return;
  }
  if (cmd.args.size() == 1 && cmd.args[0].type == ArgType::kOnOff) {
    const bool on = cmd.checked && cmd.checked(*this);
    if (ImGui::MenuItem(label.c_str(), keys.c_str(), on, enabled))
      RunCommand(cmd, on ? "off" : "on", CommandSource::kMenu);
    hover();
    return;
  }
  if (const CommandArg* arg = SubmenuArg(cmd)) {
    const bool open = ImGui::BeginMenu(label.c_str(), enabled);
    hover();
    if (!open) return;
    const std::vector<std::string> values = arg->choices.empty() ? arg->offer(*this) : arg->choices;
    const std::string now = arg->initial ? arg->initial(*this) : std::string();
    // Overlays are a set: each one is a check mark that adds or removes it.
    const bool overlay_set = cmd.name == "overlay";
    std::string heading;
    for (const std::string& v : values) {
      if (arg->group && arg->group(v) != heading) {
        heading = arg->group(v);
        if (&v != &values.front()) ImGui::Separator();
        ImGui::TextDisabled("%s", heading.c_str());
      }
      bool on = v == now;
      if (overlay_set) on = state_.overlays.count(v) > 0;
      if (ImGui::MenuItem(v.c_str(), nullptr, on))
        RunCommand(cmd, overlay_set && on ? "-" + v : v, CommandSource::kMenu);
    }
    if (values.empty()) ImGui::TextDisabled("(none now)");
    if (arg->type != ArgType::kChoice) {
      ImGui::Separator();
      if (ImGui::MenuItem("Other…")) OpenCommandDialog(cmd);
    }
    ImGui::EndMenu();
    return;
  }
  if (ImGui::MenuItem(label.c_str(), keys.c_str(), false, enabled)) {
    if (HasRequiredArgs(cmd))
      OpenCommandDialog(cmd);
    else
      RunCommand(cmd, "", CommandSource::kMenu);
  }
  hover();
}

void AppUi::OpenCommandDialog(const Command& cmd) {
  state_.dialog_command = cmd.name;
  state_.dialog_error.clear();
  for (std::size_t i = 0; i < 3; ++i) {
    std::string initial;
    if (i < cmd.args.size() && cmd.args[i].initial) initial = cmd.args[i].initial(*this);
    CopyString(state_.dialog_args[i], sizeof state_.dialog_args[i], initial);
  }
}

void AppUi::DrawCommandDialog() {
  if (state_.dialog_command.empty()) return;
  const Command* cmd = FindCommand(state_.dialog_command);
  if (cmd == nullptr) {
    state_.dialog_command.clear();
    return;
  }
  const char* kTitle = "Run a command###command_dialog";
  if (!ImGui::IsPopupOpen(kTitle)) ImGui::OpenPopup(kTitle);
  ImGui::SetNextWindowSize(ImVec2(520, 0), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_NoSavedSettings)) return;
  ImGui::TextUnformatted(cmd->menu.empty() ? cmd->name.c_str() : cmd->menu.c_str());
  ImGui::PushTextWrapPos(0);
  ImGui::TextDisabled("%s", cmd->help.c_str());
  ImGui::PopTextWrapPos();
  bool run = false;
  for (std::size_t i = 0; i < cmd->args.size() && i < 3; ++i) {
    const CommandArg& a = cmd->args[i];
    ImGui::PushID(static_cast<int>(i));
    if (ImGui::IsWindowAppearing() && i == 0) ImGui::SetKeyboardFocusHere();
    ImGui::SetNextItemWidth(-1);
    const std::string hint = a.name + ": " + a.TypeText() + (a.optional ? " (optional)" : "");
    if (ImGui::InputTextWithHint("##arg", hint.c_str(), state_.dialog_args[i],
                                 sizeof state_.dialog_args[i],
                                 ImGuiInputTextFlags_EnterReturnsTrue))
      run = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", hint.c_str());
    ImGui::PopID();
  }
  if (!state_.dialog_error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.85f, 0.15f, 0.1f, 1));
    ImGui::PushTextWrapPos(0);
    ImGui::TextUnformatted(
        state_.dialog_error.c_str(),
        state_.dialog_error.c_str() + std::min<std::size_t>(state_.dialog_error.size(), 400));
    ImGui::PopTextWrapPos();
    ImGui::PopStyleColor();
  }
  if (ImGui::Button("Run") || run) {
    std::string args;
    for (std::size_t i = 0; i < cmd->args.size() && i < 3; ++i)
      if (state_.dialog_args[i][0] != 0)
        args += (args.empty() ? "" : " ") + std::string(state_.dialog_args[i]);
    state_.dialog_error = RunCommand(*cmd, args, CommandSource::kMenu);
    if (state_.dialog_error.empty()) {
      state_.dialog_command.clear();
      ImGui::CloseCurrentPopup();
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) {
    state_.dialog_command.clear();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void AppUi::DrawAbout() {
  if (!state_.about) return;
  if (!ImGui::IsPopupOpen("About formsim")) ImGui::OpenPopup("About formsim");
  if (ImGui::BeginPopupModal("About formsim", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted(AboutText().c_str());
    if (ImGui::Button("Close") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) {
      state_.about = false;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

}  // namespace formsim::app
