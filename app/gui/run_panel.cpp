#include "app/gui/run_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/flow_layout.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/theme.hpp"
#include "sim/core/number_format.hpp"
#include "sim/session/session.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {

const std::vector<double>& SpeedChoices() {
  static const std::vector<double> kSpeeds = {0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 0.0};
  return kSpeeds;
}

namespace {

std::string SpeedLabel(double s) {
  if (s == 0.0) return "max";
  return sim::FormatSignificant(s) + "×";
}

// The speeds as the speed command names them.
std::vector<std::string> SpeedNames() {
  std::vector<std::string> out;
  for (double s : SpeedChoices()) out.push_back(s == 0.0 ? "max" : sim::FormatDouble(s));
  return out;
}


}  // namespace

std::string RunPanel::CmdPlay() {
  ctx_.run("live");  // playing resumes from the live end
  if (held_) {
    // The question stays open: the run plays as soon as it is answered or closed.
    resume_ = true;
    ctx_.SetStatus("the run plays once the lesson's prediction is answered (Lesson tab)");
    return "";
  }
  ctx_.state->playing = true;
  return "";
}

std::string RunPanel::CmdPause() {
  ctx_.state->playing = false;
  resume_ = false;
  return "";
}

bool RunPanel::Playing() const { return ctx_.state->playing || (held_ && resume_); }

std::string RunPanel::HeldText() const {
  if (!held_) return "";
  return resume_ ? "paused for the prediction: plays once you choose (Lesson tab)"
                 : "paused for the prediction (Lesson tab)";
}

std::string RunPanel::CmdStep() {
  ctx_.run("live");
  ctx_.state->playing = false;
  resume_ = false;
  if (ctx_.session().exp().finished()) {
    return ctx_.Refuse("the run has reached its duration: reset (r) to run again");
  }
  try {
    ctx_.session().Step();
  } catch (const std::exception& e) {
    return ctx_.Refuse(std::string("step failed: ") + e.what());
  }
  if (ctx_.session().exp().finished()) ctx_.Find<HistoryPanel>()->NoteRun(ctx_.session().exp().status());
  return "";
}

std::string RunPanel::CmdReset() {
  // The run replaced keeps its history row (PanelContext::replace_run).
  const std::string err = ctx_.replace_run("reset", [&] { return ctx_.session().Reset(); });
  if (!err.empty()) return ctx_.Refuse(err);
  step_budget_ = 0;
  CopyString(seed_text_, sizeof seed_text_, std::to_string(ctx_.session().seed()));
  ctx_.SetStatus("reset");
  return "";
}

std::string RunPanel::CmdResetSeed(const std::string& seed_text) {
  std::string t = seed_text;
  t.erase(0, t.find_first_not_of(" \t"));
  t.erase(t.find_last_not_of(" \t") + 1);
  std::uint64_t seed = 0;
  if (!sim::ParseUint64(t, &seed)) {
    const std::string why =
        "seed must be a whole number in [0, 18446744073709551615], got '" + seed_text + "'";
    ctx_.SetStatus(why, true);
    return why;
  }
  // The run replaced keeps its history row (PanelContext::replace_run).
  const std::string err = ctx_.replace_run("reset", [&] { return ctx_.session().Reset(seed); });
  if (!err.empty()) return ctx_.Refuse(err);
  step_budget_ = 0;
  CopyString(seed_text_, sizeof seed_text_, std::to_string(seed));
  ctx_.SetStatus("reset with seed " + std::to_string(seed));
  return "";
}

