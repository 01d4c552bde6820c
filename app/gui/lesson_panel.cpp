// The Lesson tab: a lesson file's text (title, goal, the equations) wrapped to the width of the
// panel, then its guided steps one at a time: the step's text, its prediction (options, the
// answer judged once the run has shown it), its action button and what you should see (each
// check the step names, measured on the current run: sim/study/lesson_checks.hpp).
#include "app/gui/lesson_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <vector>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/scenario_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/fonts.hpp"
#include "app/render/long_text.hpp"
#include "sim/core/yaml_reader.hpp"
#include "sim/scenario/scenario_files.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {
namespace {

// The paper each shipped lesson teaches (its scenario's type), read once: name -> paper.
const std::map<std::string, std::string>& LessonPapers() {
  static const std::map<std::string, std::string> kPapers = [] {
    std::map<std::string, std::string> out;
    for (const std::string& f : sim::ShippedLessons()) {
      std::string type = "?";
      try {
        const YAML::Node root = sim::LoadYamlFile(f);
        if (root["type"] && root["type"].IsScalar()) type = root["type"].Scalar();
      } catch (const std::exception&) {  // listed under "?"; opening it reports the error
      }
      out[std::filesystem::path(f).stem().string()] = type;
    }
    return out;
  }();
  return kPapers;
}

std::string PaperOf(const std::string& lesson) {
  const auto& papers = LessonPapers();
  const auto it = papers.find(lesson);
  return it == papers.end() ? "?" : it->second;
}

// The shipped lessons grouped by paper (as `formsim list`), by name within a paper.
std::vector<std::string> LessonNames(const AppUi&) {
  std::vector<std::pair<std::string, std::string>> by;
  for (const auto& [name, paper] : LessonPapers()) by.emplace_back(paper, name);
  std::sort(by.begin(), by.end());
  std::vector<std::string> out;
  for (const auto& p : by) out.push_back(p.second);
  return out;
}

const LessonGuide* GuideOf(const AppUi& ui) {
  const LessonPanel* p = ui.Find<LessonPanel>();
  return p == nullptr ? nullptr : &p->guide();
}

CommandArg Grouped(CommandArg a, std::function<std::string(const std::string&)> group) {
  a.group = std::move(group);
  return a;
}

LessonGuide* GuideOf(AppUi& ui) {
  LessonPanel* p = ui.Find<LessonPanel>();
  return p == nullptr ? nullptr : &p->guide();
}

std::string NeedsLesson(const AppUi& ui) {
  const LessonGuide* g = GuideOf(ui);
  return g == nullptr ? "the window has no Lesson panel" : g->Inactive();
}

// Why the step shown cannot run its action now ("" when it can).
std::string NeedsStepAction(const AppUi& ui) {
  const LessonGuide* g = GuideOf(ui);
  return g == nullptr ? "the window has no Lesson panel" : g->ActionBlocked();
}

std::string NeedsPrediction(const AppUi& ui) {
  if (const std::string why = NeedsLesson(ui); !why.empty()) return why;
  const LessonGuide& g = *GuideOf(ui);
  return g.Current()->predict.question.empty()
             ? "step " + std::to_string(g.Step()) + " asks for no prediction"
             : "";
}

std::vector<std::string> StepNumbers(const AppUi& ui) {
  std::vector<std::string> out;
  const LessonGuide* g = GuideOf(ui);
  for (int i = 1; g != nullptr && i <= g->Steps(); ++i) out.push_back(std::to_string(i));
  return out;
}

std::vector<std::string> OptionNumbers(const AppUi& ui) {
  std::vector<std::string> out;
  if (!NeedsPrediction(ui).empty()) return out;
  const std::size_t n = GuideOf(ui)->Current()->predict.options.size();
  for (std::size_t i = 1; i <= n; ++i) out.push_back(std::to_string(i));
  return out;
}

// A row of the table run from a button: the same path as a script or the menu.
void Press(const PanelContext& ctx, const std::string& line) { ctx.run(line); }

void Heading(const Fonts& fonts, const char* text) {
  ImGui::PushFont(fonts.Get(FontRole::kLabel));
  ImGui::TextUnformatted(text);
  ImGui::PopFont();
}

}  // namespace

