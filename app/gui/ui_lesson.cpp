// The Lesson tab: a lesson file's text (title, goal, what to watch, the equations, what to try
// next), wrapped to the width of the panel.
#include <imgui.h>

#include "app/render/fonts.hpp"
#include "app/render/long_text.hpp"
#include "app/gui/ui.hpp"

namespace formsim::app {

void AppUi::DrawLessonTab(const Fonts& fonts) {
  const sim::LessonDef& l = session_->lesson();
  ImGui::BeginChild("lesson_text", ImVec2(0, 0), false);
  ImGui::PushFont(fonts.Get(FontRole::kTitle));
  LongTextWrapped("title", l.title, 300);  // any length (app/render/long_text.hpp)
  ImGui::PopFont();
  ImGui::Spacing();
  // One heading and its wrapped text per part of the lesson.
  auto part = [&](const char* heading, const std::string& text) {
    ImGui::PushFont(fonts.Get(FontRole::kLabel));
    ImGui::TextUnformatted(heading);
    ImGui::PopFont();
    LongTextWrapped(heading, text);
    ImGui::Spacing();
  };
  part("Goal", l.goal);
  if (!l.equations.empty()) {
    ImGui::PushFont(fonts.Get(FontRole::kLabel));
    ImGui::TextUnformatted("Equations");
    ImGui::PopFont();
    // Indented, one per line, so a formula never runs into the prose.
    ImGui::Indent();
    for (std::size_t i = 0; i < l.equations.size() && i < 200; ++i)
      LongTextWrapped(("eq" + std::to_string(i)).c_str(), l.equations[i], 400);
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
      if (ImGui::Button(Shorten(a.label, 80).c_str())) CmdAction(a.id);
      if (!a.help.empty() && ImGui::IsItemHovered()) SafeTooltip(a.help);
      ImGui::SameLine();
    }
    ImGui::NewLine();
  }
  ImGui::EndChild();
}

}  // namespace formsim::app
