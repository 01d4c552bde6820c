#pragma once
/// \file What the window (AppUi) hands every panel (app/gui/panel.hpp) instead of itself: the
/// session and its record, the window's options (view, theme, status text, playing), the status
/// line, the command runner, ReplaceRun, and the other panels. A panel reaches nothing else of the
/// window.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/gui/panel.hpp"

namespace formsim::sim {
class Experiment;
class Session;
class SessionRecord;
}  // namespace formsim::sim

namespace formsim::app {

struct UiState;

struct PanelContext {
  /// The session now (loading another scenario replaces it: ask again, keep no reference).
  std::function<sim::Session&()> session;
  /// The experiment the world view shows: the timeline's replay when it is on, else the live
  /// run (the plots' time cursor).
  std::function<const sim::Experiment&()> shown;
  /// The record of the session (notes of what the panels did go into it).
  sim::SessionRecord* record = nullptr;
  /// The window's options shared by the panels: the view, the theme, `playing`, the status
  /// text, the slider gesture (app/gui/ui.hpp).
  UiState* state = nullptr;
  /// Replaces the session by `session` (a scenario loaded), keeping the old one's history;
  /// `message` goes to the status line.
  std::function<void(std::unique_ptr<sim::Session> session, const std::string& message)> adopt;
  /// The session's scenario changed in place (reloaded): the panels follow its file and kind.
  std::function<void()> scenario_changed;
  /// The status line's message (an error in red, also over the world view).
  std::function<void(const std::string& message, bool error)> set_status;
  /// Runs one script action "ACTION [ARGS]" through the command table (a command of another
  /// part of the window, checked as from a script). Returns "" or why it was refused.
  std::function<std::string(const std::string& line)> run;
  /// Replaces the live run by `change` (a structural change, a branch), keeping the old run's
  /// history row with `status` when `change` succeeds (AppUi::ReplaceRun).
  std::function<std::string(const std::string& status, const std::function<std::string()>& change)>
      replace_run;
  /// A file the user asked for was written (a saved scenario or session, a screenshot, a
  /// figure): the browser page offers it as a download (AppUi::SetFileWrittenHook).
  std::function<void(const std::string& path, const std::string& mime)> file_written;
  /// The window's panels and the kind's own panel (may hold null), for Find().
  const std::vector<std::unique_ptr<Panel>>* panels = nullptr;
  const std::unique_ptr<Panel>* kind_panel = nullptr;

  void SetStatus(const std::string& message, bool error = false) const {
    set_status(message, error);
  }
  void NoteFileWritten(const std::string& path, const std::string& mime) const {
    if (file_written) file_written(path, mime);
  }
  /// Shows `why` in red in the status line and returns it (a command's refusal).
  std::string Refuse(const std::string& why) const {
    set_status(why, true);
    return why;
  }

  /// The panel of type P the window has now, or null.
  template <class P>
  P* Find() const {
    if (kind_panel != nullptr)
      if (auto* p = dynamic_cast<P*>(kind_panel->get())) return p;
    if (panels != nullptr)
      for (const auto& panel : *panels)
        if (auto* p = dynamic_cast<P*>(panel.get())) return p;
    return nullptr;
  }
};

}  // namespace formsim::app