std::vector<Command> LessonPanel::Rows() {
  using namespace rows;
  std::vector<Command> t;
  t.push_back(
      {.name = "lesson",
       .args = {Grouped(Offer(Text("NAME", "a shipped lesson's name", ArgType::kChoice), LessonNames),
                        PaperOf)},
       .menu = "Help/Lessons",
       .help = "Open a lesson (listed by paper): its scenario, with its steps in the Lesson tab",
       .run = [](AppUi& ui, const CommandArgs& a, CommandSource) {
         const std::string err = ui.Find<ScenarioPanel>()->CmdOpen(sim::ResolveLesson(a.Text(0)));
         if (err.empty()) ui.state().select_tab = "lesson";
         return err;
       }});
  t.push_back(
      {.name = "lesson-step",
       .args = {Offer(Whole("N", 1, 1000), StepNumbers)},
       .menu = "Help/Lesson step…",
       .help = "Show step N of the lesson (kept between runs, per lesson)",
       .disabled = NeedsLesson,
       .run = [](AppUi& ui, const CommandArgs& a, CommandSource) {
         return GuideOf(ui)->GoTo(static_cast<int>(a.Whole(0)));
       }});
  t.push_back({.name = "lesson-action",
               .menu = "Help/Lesson step's action",
               .help = "Do what the lesson's step asks (its edits, through this table: undoable)",
               .disabled = NeedsStepAction,
               .run = [](AppUi& ui, const CommandArgs&, CommandSource) {
                 return GuideOf(ui)->RunAction();
               }});
  t.push_back(
      {.name = "lesson-predict",
       .args = {Offer(Whole("K", 1, 4), OptionNumbers)},
       .menu = "Help/Lesson prediction…",
       .help = "Choose option K of the step's prediction (judged once the run has shown it)",
       .disabled = NeedsPrediction,
       .run = [](AppUi& ui, const CommandArgs& a, CommandSource) {
         return GuideOf(ui)->Predict(static_cast<int>(a.Whole(0)));
       }});
  return t;
}

bool LessonPanel::Unanswered() const {
  const sim::LessonStep* step = guide_.Current();
  return step != nullptr && !step->predict.question.empty() &&
         guide_.Progress().predicted.count(guide_.Step()) == 0;
}

bool LessonPanel::QuestionOpen() const {
  if (ImGui::GetCurrentContext() == nullptr) return false;
  // Drawn in this frame or the one before (the run advances before the frame draws), or about
  // to be: the Lesson tab was just asked for (a lesson opened, a step shown).
  const UiState& st = *ctx_.state;
  const int frame = ImGui::GetFrameCount();
  // A tab bar shows a tab asked for at the frame after: held until then too.
  if (st.select_tab == "lesson" && !st.present) asked_frame_ = std::max(asked_frame_, frame + 1);
  return asked_frame_ >= frame - 1 && Unanswered();
}

