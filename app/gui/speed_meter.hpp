#pragma once
/// \file The achieved speed of a run in the window: simulated seconds per wall second, averaged
/// over about the last second, and whether the run has fallen behind the chosen speed (the
/// simulation cannot keep up, so the window slows down rather than freeze).

#include <string>

namespace formsim::app {

class SpeedMeter {
 public:
  /// One frame: `wall_dt` wall seconds in which the run advanced `sim_dt` simulated seconds at
  /// the chosen `speed` (0: as fast as possible, never behind). Not `running` (paused,
  /// finished): the meter starts afresh.
  void Add(double wall_dt, double sim_dt, double speed, bool running);
  /// Simulated seconds per wall second over about the last second (0 before any).
  double achieved() const { return wall_ > 0 ? sim_ / wall_ : 0.0; }
  /// Below 90% of the chosen speed for more than a second.
  bool behind() const { return behind_; }
  /// "achieved 0.65x, behind" / "achieved 1.00x" / "" when not running.
  std::string Label() const;

 private:
  double wall_ = 0, sim_ = 0, below_for_ = 0;
  bool running_ = false, behind_ = false;
};

}  // namespace formsim::app
