/// \file The session record of the interface (everything done, with its step, for `formsim
/// replay`), its writing (Save session, --session), and the per-frame housekeeping of the
/// background work of tuning: pin replays, the Monte Carlo, the timeline.
#include <chrono>
#include <filesystem>

#include "app/gui/history_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/run_output.hpp"

namespace fs = std::filesystem;

namespace formsim::app {

namespace {

double WallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

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
  std::snprintf(state_.session_path, sizeof(state_.session_path), "%s", path.c_str());
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
  return "";
}

bool AppUi::Busy() const {
  for (const auto& p : pins_)
    if (p->job.valid()) return true;
  if (mc_.run && (!mc_.run->finished() || !mc_.tables)) return true;
  if (span_.Busy()) return true;
  return timeline_->CatchingUp();
}

void AppUi::UpdateBackground() {
  // Pins whose replay has finished.
  for (auto& p : pins_) {
    if (!p->job.valid() || p->job.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
      continue;
    PinnedRun::Result r = p->job.get();
    if (!r.error.empty()) {
      p->error = r.error;
      SetStatus("pin " + std::to_string(p->id) + " failed: " + r.error, true);
      continue;
    }
    p->exp = std::move(r.exp);
    p->values = std::move(r.values);
    p->results = p->exp->Results();
  }
  // The Monte Carlo: its spread now and then while it runs, everything once it is done.
  if (mc_.run) {
    const double now = WallSeconds();
    const bool done = mc_.run->finished();
    if ((done && !mc_.tables) || now - mc_.bands_at > 0.5) {
      mc_.bands = mc_.run->Bands();
      mc_.headlines = mc_.run->HeadlineStats();
      mc_.bands_at = now;
    }
    if (done && !mc_.tables) {
      mc_.tables = mc_.run->Tables();
      const sim::SweepProgress p = mc_.run->progress();
      const std::string err = mc_.run->error();
      if (!err.empty())
        SetStatus("Monte Carlo failed: " + err, true);
      else
        SetStatus(std::string(mc_.run->cancelled() && p.done < p.total ? "Monte Carlo cancelled: "
                                                                       : "Monte Carlo done: ") +
                  std::to_string(p.done) + " of " + std::to_string(p.total) + " seeds" +
                  (p.failed ? ", " + std::to_string(p.failed) + " failed" : ""));
    }
  }
  timeline_->Advance(0.02);
}

RunValues AppUi::CurrentValues() const {
  RunValues v;
  for (const sim::Param& p : session_->params().all()) v.emplace_back(p.key, p.Text());
  v.emplace_back("seed", std::to_string(session_->seed()));
  return v;
}

void AppUi::DropScenarioState() {
  pins_.clear();  // each pin's destructor waits for its replay, which stops at once
  span_.Clear();
  state_.value_entry.Close();
  next_pin_ = 1;
  mc_ = MonteCarloState();
  timeline_->Forget();
  history_->Forget();
}

}  // namespace formsim::app
