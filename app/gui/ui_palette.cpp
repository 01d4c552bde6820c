/// \file The command palette (Ctrl+K): type to filter every command of the table and every
/// tunable of the scenario by name, label or help ("k_l R2" finds R2's k_l); Enter runs the
/// command (its argument dialog when it takes arguments) or puts the keyboard in the tunable's
/// field. Recent commands come first.
#include <algorithm>
#include <cctype>

#include "app/gui/parameters_panel.hpp"
#include "app/gui/tunable_label.hpp"
#include "app/gui/ui.hpp"
#include "app/render/label_markup.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<std::string> Words(const std::string& s) {
  std::vector<std::string> out;
  std::string w;
  for (char c : s) {
    if (c == ' ' || c == '\t') {
      if (!w.empty()) out.push_back(Lower(w));
      w.clear();
    } else {
      w += c;
    }
  }
  if (!w.empty()) out.push_back(Lower(w));
  return out;
}

// Every word of the filter must occur in the entry's text; a word in its name counts more.
bool Matches(const std::vector<std::string>& words, const std::string& name,
             const std::string& text, int* score) {
  const std::string n = Lower(name), t = Lower(text);
  *score = 0;
  for (const std::string& w : words) {
    if (n.find(w) != std::string::npos) continue;
    if (t.find(w) == std::string::npos) return false;
    *score += 1;
  }
  return true;
}

}  // namespace

std::string AppUi::CmdPalette(const std::string& filter) {
  state_.palette = true;
  state_.palette_focus = true;
  state_.palette_selected = 0;
  CopyString(state_.palette_filter, sizeof state_.palette_filter, filter);
  return "";
}

std::vector<PaletteEntry> AppUi::PaletteEntries(const std::string& filter) const {
  const std::vector<std::string> words = Words(filter);
  std::vector<PaletteEntry> entries;
  // Commands: recent ones first when nothing is typed.
  for (const Command& c : Commands()) {
    if (c.script_only) continue;
    int score = 0;
    if (!Matches(words, c.name, c.menu + " " + c.help + " " + c.KeysText(), &score)) continue;
    const auto r = std::find(state_.recent_commands.begin(), state_.recent_commands.end(), c.name);
    if (words.empty() && r != state_.recent_commands.end())
      score = -100 + static_cast<int>(r - state_.recent_commands.begin());
    entries.push_back({false, c.name, c.help, EscapeMarkup(c.help), c.KeysText(), score});
  }
  // Tunables, only once something is typed (there can be thousands).
  if (!words.empty())
    for (const sim::Param& p : session_->params().all()) {
      const std::string unit = p.tune.unit.empty() ? "" : " [" + p.tune.unit + "]";
      // The tunable's one name, as the Parameters panel shows it (with its subscripts).
      const std::string markup =
          EscapeMarkup(p.tune.group.empty() ? "" : p.tune.group + ": ") + TunableLabel(p) +
          EscapeMarkup(unit + " = " + p.Text());
      int score = 0;
      if (!Matches(words, p.key, p.tune.label + unit + " " + p.tune.group, &score)) continue;
      entries.push_back({true, p.key, MarkupText(markup), markup, "", score + 1});
    }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const PaletteEntry& a, const PaletteEntry& b) { return a.score < b.score; });
  return entries;
}

void AppUi::DrawPalette(ImVec2 display) {
  if (!state_.palette) return;
  const std::vector<PaletteEntry> entries = PaletteEntries(state_.palette_filter);
  const int shown = static_cast<int>(std::min<std::size_t>(entries.size(), 14));
  state_.palette_selected = std::clamp(state_.palette_selected, 0, std::max(0, shown - 1));

  const float w = std::min(680.0f, display.x - 40);
  ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, 0.12f * display.y), ImGuiCond_Always,
                          ImVec2(0.5f, 0));
  ImGui::SetNextWindowSize(ImVec2(w, 0));
  ImGui::SetNextWindowFocus();
  ImGui::Begin("##palette", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::TextDisabled(
      "Command palette: type to filter commands and tunables; Enter runs, Esc closes");
  if (state_.palette_focus) {
    ImGui::SetKeyboardFocusHere();
    state_.palette_focus = false;
  }
  ImGui::SetNextItemWidth(-1);
  const bool enter =
      ImGui::InputTextWithHint("##filter", "e.g. k_l R2, pin, theme", state_.palette_filter,
                               sizeof state_.palette_filter, ImGuiInputTextFlags_EnterReturnsTrue);
  if (ImGui::IsItemEdited()) state_.palette_selected = 0;
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_DownArrow)))
    state_.palette_selected = std::min(state_.palette_selected + 1, std::max(0, shown - 1));
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_UpArrow)))
    state_.palette_selected = std::max(state_.palette_selected - 1, 0);
  const bool escape = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false);
  int chosen = enter ? state_.palette_selected : -1;
  ImGui::Separator();
  for (int i = 0; i < shown; ++i) {
    const PaletteEntry& e = entries[i];
    ImGui::PushID(i);
    const std::string left = (e.tunable ? "tunable  " : "") + e.name;
    // One highlighted row: the selection. The mouse moves the selection (a row hovered after
    // the mouse moved becomes the selected one) instead of lighting a second row.
    const bool selected = i == state_.palette_selected;
    if (!selected) {
      ImGui::PushStyleColor(ImGuiCol_HeaderHovered, ImVec4(0, 0, 0, 0));
      ImGui::PushStyleColor(ImGuiCol_HeaderActive, ImGui::GetStyleColorVec4(ImGuiCol_Header));
    }
    if (ImGui::Selectable(left.c_str(), selected)) chosen = i;
    if (!selected) ImGui::PopStyleColor(2);
    const ImVec2 moved = ImGui::GetIO().MouseDelta;
    if (ImGui::IsItemHovered() && (moved.x != 0 || moved.y != 0)) state_.palette_selected = i;
    ImGui::SameLine(std::max(230.0f, ImGui::CalcTextSize(left.c_str()).x + 30));
    MarkupTextItem(ShortenMarkup(e.detail_markup, 90),
                   ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    if (!e.keys.empty()) {
      ImGui::SameLine(w - ImGui::CalcTextSize(e.keys.c_str()).x - 20);
      ImGui::TextDisabled("%s", e.keys.c_str());
    }
    ImGui::PopID();
  }
  if (entries.empty())
    ImGui::TextDisabled("nothing matches");
  else if (static_cast<int>(entries.size()) > shown)
    ImGui::TextDisabled(
        "%s", sim::Sprintf("… %zu more: type more to narrow", entries.size() - shown).c_str());
  ImGui::End();

  if (escape) {
    state_.palette = false;
    return;
  }
  if (chosen < 0 || chosen >= shown) return;
  const PaletteEntry e = entries[chosen];
  state_.palette = false;
  if (e.tunable) {
    parameters_->Focus(e.name);
    state_.present = false;  // the field is in the left-hand panel
    SetStatus("tunable " + e.name + ": type its value");
    return;
  }
  const Command* cmd = FindCommand(e.name);
  if (cmd == nullptr) return;
  bool needs_args = false;
  for (const CommandArg& a : cmd->args) needs_args |= !a.optional;
  if (needs_args && !(cmd->args.size() == 1 && cmd->args[0].type == ArgType::kOnOff))
    OpenCommandDialog(*cmd);
  else
    RunCommand(*cmd, cmd->args.size() == 1 && cmd->args[0].type == ArgType::kOnOff ? "toggle" : "",
               CommandSource::kPalette);
}

}  // namespace formsim::app
