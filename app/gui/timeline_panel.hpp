#pragma once
/// \file The Timeline panel, the strip under the world view: a time slider over the live run.
/// Scrubbing shows the world (poses, estimates, trails) at an earlier time from a second
/// experiment that replays the run's log: it steps forward as the slider moves forward (a few
/// milliseconds of stepping per frame) and is rebuilt from step 0 only to go back, so a scrub
/// costs at most the steps of the run so far, and the state shown is exact. "Branch from here"
/// restarts the live run from that step (Session::Branch: an exact replay up to it), pinning the
/// original first if asked. It owns the timeline's state and registers scrub, live and branch.

#include <imgui.h>

#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"
#include "app/gui/tuning_state.hpp"

namespace formsim::app {

class TimelinePanel : public Panel {
 public:
  explicit TimelinePanel(const PanelContext& ctx) : ctx_(ctx) {}
  /// scrub, live, branch (Compare menu).
  static std::vector<Command> Rows();

  const char* Name() const override { return "Timeline"; }
  /// The strip, in the rectangle Place() gave for this frame.
  void Draw(const Fonts& fonts) override;
  /// Where the strip goes (under the world view).
  void Place(ImVec2 min, ImVec2 max) {
    min_ = min;
    max_ = max;
  }

  /// Shows the world at simulated time `t` of the live run; `finish_now`: the replay reaches
  /// it before this returns (else it catches up a little every frame).
  std::string CmdScrub(double t, bool finish_now = true);
  /// Back to the live end.
  std::string CmdLive();
  /// Restarts the run from the time shown (exact), pinning the original first when asked.
  std::string CmdBranch();

  /// The world view shows an earlier time than the live end.
  bool Active() const { return tl_.active; }
  /// The replay is still on its way to the time shown (the script action `wait` holds).
  bool CatchingUp() const;
  /// The replayed run at the time shown, or null when the world view shows the live run.
  const sim::Experiment* Shown() const;
  /// Per frame: the replay steps towards the time shown for at most `budget_s` seconds (0: all
  /// the way); a reset or branched live run sends the timeline back to its end.
  void Advance(double budget_s);
  /// Another scenario was loaded: the timeline is back at the live end.
  void Forget() { tl_ = Timeline(); }

 private:
  const PanelContext& ctx_;
  Timeline tl_;
  bool pins_original_ = true;  ///< "branch from here" pins the run it leaves first
  ImVec2 min_{0, 0}, max_{0, 0};
};

}  // namespace formsim::app
