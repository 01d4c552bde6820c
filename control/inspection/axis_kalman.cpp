#include "control/inspection/axis_kalman.hpp"

#include <cmath>

namespace formsim::control::inspection {

AxisKalman::AxisKalman(const AxisKalmanDef& def) {
  kf_.A(0, 0) = 1.0;
  kf_.B(0, 0) = 1.0;  // the dead-reckoning displacement enters directly
  kf_.H(0, 0) = 1.0;
  SetDef(def);
}

void AxisKalman::SetDef(const AxisKalmanDef& def) {
  def_ = def;
  kf_.R(0, 0) = def_.r;
}

void AxisKalman::Reset(double x0) {
  LinearKalmanFilter<1, 1, 1>::State x;
  x(0) = x0;
  LinearKalmanFilter<1, 1, 1>::Cov p;
  p(0, 0) = def_.p0;
  kf_.Reset(x, p);
  gated_in_row_ = 0;
}

bool AxisKalman::Predict(double du, double dt) {
  const auto x_before = kf_.x();
  const auto p_before = kf_.P();
  kf_.Q(0, 0) = def_.q_per_m * std::abs(du) + def_.q_per_s * dt;
  LinearKalmanFilter<1, 1, 1>::Input u;
  u(0) = du;
  kf_.Predict(u);
  if (!std::isfinite(kf_.x()(0)) || !std::isfinite(kf_.P()(0, 0)) || kf_.P()(0, 0) < 0.0) {
    kf_.Reset(x_before, p_before);
    return false;
  }
  return true;
}

AxisUpdate AxisKalman::Update(double z) {
  if (!std::isfinite(z)) return AxisUpdate::kFault;
  LinearKalmanFilter<1, 1, 1>::Meas m;
  m(0) = z;
  nis_ = kf_.Nis(m);
  if (!std::isfinite(nis_)) return AxisUpdate::kFault;
  if (def_.nis_gate > 0.0 && nis_ > def_.nis_gate) {
    if (++gated_in_row_ < def_.reacquire_after) return AxisUpdate::kGated;
    // The estimate has lost the fixes for good (e.g. wheel slip): start again from the fix.
    Reset(z);
    return AxisUpdate::kReinitialised;
  }
  const auto x_before = kf_.x();
  const auto p_before = kf_.P();
  const double p_prior = kf_.P()(0, 0);
  kf_.Update(m);
  if (!std::isfinite(kf_.x()(0)) || !std::isfinite(kf_.P()(0, 0)) || kf_.P()(0, 0) < 0.0) {
    kf_.Reset(x_before, p_before);
    return AxisUpdate::kFault;
  }
  gated_in_row_ = 0;
  gain_ = p_prior / (p_prior + def_.r);
  return AxisUpdate::kAccepted;
}

void PositionKalman::SetDef(const AxisKalmanDef& def) {
  x_.SetDef(def);
  y_.SetDef(def);
}

void PositionKalman::Reset(const Vec2& p0) {
  x_.Reset(p0.x);
  y_.Reset(p0.y);
}

bool PositionKalman::Predict(double ds, double theta, double dt) {
  const double dx = ds * std::sin(theta), dy = ds * std::cos(theta);
  if (!std::isfinite(dx) || !std::isfinite(dy)) return false;
  const bool ok_x = x_.Predict(dx, dt);
  const bool ok_y = y_.Predict(dy, dt);
  return ok_x && ok_y;
}

PositionKalman::Result PositionKalman::Update(const Vec2& z) {
  Result r;
  r.x = x_.Update(z.x);
  r.y = y_.Update(z.y);
  return r;
}

}  // namespace formsim::control::inspection
