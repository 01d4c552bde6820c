/// \file The session record of the interface (everything done, with its step, for `formsim
/// replay`), its writing (Save session, --session), and the per-frame housekeeping of the
/// background work of the panels: pin replays, the Monte Carlo (Compare), the timeline.
#include <filesystem>

#include "app/gui/parameters_panel.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/run_output.hpp"

namespace fs = std::filesystem;

namespace formsim::app {

void AppUi::StartRecording(const std::vector<sim::Override>& cli, long step) {
  sim::SessionEvent load;
  load.kind = sim::SessionEvent::Kind::kLoad;
  load.step = step;
  load.source = std::make_shared<sim::ScenarioSource>(session_->source());
  load.overrides = cli;
  record_.Add(load);
  session_->SetObserver([this](const sim::SessionEvent& e) { record_.Add(e); });
}

void AppUi::SetSessionFile(const std::string& path) {
  session_file_ = path;
  CopyString(state_.session_path, sizeof(state_.session_path), path);
}

std::string AppUi::CmdSaveSession(const std::string& path) {
  if (path.empty()) {
    SetStatus("save session: give a file name", true);
    return state_.status;
  }
  try {
    record_.Write(path, session_->exp().steps());
  } catch (const std::exception& e) {
    SetStatus(std::string("session not saved: ") + e.what(), true);
    return state_.status;
  }
  SetStatus("session saved to " + path + " (replay: formsim replay " + path + ")");
  NoteFileWritten(path, "application/x-yaml");
  return "";
}

bool AppUi::Busy() const {
  return compare_->Busy() || timeline_->CatchingUp();
}

void AppUi::UpdateBackground() {
  compare_->Update();
  timeline_->Advance(0.02);
}

void AppUi::DropScenarioState() {
  compare_->Clear();
  parameters_->Clear();
  timeline_->Forget();
  history_->Forget();
}

}  // namespace formsim::app