void RunPanel::Advance(double wall_dt) {
  using Clock = std::chrono::steady_clock;
  sim::Experiment& exp = ctx_.session().exp();
  const auto t0 = Clock::now();
  int steps = 0;
  // While paused, drags and edits still apply at once (between steps, as always).
  try {
    ctx_.session().ApplyPending();
  } catch (const std::exception& e) {
    ctx_.SetStatus(std::string("could not apply the edits: ") + e.what(), true);
  }
  // Between two steps, as the pending changes: while a lesson's prediction question is open
  // the run is held; once it is answered or closed the run goes on as it was (it plays again
  // if it played, or if Play was pressed meanwhile; paused, it stays paused).
  const LessonPanel* lesson = ctx_.Find<LessonPanel>();
  const bool asking = lesson != nullptr && lesson->QuestionOpen();
  if (asking && !held_) {
    held_ = true;
    resume_ = ctx_.state->playing;
    if (ctx_.state->playing) {
      ctx_.state->playing = false;
      ctx_.SetStatus("paused while the prediction is open: choose an option, and the run goes on");
    }
  } else if (!asking && held_) {
    held_ = false;
    if (resume_ && !exp.finished()) ctx_.state->playing = true;
    resume_ = false;
  }
  if (ctx_.state->playing && ctx_.Find<TimelinePanel>()->Active()) ctx_.state->playing = false;  // the timeline pauses
  if (ctx_.state->playing && !exp.finished()) {
    try {
      const double speed = SpeedChoices()[speed_index_];
      if (speed == 0.0) {
        // As fast as possible, but leave the frame responsive: ~15 ms of stepping per frame.
        while (!ctx_.session().exp().finished()) {
          ctx_.session().Step();
          if ((++steps & 7) == 0 && std::chrono::duration<double>(Clock::now() - t0).count() > 0.015)
            break;
        }
        step_budget_ = 0;
      } else {
        step_budget_ = std::min(step_budget_ + wall_dt * speed, 0.25 * speed + exp.dt());
        while (step_budget_ >= 0.5 * exp.dt() && !ctx_.session().exp().finished()) {
          ctx_.session().Step();
          ++steps;
          step_budget_ -= ctx_.session().exp().dt();
          if (std::chrono::duration<double>(Clock::now() - t0).count() > 0.05) {
            step_budget_ = 0;  // cannot keep up: slow down rather than freeze
            break;
          }
        }
      }
      if (ctx_.session().exp().finished()) {
        ctx_.state->playing = false;
        ctx_.SetStatus("finished at " + sim::FormatSimTime(ctx_.session().exp().time()));
        ctx_.Find<HistoryPanel>()->NoteRun(ctx_.session().exp().status());
      }
    } catch (const std::exception& e) {
      // Nothing a step throws may end the program: stop and say what happened.
      ctx_.state->playing = false;
      ctx_.SetStatus(std::string("the simulation stopped: ") + e.what() + " (reset to go on)", true);
    }
  }
  steps_last_frame_ = steps;
  speed_meter_.Add(wall_dt, steps * ctx_.session().exp().dt(), SpeedChoices()[speed_index_],
                         ctx_.state->playing && !ctx_.session().exp().finished());
  sim_ms_ = 1e3 * std::chrono::duration<double>(Clock::now() - t0).count();
}

