#pragma once
/// \file The paper's DR/LMS fusion (section 1.3): one scalar linear Kalman filter per axis.
///   state:        x(k) = x(k−1) + ΔS sin θ + Γ w,    y(k) = y(k−1) + ΔS cos θ + Γ w
///   measurement:  z_x = x + v,  z_y = y + v   (the laser trilateration fix, eq. 2)
/// Each axis is a LinearKalmanFilter<1,1,1> with A = B = H = 1; the process noise of a step is
/// Γ²Q = q_per_m·|Δ| + q_per_s·Δt (odometry error grows with the distance along that axis).
/// Fixes whose normalised innovation exceeds a gate are rejected (laser outliers); after
/// `reacquire_after` rejections in a row the axis is re-initialised on the fix. A non-finite
/// input, state or variance is a fault: the step is undone and reported, never propagated.

#include "control/common/geometry.hpp"
#include "control/common/linear_kf.hpp"

namespace formsim::control::inspection {

struct AxisKalmanDef {
  double q_per_m = 2e-4;     ///< process noise variance per metre moved along the axis, m²/m
  double q_per_s = 1e-5;     ///< process noise variance per second, m²/s
  double r = 4e-3;           ///< fix noise variance R, m²
  double p0 = 1e-2;          ///< initial variance P0, m²
  double nis_gate = 16.0;    ///< innovation²/S above this rejects the fix; ≤ 0 disables the gate
  int reacquire_after = 25;  ///< consecutive rejected fixes before re-initialising on the fix
};
inline AxisKalmanDef DefaultAxisKalmanDef() {
  return AxisKalmanDef{};
}

/// Outcome of one measurement update.
enum class AxisUpdate { kAccepted, kGated, kReinitialised, kFault };

/// One axis.
class AxisKalman {
 public:
  explicit AxisKalman(const AxisKalmanDef& def = DefaultAxisKalmanDef());
  void SetDef(const AxisKalmanDef& def);
  void Reset(double x0);
  /// Time update with the dead-reckoning displacement `du` along this axis over `dt` seconds.
  /// Returns false (and leaves the state unchanged) on a non-finite result.
  bool Predict(double du, double dt);
  AxisUpdate Update(double z);
  double x() const { return kf_.x()(0); }
  double P() const { return kf_.P()(0, 0); }
  double gain() const { return gain_; }  ///< Kalman gain of the last accepted update
  double nis() const { return nis_; }    ///< normalised innovation of the last offered fix

 private:
  AxisKalmanDef def_;
  LinearKalmanFilter<1, 1, 1> kf_;
  int gated_in_row_ = 0;
  double gain_ = 0.0, nis_ = 0.0;
};

/// Both axes, predicted together from ΔS and the heading (eq. 1), updated with a 2-D fix.
class PositionKalman {
 public:
  explicit PositionKalman(const AxisKalmanDef& def = DefaultAxisKalmanDef()) : x_(def), y_(def) {}
  void SetDef(const AxisKalmanDef& def);
  void Reset(const Vec2& p0);
  /// Returns false on a numerical fault (the estimate is then left as it was).
  bool Predict(double ds, double theta, double dt);
  struct Result {
    AxisUpdate x = AxisUpdate::kAccepted;
    AxisUpdate y = AxisUpdate::kAccepted;
    bool fault() const { return x == AxisUpdate::kFault || y == AxisUpdate::kFault; }
    bool reinitialised() const {
      return x == AxisUpdate::kReinitialised || y == AxisUpdate::kReinitialised;
    }
  };
  Result Update(const Vec2& z);
  Vec2 position() const { return {x_.x(), y_.x()}; }
  const AxisKalman& axis_x() const { return x_; }
  const AxisKalman& axis_y() const { return y_; }

 private:
  AxisKalman x_, y_;
};

}  // namespace formsim::control::inspection
