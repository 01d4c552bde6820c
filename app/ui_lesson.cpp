// The Lesson tab: a lesson file's text (title, goal, what to watch, the equations, what to try
// next), wrapped to the width of the panel.
#include <imgui.h>

#include "app/fonts.hpp"
#include "app/ui.hpp"

namespace formsim::app {

void AppUi::DrawLessonTab(const Fonts& fonts) {
  const sim::LessonDef& l = session_->lesson();
  ImGui::BeginChild("lesson_text", ImVec2(0, 0), false);
  ImGui::PushFont(fonts.Get(FontRole::kTitle));
  ImGui::TextWrapped("%s", l.title.c_str());
  ImGui::PopFont();
  ImGui::Spacing();
  // One heading and its wrapped text per part of the lesson.
  auto part = [&](const char* heading, const std::string& text) {
    ImGui::PushFont(fonts.Get(FontRole::kLabel));
    ImGui::TextUnformatted(heading);
    ImGui::PopFont();
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::Spacing();
  };
  part("Goal", l.goal);
  if (!l.equations.empty()) {
    ImGui::PushFont(fonts.Get(FontRole::kLabel));
    ImGui::TextUnformatted("Equations");
    ImGui::PopFont();
    // Indented, one per line, so a formula never runs into the prose.
    ImGui::Indent();
    for (const std::string& e : l.equations) ImGui::TextWrapped("%s", e.c_str());
    ImGui::Unindent();
    ImGui::Spacing();
  }
  part("What to watch", l.watch);
  part("What to try next", l.try_next);
  const auto actions = session_->exp().Actions();
  if (!actions.empty()) {
    ImGui::Separator();
    ImGui::TextDisabled("This scenario's buttons (also under Parameters):");
    for (const sim::ActionSpec& a : actions) {
      if (ImGui::Button(a.label.c_str())) CmdAction(a.id);
      if (!a.help.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", a.help.c_str());
      ImGui::SameLine();
    }
    ImGui::NewLine();
  }
  ImGui::EndChild();
}

}  // namespace formsim::app