void RunPanel::Draw(const Fonts&) {
  if (ImGui::Button(Playing() ? "Pause" : "Play", ImVec2(70, 0))) Playing() ? CmdPause() : CmdPlay();
  SameLineIfFits(ButtonWidth("Step"));
  if (ImGui::Button("Step")) CmdStep();
  SameLineIfFits(ButtonWidth("Reset"));
  if (ImGui::Button("Reset")) CmdReset();
  if (SameLineIfFits(TextWidth("(space . r)"))) ImGui::TextDisabled("(space . r)");

  const auto& speeds = SpeedChoices();
  ImGui::SetNextItemWidth(120);
  int si = speed_index_;
  if (ImGui::SliderInt("speed", &si, 0, static_cast<int>(speeds.size()) - 1,
                       SpeedLabel(speeds[si]).c_str(), ImGuiSliderFlags_AlwaysClamp))
    speed_index_ = std::clamp(si, 0, static_cast<int>(speeds.size()) - 1);
  DrawAchievedSpeed();

  ImGui::SetNextItemWidth(120);
  ImGui::InputText("seed", seed_text_, sizeof seed_text_,
                   ImGuiInputTextFlags_CharsDecimal);
  SameLineIfFits(ButtonWidth("Reset with seed"));
  if (ImGui::Button("Reset with seed")) CmdResetSeed(seed_text_);

  // Read the experiment after the buttons: a reset above has replaced it.
  const sim::Experiment& exp = ctx_.session().exp();
  const double dur = exp.setup().duration;
  const std::string progress = sim::Sprintf("t = %.2f / %.1f s", exp.time(), dur);
  ImGui::ProgressBar(static_cast<float>(std::clamp(exp.time() / dur, 0.0, 1.0)), ImVec2(-1, 0),
                     progress.c_str());
  if (const std::string held = HeldText(); !held.empty()) ImGui::TextWrapped("%s", held.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped(
      "%s", sim::Sprintf("%ld steps of %.3g s; last frame: %d steps, sim %.1f ms, frame %.1f ms",
                         exp.steps(), exp.dt(), steps_last_frame_, sim_ms_, ctx_.state->frame_ms)
                .c_str());
  ImGui::PopStyleColor();
}

void RunPanel::DrawAchievedSpeed() {
  const std::string label = speed_meter_.Label();
  if (label.empty()) return;
  SameLineIfFits(TextWidth(label.c_str()));
  if (speed_meter_.behind())
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(ToImColor(GetTheme(ctx_.state->theme).error)), "%s",
                       label.c_str());
  else
    ImGui::TextDisabled("%s", label.c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Simulated seconds per wall second over the last second; \"behind\": the "
                      "simulation cannot keep up with the chosen speed");
}

void RunPanel::SetSpeed(double speed) {
  const auto& speeds = SpeedChoices();
  speed_index_ = static_cast<int>(
      std::min_element(speeds.begin(), speeds.end(),
                       [&](double a, double b) { return std::abs(a - speed) < std::abs(b - speed); }) -
      speeds.begin());
}

void RunPanel::SetSeedField(const std::string& text) {
  CopyString(seed_text_, sizeof seed_text_, text);
}

void RunPanel::SyncScenario() {
  SetSeedField(std::to_string(ctx_.session().seed()));
  step_budget_ = 0;
}

std::vector<Command> RunPanel::Rows() {
  using namespace rows;
  using Src = CommandSource;
  auto panel = [](AppUi& ui) { return ui.Find<RunPanel>(); };
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "play-pause",
       .keys = {"space"},
       .menu = "Run/Play or pause",
       .help = "Play when paused, pause when playing",
       .run = [panel](AppUi& ui, const CommandArgs&, Src) {
         return panel(ui)->Playing() ? panel(ui)->CmdPause() : panel(ui)->CmdPlay();
       }});
  row({.name = "play",
       .menu = "Run/Play",
       .help = "Run (from the live end when the timeline is back)",
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdPlay(); }});
  row({.name = "pause",
       .menu = "Run/Pause",
       .help = "Stop stepping",
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdPause(); }});
  row({.name = "step",
       .keys = {"."},
       .menu = "Run/Step",
       .help = "One step, then pause",
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdStep(); }});
  row({.name = "reset",
       .keys = {"r"},
       .menu = "Run/Reset",
       .help = "Start the run again with the current values and seed",
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdReset(); }});
  row({.name = "reset-seed",
       .args = {Initial(Text("SEED", "a seed 0 ... 18446744073709551615", ArgType::kWord),
                        [](const AppUi& ui) { return std::string(ui.Find<RunPanel>()->seed_text_); })},
       .menu = "Run/Reset with seed…",
       .help = "Start the run again with another seed",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) { return panel(ui)->CmdResetSeed(a.Text(0)); }});
  row({.name = "speed",
       .args = {Initial(Choice("SPEED", SpeedNames()),
                        [](const AppUi& ui) { return SpeedNames()[ui.Find<RunPanel>()->speed_index_]; })},
       .menu = "Run/Speed",
       .help = "Simulated seconds per second of real time (max: as fast as the frame allows)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         const auto names = SpeedNames();
         for (std::size_t i = 0; i < names.size(); ++i)
           if (names[i] == a.Text(0)) panel(ui)->speed_index_ = static_cast<int>(i);
         return std::string();
       }});
  return t;
}


}  // namespace formsim::app
