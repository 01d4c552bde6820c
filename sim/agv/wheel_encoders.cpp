#include "sim/agv/wheel_encoders.hpp"

#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::sim::agv {

double WheelEncoders::Quantise(double angle) const {
  if (def_.ticks_per_rev <= 0) return angle;
  const double tick = 2.0 * control::kPi / def_.ticks_per_rev;
  // The relative epsilon keeps whole revolutions (k·2π) from reading one tick short.
  return std::floor(angle / tick + 1e-9) * tick;
}

void WheelEncoders::Latch(const control::agv::WheelArray& angles) {
  for (int i = 0; i < control::agv::kMecanumWheels; ++i) last_[i] = Quantise(angles[i]);
}

control::agv::WheelArray WheelEncoders::Read(const control::agv::WheelArray& angles, double period) {
  control::agv::WheelArray out{};
  for (int i = 0; i < control::agv::kMecanumWheels; ++i) {
    const double q = Quantise(angles[i]);
    const double noise = rng_.Normal();
    out[i] = period > 0.0 ? (q - last_[i]) / period + def_.speed_noise * noise : 0.0;
    last_[i] = q;
  }
  return out;
}

}  // namespace formsim::sim::agv
