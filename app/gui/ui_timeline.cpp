/// \file The timeline under the world view: a time slider over the live run. Scrubbing shows the
/// world (poses, estimates, trails) at an earlier time from a second experiment that replays the
/// run's log: it steps forward as the slider moves forward (a few milliseconds of stepping per
/// frame) and is rebuilt from step 0 only to go back, so a scrub costs at most the steps of the
/// run so far, and the state shown is exact. "Branch from here" restarts the live run from that
/// step (Session::Branch: an exact replay up to it), pinning the original first if asked.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "app/gui/ui.hpp"

namespace formsim::app {

double AppUi::CursorTime() const {
  return ShownExperiment().time();
}

const sim::Experiment& AppUi::ShownExperiment() const {
  if (timeline_.active && timeline_.replay) return timeline_.replay->exp();
  return session_->exp();
}

void AppUi::AdvanceTimeline(double budget_s) {
  if (!timeline_.active) return;
  if (timeline_.run_id != session_->run_id()) {
    timeline_ = Timeline();  // the run was reset or branched: the timeline is back at its end
    return;
  }
  try {
    if (!timeline_.replay || timeline_.replay->step() > timeline_.target) {
      timeline_.replay = std::make_unique<sim::RunReplay>(
          session_->source(), session_->run_log(),
          [](sim::Experiment& e) { e.mutable_recorder().SetHistoryLimit(2000); });
      ++timeline_.rebuilds;
    }
    using Clock = std::chrono::steady_clock;
    const auto end = Clock::now() + std::chrono::duration<double>(budget_s);
    std::function<bool()> stop;
    if (budget_s > 0) stop = [&] { return Clock::now() > end; };
    timeline_.replay->AdvanceTo(timeline_.target, false, stop);
  } catch (const std::exception& e) {
    timeline_ = Timeline();
    SetStatus(std::string("timeline: the replay failed: ") + e.what(), true);
  }
}

std::string AppUi::CmdScrub(double t, bool finish_now) {
  const sim::Experiment& exp = session_->exp();
  // [0, end of the run so far]: refused outside it before t becomes a step (1e308 / dt is no
  // step number). A step of slack (and the float rounding of the slider) so that the live end,
  // typed as shown or dragged to, is accepted.
  const double end = std::max(exp.time(), static_cast<double>(exp.steps()) * exp.dt());
  if (!std::isfinite(t) || t < 0 || t > end + std::max(exp.dt(), 1e-6 * end)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "scrub: t = %.6g s is outside the run so far, 0 ... %.6g s",
                  t, end);
    const std::string why = buf;
    SetStatus(why, true);
    return why;
  }
  const long step = std::min(exp.steps(), static_cast<long>(std::llround(t / exp.dt())));
  if (step >= exp.steps()) return CmdLive();
  state_.playing = false;
  if (timeline_.run_id != session_->run_id()) timeline_ = Timeline();
  timeline_.active = true;
  timeline_.run_id = session_->run_id();
  timeline_.target = step;
  if (finish_now) AdvanceTimeline(0);
  char buf[96];
  std::snprintf(buf, sizeof buf,
                "timeline at t = %.2f s (live end %.2f s): play to go on, or "
                "branch from here",
                step * exp.dt(), exp.time());
  SetStatus(buf);
  return "";
}

std::string AppUi::CmdLive() {
  timeline_.active = false;
  timeline_.replay.reset();
  return "";
}

std::string AppUi::CmdBranch() {
  if (!timeline_.active) {
    const std::string why = "branch: move the timeline to the time to branch from first";
    SetStatus(why, true);
    return why;
  }
  const long at = timeline_.target;
  const double t = at * session_->exp().dt();
  if (state_.branch_pins_original) CmdPin();
  auto row = PendingRow("branched");
  const std::string err = session_->Branch(at);
  if (!err.empty()) {
    SetStatus(err, true);
    return err;
  }
  if (row) history_.Add(std::move(*row));
  timeline_ = Timeline();
  state_.playing = false;
  char buf[96];
  std::snprintf(buf, sizeof buf, "branched at t = %.2f s: change the gains, then play", t);
  SetStatus(buf);
  return "";
}

void AppUi::DrawTimeline(ImVec2 min, ImVec2 max) {
  const sim::Experiment& live = session_->exp();
  ImGui::SetCursorScreenPos(ImVec2(min.x + 6, min.y + 4));
  ImGui::PushID("timeline");
  const ImGuiStyle& st = ImGui::GetStyle();
  auto button_w = [&](const char* s) { return ImGui::CalcTextSize(s).x + 2 * st.FramePadding.x; };
  // A narrow view keeps room for the slider with shorter labels.
  const bool narrow = max.x - min.x < 560;
  const char* branch = narrow ? "Branch" : "Branch from here";
  const char* pin = narrow ? "pin" : "pin original";
  const float buttons = button_w("Live") + button_w(branch) + ImGui::GetFrameHeight() +
                        st.ItemInnerSpacing.x + ImGui::CalcTextSize(pin).x + 3 * st.ItemSpacing.x;
  ImGui::SetNextItemWidth(std::max(60.0f, max.x - min.x - buttons - 14));
  float t = static_cast<float>(timeline_.active ? timeline_.target * live.dt() : live.time());
  const float end = static_cast<float>(std::max(live.time(), live.dt()));
  char fmt[64];
  std::snprintf(fmt, sizeof fmt, timeline_.active ? "t = %%.2f s of %.2f" : "t = %%.2f s (live)",
                live.time());
  if (ImGui::SliderFloat("##t", &t, 0.0f, end, fmt, ImGuiSliderFlags_AlwaysClamp))
    CmdScrub(t, false);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Timeline: drag back to see the world at an earlier time (an exact\n"
        "replay of the run); play goes on from the live end");
  ImGui::SameLine();
  ImGui::BeginDisabled(!timeline_.active);
  if (ImGui::Button("Live")) CmdLive();
  ImGui::SameLine();
  if (ImGui::Button(branch)) CmdBranch();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "Branch from here: restart the run from this time with the gains as you\n"
        "set them next (the state of the whole world at this time, exactly)");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::Checkbox(pin, &state_.branch_pins_original);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Pin the original run before branching");
  ImGui::PopID();
}

}  // namespace formsim::app
