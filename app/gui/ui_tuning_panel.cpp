/// \file The Compare section of the control panel: pin the run, run N seeds (progress, cancel),
/// undo and redo of edits, and saving the session record. Every line has a fixed height, so the
/// Parameters below never move when something here changes.
#include <algorithm>
#include <cstdio>

#include "app/gui/ui.hpp"

namespace formsim::app {

void AppUi::DrawTuningSection() {
  if (ImGui::Button("Pin")) CmdPin();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Keep this run as a reference: dashed in every plot, faded in the world\n"
        "view, a column of the comparison table");
  ImGui::SameLine();
  ImGui::BeginDisabled(pins_.empty());
  if (ImGui::Button("Unpin all")) CmdUnpinAll();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("%zu pinned (History tab)", pins_.size());

  // Monte Carlo: the count, Run or Cancel, and a bar that is always there.
  const bool running = mc_.run && !mc_.run->finished();
  ImGui::SetNextItemWidth(90);
  ImGui::BeginDisabled(running);
  ImGui::InputInt("##seeds", &state_.mc_seeds, 1, 10);
  state_.mc_seeds = std::clamp(state_.mc_seeds, 1, 100000);
  ImGui::SameLine();
  char run_label[48];
  std::snprintf(run_label, sizeof run_label, "Run %d seeds", state_.mc_seeds);
  if (ImGui::Button(run_label)) CmdSeeds(state_.mc_seeds);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "The current settings over seeds 1..N in the background: bands on every\n"
        "time plot, mean ± σ in the comparison table (as formsim sweep --seeds 1..N)");
  ImGui::SameLine();
  ImGui::BeginDisabled(!running);
  if (ImGui::Button("Cancel")) CmdCancelSeeds();
  ImGui::EndDisabled();
  float fraction = 0;
  char bar[160] = "no Monte Carlo yet";
  if (mc_.run) {
    const sim::SweepProgress p = mc_.run->progress();
    fraction = p.total ? static_cast<float>(p.done) / static_cast<float>(p.total) : 1.0f;
    std::snprintf(bar, sizeof bar, "%zu / %zu seeds%s: %s", p.done, p.total,
                  running                                    ? ""
                  : mc_.run->cancelled() && p.done < p.total ? " (cancelled)"
                                                             : "",
                  mc_.settings.c_str());
  }
  ImGui::ProgressBar(fraction, ImVec2(-1, 0), bar);
  if (mc_.run && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", bar);

  // Undo / redo of edits (Ctrl+Z / Ctrl+Y).
  ImGui::BeginDisabled(!session_->can_undo());
  if (ImGui::Button("Undo")) CmdUndo();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Ctrl+Z: %s",
                      session_->can_undo() ? session_->UndoText().c_str() : "nothing");
  ImGui::SameLine();
  ImGui::BeginDisabled(!session_->can_redo());
  if (ImGui::Button("Redo")) CmdRedo();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Ctrl+Y: %s",
                      session_->can_redo() ? session_->RedoText().c_str() : "nothing");
  ImGui::SameLine();
  ImGui::TextDisabled("%d edits since loading", session_->accepted_edits());

  ImGui::SetNextItemWidth(-110);
  ImGui::InputText("##session", state_.session_path, sizeof(state_.session_path));
  ImGui::SameLine();
  if (ImGui::Button("Save session")) CmdSaveSession(state_.session_path);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Everything done so far, step by step (replay it headless:\n"
        "formsim replay FILE --out DIR)");
}

}  // namespace formsim::app
