/// \file Crash-safe sessions in the window: the session record journaled as it grows
/// (sim::SessionJournal), and the restore of an unfinished session (a journal whose window is
/// gone) offered by a banner and the script actions restore-session / discard-session, never
/// done by itself.
#include <imgui.h>

#include <algorithm>
#include <ctime>
#include <filesystem>

#include "app/gui/history_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/long_text.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

std::string LocalTime(std::time_t t) {
  char buf[64];
  std::tm tm{};
  localtime_r(&t, &tm);
  std::strftime(buf, sizeof(buf), "%Y-%m-%d %H:%M", &tm);
  return buf;
}

std::string Describe(const sim::RecoveredSession& r) {
  return "an unfinished session from " + LocalTime(r.started) + " (" + Shorten(r.scenario, 80) +
         ", " + std::to_string(r.edits) + (r.edits == 1 ? " edit" : " edits") + ", up to step " +
         std::to_string(r.record.end_step()) + ")";
}

}  // namespace

void AppUi::StartJournal(const std::string& dir) {
  try {
    journal_ =
        std::make_unique<sim::SessionJournal>(dir, Shorten(session_->exp().setup().name, 200));
  } catch (const std::exception& e) {
    SetStatus(std::string("the session is not journaled (not safe from a crash): ") + e.what(),
              true);
    return;
  }
  for (const sim::SessionEvent& e : record_.events()) journal_->Append(e);
  record_.SetListener([this](const sim::SessionEvent& e) {
    if (journal_) journal_->Append(e);
  });
}

void AppUi::NoteJournalStep() {
  if (!journal_) return;
  journal_->NoteStep(session_->exp().steps());
  if (!journal_->error().empty() && !journal_error_shown_) {
    journal_error_shown_ = true;
    SetStatus(journal_->error(), true);
  }
}

void AppUi::CloseJournal(bool remove) {
  if (!journal_) return;
  record_.SetListener(nullptr);
  if (remove) {
    journal_->Remove();
  } else {
    journal_->NoteStep(session_->exp().steps(), 0);
  }
  journal_.reset();
}

void AppUi::FindUnfinishedSessions(const std::string& dir) {
  unfinished_ = sim::UnfinishedSessions(dir);
  if (journal_)
    unfinished_.erase(
        std::remove_if(unfinished_.begin(), unfinished_.end(),
                       [&](const sim::RecoveredSession& r) { return r.path == journal_->path(); }),
        unfinished_.end());
  if (!unfinished_.empty())
    SetStatus("There is " + Describe(unfinished_.front()) +
              ": Restore or Discard it (top of the panel)");
}

std::string AppUi::CmdRestoreSession() {
  if (unfinished_.empty()) {
    SetStatus("restore session: there is no unfinished session to restore", true);
    return state_.status;
  }
  const sim::RecoveredSession r = unfinished_.front();
  // Replayed as `formsim replay` does (the same run setup, so --out gets the restored run's
  // rows); the current run's stream is dropped first and taken up again if the replay fails.
  std::unique_ptr<sim::Session> restored;
  if (run_setup_) session_->exp().mutable_recorder().AbandonStream();
  try {
    sim::SessionReplay replay(r.record, run_setup_);
    while (replay.Advance()) {
    }
    restored = replay.Release();
  } catch (const std::exception& e) {
    if (run_setup_) run_setup_(session_->exp());
    SetStatus(std::string("session not restored (") + r.path + "): " + e.what(), true);
    return state_.status;
  }
  // As a load: the current run goes into its history, then the restored session takes over,
  // its record (and journal) going on from the restored one.
  history_->Shelve(session_->file());
  DropScenarioState();
  session_->SetObserver(nullptr);
  owned_ = std::move(restored);
  session_ = owned_.get();
  SyncScenarioFields();
  record_ = r.record;
  record_.SetListener(nullptr);
  if (journal_) {
    journal_->Rewrite(record_, session_->exp().steps());
    record_.SetListener([this](const sim::SessionEvent& e) {
      if (journal_) journal_->Append(e);
    });
  }
  session_->SetObserver([this](const sim::SessionEvent& e) { record_.Add(e); });
  history_->LoadFor(session_->file());
  std::error_code ec;
  std::filesystem::remove(r.path, ec);
  unfinished_.erase(unfinished_.begin());
  state_.playing = false;
  SetStatus("restored " + Describe(r) +
            "; paused at t = " + std::to_string(session_->exp().time()) + " s");
  return "";
}

std::string AppUi::CmdDiscardSession() {
  if (unfinished_.empty()) {
    SetStatus("discard session: there is no unfinished session", true);
    return state_.status;
  }
  const sim::RecoveredSession r = unfinished_.front();
  std::error_code ec;
  std::filesystem::remove(r.path, ec);
  if (ec) {
    SetStatus("discard session: cannot remove " + r.path + ": " + ec.message(), true);
    return state_.status;
  }
  unfinished_.erase(unfinished_.begin());
  SetStatus("discarded " + Describe(r));
  return "";
}

void AppUi::DrawRestoreBanner() {
  if (unfinished_.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_ChildBg, ImVec4(0.98f, 0.92f, 0.70f, 1));
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.2f, 0.15f, 0.0f, 1));
  const float h = 3.2f * ImGui::GetTextLineHeightWithSpacing() + ImGui::GetFrameHeightWithSpacing();
  if (ImGui::BeginChild("##restore_banner", ImVec2(0, h), true)) {
    const std::string text = "An unfinished session: " + Describe(unfinished_.front()).substr(22);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    const std::string path = unfinished_.front().path;
    bool restore = ImGui::Button("Restore");
    if (ImGui::IsItemHovered())
      SafeTooltip("Replays it and goes on from where it stopped (script: restore-session)\n" +
                  path);
    ImGui::SameLine();
    const bool discard = ImGui::Button("Discard");
    if (ImGui::IsItemHovered())
      SafeTooltip("Deletes its journal (script: discard-session)\n" + path);
    if (restore)
      CmdRestoreSession();
    else if (discard)
      CmdDiscardSession();
    if (!unfinished_.empty() && unfinished_.size() > 1) {
      ImGui::SameLine();
      ImGui::TextDisabled("%s", sim::Sprintf("(%zu more)", unfinished_.size() - 1).c_str());
    }
  }
  ImGui::EndChild();
  ImGui::PopStyleColor(2);
}

}  // namespace formsim::app
