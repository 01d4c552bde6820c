#pragma once
/// \file The Run panel: play, pause, step and reset (with a seed), the speed, and the stepping
/// itself: each frame it advances the simulation by the wall time that passed at the chosen
/// speed, and measures the speed achieved ("behind" when the run cannot keep up). It owns the
/// speed, the seed field, the simulated time owed to real time and the speed meter, and
/// registers play-pause, play, pause, step, reset, reset-seed and speed. Whether the run plays
/// is the window's (UiState::playing): the timeline and the comparison read it too.

#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"
#include "app/gui/speed_meter.hpp"

namespace formsim::app {

/// Speeds offered by the Run panel; 0 means as fast as possible.
const std::vector<double>& SpeedChoices();

class RunPanel : public Panel {
 public:
  explicit RunPanel(const PanelContext& ctx) : ctx_(ctx) {}
  /// play-pause, play, pause, step, reset, reset-seed (Run menu), speed.
  static std::vector<Command> Rows();

  const char* Name() const override { return "Run"; }
  /// The Run section of the control panel.
  void Draw(const Fonts& fonts) override;
  /// The achieved speed beside the speed field (red and "behind" when it cannot keep up); also
  /// on the presentation bar.
  void DrawAchievedSpeed();

  /// Advances the simulation for `wall_dt` seconds of real time at the chosen speed (each
  /// frame of the window).
  void Advance(double wall_dt);

  /// Play. While a lesson's prediction question is open the run stays held, and plays once it
  /// is answered or closed.
  std::string CmdPlay();
  std::string CmdPause();
  /// Whether the run plays, or will play once the prediction question holding it is closed.
  bool Playing() const;
  /// The run is held while a lesson's prediction question is open (Advance checks it between
  /// two steps, as it applies the pending changes): what the holding says, "" when not held.
  std::string HeldText() const;
  std::string CmdStep();
  std::string CmdReset();
  /// Reset with a seed given as text (0 ... 2^64 - 1).
  std::string CmdResetSeed(const std::string& seed_text);
  /// The speed closest to `speed` (0: as fast as possible) among SpeedChoices().
  void SetSpeed(double speed);
  /// The seed field's text (a history row's seed restored into it).
  void SetSeedField(const std::string& text);
  /// The simulated time owed to real time is forgiven (after a structural change, so the run
  /// does not race to catch up).
  void ForgetOwedTime() { step_budget_ = 0; }
  /// Another scenario (or a reload): the seed field shows its seed, nothing is owed.
  void SyncScenario();
  /// The wall time the last Advance spent stepping, in ms (--timing).
  double sim_ms() const { return sim_ms_; }

 private:
  const PanelContext& ctx_;
  int speed_index_ = 3;     ///< into SpeedChoices(), 3 = 1x
  char seed_text_[32] = "";
  double step_budget_ = 0;  ///< simulated seconds owed to real time
  SpeedMeter speed_meter_;  ///< the achieved speed and whether the run is behind the chosen one
  double sim_ms_ = 0;
  int steps_last_frame_ = 0;
  /// A prediction question is open (app/gui/lesson_panel.hpp): the run was paused for it.
  bool held_ = false;
  /// Whether the run plays again when the question closes: it played when the question
  /// opened, or Play was pressed while it was open (Pause and Step clear it).
  bool resume_ = false;
};

}  // namespace formsim::app