void LessonPanel::DrawStep(const Fonts& fonts) {
  const int n = guide_.Steps(), at = guide_.Step();
  if (n == 0) return;
  const LessonProgress prog = guide_.Progress();
  ImGui::Separator();
  Heading(fonts, ("Step " + std::to_string(at) + " of " + std::to_string(n) + "   (" +
                  std::to_string(prog.done.size()) + " done)")
                     .c_str());
  // The steps as small buttons, wrapping to the panel's width; a done step is marked √.
  for (int i = 1; i <= n; ++i) {
    const std::string label = std::to_string(i) + (prog.done.count(i) ? " √" : "") + "##step" +
                              std::to_string(i);
    const float w = ImGui::CalcTextSize(label.c_str(), nullptr, true).x +
                    2 * ImGui::GetStyle().FramePadding.x;
    if (i > 1) {
      ImGui::SameLine();
      if (ImGui::GetContentRegionAvail().x < w) ImGui::NewLine();
    }
    if (i == at) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    if (ImGui::SmallButton(label.c_str())) Press(ctx_, "lesson-step " + std::to_string(i));
    if (i == at) ImGui::PopStyleColor();
  }
  const sim::LessonStep step = *guide_.Current();  // a copy: a button may change the session
  ImGui::Spacing();
  LongTextWrapped("step_text", guide_.Render(step.text));
  ImGui::Spacing();
  if (!step.predict.question.empty()) {
    Heading(fonts, "Predict, then run");
    if (Unanswered()) asked_frame_ = ImGui::GetFrameCount();
    LongTextWrapped("question", step.predict.question);
    const auto chosen = prog.predicted.find(at);
    for (std::size_t k = 0; k < step.predict.options.size(); ++k) {
      const int option = static_cast<int>(k) + 1;
      const bool on = chosen != prog.predicted.end() && chosen->second == option;
      if (ImGui::RadioButton(("##option" + std::to_string(option)).c_str(), on))
        Press(ctx_, "lesson-predict " + std::to_string(option));
      ImGui::SameLine();
      LongTextWrapped(("option" + std::to_string(option)).c_str(),
                      std::string(1, static_cast<char>('A' + k)) + ".  " + step.predict.options[k]);
    }
    LongTextWrapped("verdict", guide_.Verdict());
    if (!step.predict.explain.empty() && guide_.Judged()) LongTextWrapped("explain", guide_.Render(step.predict.explain));
    ImGui::Spacing();
  }
  if (!step.action.label.empty()) {
    const std::string why = guide_.ActionBlocked();
    ImGui::BeginDisabled(!why.empty());
    if (ImGui::Button(Shorten(step.action.label, 80).c_str())) Press(ctx_, "lesson-action");
    ImGui::EndDisabled();
    if (!why.empty() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) SafeTooltip(why);
  }
  if (at > 1) {
    if (!step.action.label.empty()) ImGui::SameLine();
    if (ImGui::Button("< Previous")) Press(ctx_, "lesson-step " + std::to_string(at - 1));
  }
  if (at < n) {
    if (at > 1 || !step.action.label.empty()) ImGui::SameLine();
    if (ImGui::Button("Next >")) guide_.Next();
  }
  const std::vector<std::string> checks = step.Checks();
  if (!checks.empty() && !step.predict.question.empty() && !guide_.Judged()) {
    // The checks state the answer: kept until the run has shown it.
    ImGui::Spacing();
    Heading(fonts, "What you should see");
    ImGui::TextDisabled("(shown once your prediction is judged)");
  } else if (!checks.empty()) {
    ImGui::Spacing();
    Heading(fonts, "What you should see");
    for (std::size_t i = 0; i < checks.size() && i < 50; ++i)
      LongTextWrapped(("see" + std::to_string(i)).c_str(), guide_.SeeLine(checks[i]), 300);
  }
}

void LessonPanel::DrawAllChecks() {
  const sim::LessonDef& l = ctx_.session().lesson();
  if (l.checks.empty()) return;
  ImGui::Separator();
  const bool open = ImGui::CollapsingHeader("Every check of the lesson");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("formsim lessons check runs them on their seeds");
  if (!open) return;
  std::vector<std::string> ids;
  for (const sim::LessonCheck& c : l.checks) ids.push_back(c.id);  // SeeLine may re-read the lesson
  for (std::size_t i = 0; i < ids.size() && i < 200; ++i)
    LongTextWrapped(("check" + std::to_string(i)).c_str(), guide_.SeeLine(ids[i]), 300);
}

void LessonPanel::Draw(const Fonts& fonts) {
  const sim::LessonDef& l = ctx_.session().lesson();
  ImGui::BeginChild("lesson_text", ImVec2(0, 0), false);
  ImGui::PushFont(fonts.Get(FontRole::kTitle));
  LongTextWrapped("title", l.title, 300);  // any length (app/render/long_text.hpp)
  ImGui::PopFont();
  ImGui::Spacing();
  Heading(fonts, "Goal");
  LongTextWrapped("Goal", guide_.Render(std::string(l.goal)));  // a copy: Render measures
  ImGui::Spacing();
  if (!l.equations.empty()) {
    Heading(fonts, "Equations");
    // Indented, one per line, so a formula never runs into the prose.
    ImGui::Indent();
    for (std::size_t i = 0; i < l.equations.size() && i < 200; ++i)
      LongTextWrapped(("eq" + std::to_string(i)).c_str(), l.equations[i], 400);
    ImGui::Unindent();
    ImGui::Spacing();
  }
  DrawStep(fonts);
  DrawAllChecks();
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
