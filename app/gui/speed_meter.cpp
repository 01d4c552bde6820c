#include "app/gui/speed_meter.hpp"

#include <cmath>

#include "sim/core/number_format.hpp"

namespace formsim::app {

void SpeedMeter::Add(double wall_dt, double sim_dt, double speed, bool running) {
  if (!running || !(wall_dt > 0) || !std::isfinite(wall_dt)) {
    if (!running) *this = SpeedMeter();
    return;
  }
  running_ = true;
  // Sums that forget with a time constant of a second: the speed of about the last second.
  const double keep = std::exp(-wall_dt);
  wall_ = wall_ * keep + wall_dt;
  sim_ = sim_ * keep + sim_dt;
  const bool below = speed > 0 && wall_ > 0.5 && achieved() < 0.9 * speed;
  below_for_ = below ? below_for_ + wall_dt : 0.0;
  behind_ = below_for_ > 1.0;
}

std::string SpeedMeter::Label() const {
  if (!running_ || wall_ <= 0) return "";
  return sim::Sprintf("achieved %.2fx%s", achieved(), behind_ ? ", behind" : "");
}

}  // namespace formsim::app
