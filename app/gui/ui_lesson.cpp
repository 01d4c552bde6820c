// The Lesson tab: a lesson file's text (title, goal, what to watch, the equations, what to try
// next), wrapped to the width of the panel, and what you should see: each check the text names
// ({id}), measured on the current run once it has ended (sim/study/lesson_checks.hpp).
#include <imgui.h>

#include <vector>

#include "app/render/fonts.hpp"
#include "app/render/long_text.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/number_format.hpp"
#include "sim/study/lesson_checks.hpp"

namespace formsim::app {

namespace {

// The checks measured on the current run, once per finished run (Results() is not free).
void DrawLessonChecks(const sim::LessonDef& l, const sim::Experiment& exp) {
  if (l.checks.empty()) return;
  ImGui::Separator();
  ImGui::TextUnformatted("What you should see (formsim lessons check runs them all on their seeds)");
  struct Cache {
    const sim::Experiment* exp = nullptr;
    long steps = -1;
    const sim::LessonDef* lesson = nullptr;
    std::vector<sim::LiveCheck> results;
  };
  static Cache cache;  // the window draws on one thread
  const bool done = exp.finished();
  if (done && (cache.exp != &exp || cache.steps != exp.steps() || cache.lesson != &l)) {
    cache = {&exp, exp.steps(), &l, {}};
    for (const sim::LessonCheck& c : l.checks) cache.results.push_back(sim::MeasureOnRun(l, c, exp));
  }
  const bool fresh = done && cache.exp == &exp && cache.results.size() == l.checks.size();
  for (std::size_t i = 0; i < l.checks.size() && i < 200; ++i) {
    const sim::LessonCheck& c = l.checks[i];
    std::string line = "{" + c.id + "}  " + sim::LessonRelationText(c) + ":  ";
    if (!fresh) {
      line += "not yet (when the run has ended)";
    } else if (!cache.results[i].error.empty()) {
      line += cache.results[i].error;
    } else {
      line += sim::FormatSignificant(cache.results[i].value, 4) +
              (cache.results[i].holds ? "  holds" : "  not yet (does not hold on this run)");
    }
    LongTextWrapped(("check" + std::to_string(i)).c_str(), line, 300);
  }
}

}  // namespace

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
  DrawLessonChecks(l, session_->exp());
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
