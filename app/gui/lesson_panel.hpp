#pragma once
/// \file The Lesson panel: a lesson file's text (title, goal, the equations) and its guided
/// steps (app/gui/lesson_guide.hpp) in the Lesson tab of the right-hand window, wrapped to the
/// panel's width: the step's text, its action button, its prediction and what you should see
/// (the checks it names, live on the current run), with the scenario's action buttons. It
/// registers the rows `lesson` (Help/Lessons), `lesson-step N`, `lesson-action` and
/// `lesson-predict K`.

#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/lesson_guide.hpp"
#include "app/gui/panel_context.hpp"

namespace formsim::app {

class LessonPanel : public Panel {
 public:
  explicit LessonPanel(const PanelContext& ctx) : ctx_(ctx), guide_(ctx) {}
  /// The lesson rows: open a shipped lesson, go to a step, run its action, predict.
  static std::vector<Command> Rows();

  const char* Name() const override { return "Lesson"; }
  /// The Lesson tab's body (the window draws the tab when the session has a lesson).
  void Draw(const Fonts& fonts) override;

  /// The guided steps of the session's lesson.
  LessonGuide& guide() { return guide_; }
  /// A prediction question is open: the Lesson tab showed it in the last frame drawn and it is
  /// still unanswered (no option chosen for the step shown). The run is held meanwhile
  /// (RunPanel::Advance); a tab brought over it, another step, presentation mode or another
  /// scenario closes it.
  bool QuestionOpen() const;
  const LessonGuide& guide() const { return guide_; }

 private:
  void DrawStep(const Fonts& fonts);
  void DrawAllChecks();

  /// True while the step shown has a prediction and no option is chosen for it.
  bool Unanswered() const;

  const PanelContext& ctx_;
  LessonGuide guide_;
  /// The ImGui frame that last drew an unanswered question (or will: the tab was asked for).
  mutable int asked_frame_ = -1000;
};

}  // namespace formsim::app
