#pragma once
/// \file The guided steps of a lesson in the window (sim/scenario/lesson.hpp): the step shown,
/// the steps done and the predictions made, kept per lesson in the settings file
/// (app/gui/ui_settings.hpp); a step's action run through the window's command table (recorded
/// and undoable like any edit); the checks a step names measured live on the current run; a
/// prediction judged once the run has shown its check. The Lesson panel draws it; the script
/// actions `lesson-step N`, `lesson-action` and `lesson-predict K` call it.

#include <map>
#include <string>

#include "app/gui/panel_context.hpp"
#include "app/gui/ui_settings.hpp"
#include "sim/study/lesson_checks.hpp"

namespace formsim::sim {
class Session;
}  // namespace formsim::sim

namespace formsim::app {

/// How the session's current run came about, as a lesson check compares it: the --set values
/// and the window's edits it started with (edits back to the file's value left out, the seed
/// left out), and whether it was changed while it ran.
sim::RunEdits CurrentRunEdits(const sim::Session& session);

class LessonGuide {
 public:
  explicit LessonGuide(const PanelContext& ctx) : ctx_(ctx) {}

  /// "" when the session is a lesson with steps, else why the lesson actions are refused.
  std::string Inactive() const;
  /// The lesson's name: its file's stem (the key of its progress).
  std::string Name() const;
  /// Number of steps (0: no lesson).
  int Steps() const;
  /// The step shown, 1-based (0: no lesson).
  int Step() const;
  /// The step shown, or null.
  const sim::LessonStep* Current() const;
  /// The lesson's progress (a copy: steps done, predictions).
  LessonProgress Progress() const;

  /// Shows step `n` (1-based); refused out of range, naming the range.
  std::string GoTo(int n);
  /// Marks the step shown done and shows the next one (refused on the last).
  std::string Next();
  /// "" when the step's action can run now, else why not (no action; predict first).
  std::string ActionBlocked() const;
  /// Runs the step's action, line by line, through the command table (stops at the first
  /// refusal, naming it). Refused as ActionBlocked says.
  std::string RunAction();
  /// Chooses option `k` (1-based) of the step's prediction; refused when the step asks none or
  /// `k` is out of range.
  std::string Predict(int k);

  /// Check `id` of the lesson measured on the current run (once ready; kept until the run
  /// changes).
  sim::LiveCheck Live(const std::string& id);
  /// `paragraph` (the goal, a step's text, an explanation) as the student reads it: every
  /// {check} replaced by its value on the current run and its verdict, "(…)" while pending
  /// (sim::RenderLessonParagraph, the renderer `formsim lessons show` prints with).
  std::string Render(const std::string& paragraph);
  /// "{tau_l} within [0.95, 1.05]: 1.002  √ holds", "…  not yet (the run reaches t = 3 s)", ...
  std::string SeeLine(const std::string& id);
  /// The step's prediction: "" when the step asks none; what was chosen and, once the run has
  /// shown its check, "You predicted B — right: ..." or "... — not quite: ...".
  std::string Verdict();
  /// The step's prediction was made and its check measured on this run (its explanation and
  /// what you should see are shown only then: they state the answer).
  bool Judged();

 private:
  LessonProgress& Mutable();
  void Save();

  const PanelContext& ctx_;
  // Live checks of one run: measured once ready (Results() is not free).
  const sim::Experiment* run_exp_ = nullptr;
  long run_id_ = -1;
  std::size_t run_changes_ = 0;
  std::map<std::string, sim::LiveCheck> live_;
};

}  // namespace formsim::app
