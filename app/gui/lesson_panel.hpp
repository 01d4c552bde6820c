#pragma once
/// \file The Lesson panel: a lesson file's text (title, goal, the equations, what to watch, what
/// to try next) in the Lesson tab of the right-hand window, wrapped to the panel's width, with
/// the scenario's action buttons; it registers the `lesson` row (Help/Lessons).

#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"
#include "sim/study/lesson_checks.hpp"

namespace formsim::app {

class LessonPanel : public Panel {
 public:
  explicit LessonPanel(const PanelContext& ctx) : ctx_(ctx) {}
  /// The `lesson` row: opens a shipped lesson on its tab.
  static std::vector<Command> Rows();

  const char* Name() const override { return "Lesson"; }
  /// The Lesson tab's body (the window draws the tab when the session has a lesson).
  void Draw(const Fonts& fonts) override;

 /// The checks measured on the current run, computed once per finished run (Results() is not
  /// free) and kept until the run, its length or the lesson changes.
  struct CheckCache {
    const sim::Experiment* exp = nullptr;
    long steps = -1;
    const sim::LessonDef* lesson = nullptr;
    std::vector<sim::LiveCheck> results;
  };

 private:
  const PanelContext& ctx_;
  CheckCache checks_;
};

}  // namespace formsim::app
