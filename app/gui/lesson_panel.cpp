// The Lesson tab: a lesson file's text (title, goal, what to watch, the equations, what to try
// next), wrapped to the width of the panel, and what you should see: each check the text names
// ({id}), measured on the current run once it has ended (sim/study/lesson_checks.hpp).
#include "app/gui/lesson_panel.hpp"

#include <imgui.h>

#include <filesystem>
#include <vector>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/ui.hpp"
#include "app/render/fonts.hpp"
#include "app/render/long_text.hpp"
#include "sim/core/number_format.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/study/lesson_checks.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {
namespace {

// "What you should see": each check, measured on the current run once it has ended.
void DrawLessonChecks(const sim::LessonDef& l, const sim::Experiment& exp,
                      LessonPanel::CheckCache& cache) {
  if (l.checks.empty()) return;
  ImGui::Separator();
  ImGui::TextUnformatted("What you should see (formsim lessons check runs them all on their seeds)");
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

std::vector<std::string> LessonNames(const AppUi&) {
  std::vector<std::string> out;
  for (const std::string& f : sim::ShippedLessons())
    out.push_back(std::filesystem::path(f).stem().string());
  return out;
}

}  // namespace

std::vector<Command> LessonPanel::Rows() {
  using namespace rows;
  std::vector<Command> t;
  t.push_back(
      {.name = "lesson",
       .args = {Offer(Text("NAME", "a shipped lesson's name", ArgType::kChoice), LessonNames)},
       .menu = "Help/Lessons",
       .help = "Open a lesson: its scenario, with the text in the Lesson tab",
       .run = [](AppUi& ui, const CommandArgs& a, CommandSource) {
         const std::string err = ui.CmdOpen(sim::ResolveLesson(a.Text(0)));
         if (err.empty()) ui.state().select_tab = "lesson";
         return err;
       }});
  return t;
}

void LessonPanel::Draw(const Fonts& fonts) {
  const sim::LessonDef& l = ctx_.session().lesson();
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
  DrawLessonChecks(l, ctx_.session().exp(), checks_);
  const auto actions = ctx_.session().exp().Actions();
  if (!actions.empty()) {
    ImGui::Separator();
    ImGui::TextDisabled("This scenario's buttons (also under Parameters):");
    for (const sim::ActionSpec& a : actions) {
      if (ImGui::Button(Shorten(a.label, 80).c_str())) ctx_.run("action " + a.id);
      if (!a.help.empty() && ImGui::IsItemHovered()) SafeTooltip(a.help);
      ImGui::SameLine();
    }
    ImGui::NewLine();
  }
  ImGui::EndChild();
}

}  // namespace formsim::app
