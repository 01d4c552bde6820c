#include "app/gui/timeline_panel.hpp"

#include "app/gui/flow_layout.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/number_format.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {

namespace {

using Src = CommandSource;

// The window's timeline (every window has one).
TimelinePanel& TheTimeline(const AppUi& ui) {
  return *ui.Find<TimelinePanel>();
}

std::string NeedsTimeline(const AppUi& ui) {
  return TheTimeline(ui).Active() ? ""
                             : "move the timeline back first (the world view shows the live run)";
}

}  // namespace

const sim::Experiment* TimelinePanel::Shown() const {
  return tl_.active && tl_.replay ? &tl_.replay->exp() : nullptr;
}

bool TimelinePanel::CatchingUp() const {
  return tl_.active && (!tl_.replay || tl_.replay->step() != tl_.target) &&
         !(tl_.replay && tl_.replay->exp().finished());
}

void TimelinePanel::Advance(double budget_s) {
  if (!tl_.active) return;
  if (tl_.run_id != ctx_.session().run_id()) {
    tl_ = Timeline();  // the run was reset or branched: the timeline is back at its end
    return;
  }
  try {
    if (!tl_.replay || tl_.replay->step() > tl_.target) {
      tl_.replay = std::make_unique<sim::RunReplay>(
          ctx_.session().source(), ctx_.session().run_log(),
          [](sim::Experiment& e) { e.mutable_recorder().SetHistoryLimit(2000); });
      ++tl_.rebuilds;
    }
    using Clock = std::chrono::steady_clock;
    const auto end = Clock::now() + std::chrono::duration<double>(budget_s);
    std::function<bool()> stop;
    if (budget_s > 0) stop = [&] { return Clock::now() > end; };
    tl_.replay->AdvanceTo(tl_.target, false, stop);
  } catch (const std::exception& e) {
    tl_ = Timeline();
    ctx_.SetStatus(std::string("timeline: the replay failed: ") + e.what(), true);
  }
}

std::string TimelinePanel::CmdScrub(double t, bool finish_now) {
  const sim::Experiment& exp = ctx_.session().exp();
  // [0, end of the run so far]: refused outside it before t becomes a step (1e308 / dt is no
  // step number). A step of slack (and the float rounding of the slider) so that the live end,
  // typed as shown or dragged to, is accepted.
  const double end = std::max(exp.time(), static_cast<double>(exp.steps()) * exp.dt());
  if (!std::isfinite(t) || t < 0 || t > end + std::max(exp.dt(), 1e-6 * end)) {
    const std::string why =
        sim::Sprintf("scrub: t = %.6g s is outside the run so far, 0 ... %.6g s", t, end);
    ctx_.SetStatus(why, true);
    return why;
  }
  const long step = std::min(exp.steps(), static_cast<long>(std::llround(t / exp.dt())));
  if (step >= exp.steps()) return CmdLive();
  ctx_.state->playing = false;
  if (tl_.run_id != ctx_.session().run_id()) tl_ = Timeline();
  tl_.active = true;
  tl_.run_id = ctx_.session().run_id();
  tl_.target = step;
  if (finish_now) Advance(0);
  ctx_.SetStatus("timeline at " + sim::FormatSimTime(step * exp.dt()) + " (live end " +
                 sim::FormatFixed(exp.time(), 2) + " s): play to go on, or branch from here");
  return "";
}

std::string TimelinePanel::CmdLive() {
  tl_.active = false;
  tl_.replay.reset();
  return "";
}

std::string TimelinePanel::CmdBranch() {
  if (!tl_.active) {
    const std::string why = "branch: move the timeline to the time to branch from first";
    ctx_.SetStatus(why, true);
    return why;
  }
  const long at = tl_.target;
  const double t = at * ctx_.session().exp().dt();
  if (pins_original_) ctx_.run("pin");
  const std::string err = ctx_.replace_run("branched", [&] { return ctx_.session().Branch(at); });
  if (!err.empty()) {
    ctx_.SetStatus(err, true);
    return err;
  }
  tl_ = Timeline();
  ctx_.state->playing = false;
  ctx_.SetStatus("branched at " + sim::FormatSimTime(t) + ": change the gains, then play");
  return "";
}

void TimelinePanel::Draw(const Fonts&) {
  const ImVec2 min = min_, max = max_;
  const sim::Experiment& live = ctx_.session().exp();
  ImGui::SetCursorScreenPos(ImVec2(min.x + 6, min.y + 4));
  ImGui::PushID("timeline");
  const ImGuiStyle& st = ImGui::GetStyle();
  // A narrow view keeps room for the slider with shorter labels: the first set that leaves the
  // slider 100 px (the last one, the checkbox without its text, else).
  struct Labels {
    const char* branch;
    const char* pin;
  };
  constexpr Labels kLabels[] = {{"Branch from here", "pin original"}, {"Branch", "pin"}, {"Branch", "##pin"}};
  const float room = max.x - min.x - 6 - 8;  // the cursor starts 6 in; 8 kept free at the right
  Labels labels = kLabels[2];
  float slider = 60;
  for (const Labels& l : kLabels) {
    const float buttons = ButtonWidth("Live") + ButtonWidth(l.branch) + CheckboxWidth(l.pin) +
                          3 * st.ItemSpacing.x;
    labels = l, slider = room - buttons;
    if (slider >= 100) break;
  }
  const char* branch = labels.branch;
  const char* pin = labels.pin;
  ImGui::SetNextItemWidth(std::max(40.0f, slider));
  float t = static_cast<float>(tl_.active ? tl_.target * live.dt() : live.time());
  const float end = static_cast<float>(std::max(live.time(), live.dt()));
  // The slider's format: its own value, then the live end as text.
  const std::string fmt = tl_.active ? "t = %.2f s of " + sim::FormatFixed(live.time(), 2)
                                     : std::string("t = %.2f s (live)");
  if (ImGui::SliderFloat("##t", &t, 0.0f, end, fmt.c_str(), ImGuiSliderFlags_AlwaysClamp))
    CmdScrub(t, false);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Timeline: drag back to see the world at an earlier time (an exact\n"
        "replay of the run); play goes on from the live end");
  ImGui::SameLine();
  ImGui::BeginDisabled(!tl_.active);
  if (ImGui::Button("Live")) CmdLive();
  ImGui::SameLine();
  if (ImGui::Button(branch)) CmdBranch();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "Branch from here: restart the run from this time with the gains as you\n"
        "set them next (the state of the whole world at this time, exactly)");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::Checkbox(pin, &pins_original_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Pin the original run before branching");
  ImGui::PopID();
}

std::vector<Command> TimelinePanel::Rows() {
  using namespace rows;
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "scrub",
       .args = {Real("T", 0, 1e9, "s")},
       .menu = "Compare/Timeline: go to time…",
       .help = "Show the world at time T of the live run (exact, replayed)",
       .run = [](AppUi& ui, const CommandArgs& a, Src) { return TheTimeline(ui).CmdScrub(a.Real(0)); }});
  row({.name = "live",
       .menu = "Compare/Timeline: back to live",
       .help = "Show the live end of the run again",
       .run = [](AppUi& ui, const CommandArgs&, Src) { return TheTimeline(ui).CmdLive(); }});
  row({.name = "branch",
       .menu = "Compare/Branch from the timeline",
       .help = "Restart the run from the time the timeline shows (pins the original first)",
       .disabled = NeedsTimeline,
       .run = [](AppUi& ui, const CommandArgs&, Src) { return TheTimeline(ui).CmdBranch(); }});
  return t;
}

}  // namespace formsim::app
