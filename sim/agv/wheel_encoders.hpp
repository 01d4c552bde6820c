#pragma once
/// \file Incremental wheel encoders: they count WHEEL rotation (not ground motion), quantised to
/// ticks, plus Gaussian noise on each speed reading.

#include "control/agv/kinematics.hpp"
#include "sim/core/rng.hpp"

namespace formsim::sim::agv {

struct WheelEncoderDef {
  /// Counts per wheel revolution (0: continuous angle), at most 10^6. The count is kept as a
  /// double (exact to 2^53 ticks), so it never overflows.
  int ticks_per_rev = 4096;
  double speed_noise = 0.0;  ///< σ of each wheel speed reading, rad/s
};

class WheelEncoders {
 public:
  WheelEncoders(const WheelEncoderDef& def, Rng rng) : def_(def), rng_(rng) {}
  void SetDef(const WheelEncoderDef& def) { def_ = def; }
  const WheelEncoderDef& def() const { return def_; }
  /// Latches the current wheel angles without producing a reading (start of the first period).
  void Latch(const control::agv::WheelArray& angles);
  /// Wheel speeds [rad/s] over the `period` seconds since the last call: tick count difference
  /// over the period, plus noise. Always draws four normals, so the stream is stable.
  control::agv::WheelArray Read(const control::agv::WheelArray& angles, double period);

 private:
  double Quantise(double angle) const;
  WheelEncoderDef def_;
  Rng rng_;
  control::agv::WheelArray last_{};
};

}  // namespace formsim::sim::agv
