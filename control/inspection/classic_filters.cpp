#include "control/inspection/classic_filters.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::control::inspection {

void MeanFilter::SetWindow(int window) {
  window_ = window < 1 ? 1 : static_cast<std::size_t>(window);
  while (samples_.size() > window_) samples_.pop_front();
}

double MeanFilter::Filter(double z) {
  samples_.push_back(z);
  while (samples_.size() > window_) samples_.pop_front();
  return value();
}

double MeanFilter::value() const {
  if (samples_.empty()) return std::nan("");
  double sum = 0.0;
  for (double s : samples_) sum += s;
  return sum / static_cast<double>(samples_.size());
}

ClassicPositionFilter::ClassicPositionFilter(const LimitFilterDef& limit, int window)
    : limit_(limit), mx_(window), my_(window) {}

void ClassicPositionFilter::Configure(const LimitFilterDef& limit, int window) {
  limit_ = limit;
  mx_.SetWindow(window);
  my_.SetWindow(window);
}

void ClassicPositionFilter::Reset() {
  has_last_ = false;
  rejected_in_row_ = 0;
  mx_.Reset();
  my_.Reset();
}

bool ClassicPositionFilter::Filter(const Vec2& z, double t) {
  if (!std::isfinite(z.x) || !std::isfinite(z.y)) return false;
  const double allowed = limit_.max_step + limit_.max_rate * std::max(0.0, t - t_last_);
  const bool accept =
      !has_last_ || (z - last_).Norm() <= allowed || rejected_in_row_ >= limit_.reacquire_after;
  if (!accept) {
    ++rejected_in_row_;
    ++rejected_total_;
    return false;
  }
  has_last_ = true;
  last_ = z;
  t_last_ = t;
  rejected_in_row_ = 0;
  mx_.Filter(z.x);
  my_.Filter(z.y);
  return true;
}

void HeadingFilter::SetDef(const HeadingFilterDef& def) {
  def_ = def;
  while (static_cast<int>(samples_.size()) > std::max(1, def_.window)) samples_.pop_front();
}

void HeadingFilter::Reset(double theta) {
  theta_ = WrapToPi(theta);
  samples_.clear();
  rejected_in_row_ = 0;
}

void HeadingFilter::Propagate(double dtheta) {
  if (!std::isfinite(dtheta)) return;
  theta_ = WrapToPi(theta_ + dtheta);
  for (double& s : samples_) s = WrapToPi(s + dtheta);
}

bool HeadingFilter::Update(double theta_measured) {
  if (!std::isfinite(theta_measured)) return false;
  const bool reseed = rejected_in_row_ >= def_.reacquire_after;
  if (!reseed && std::abs(AngleDiff(theta_measured, theta_)) > def_.limit) {
    ++rejected_in_row_;
    ++rejected_total_;
    return false;
  }
  if (reseed) samples_.clear();
  rejected_in_row_ = 0;
  samples_.push_back(WrapToPi(theta_measured));
  while (static_cast<int>(samples_.size()) > std::max(1, def_.window)) samples_.pop_front();
  // Circular mean about the newest sample (all samples are within the limit of each other).
  const double ref = samples_.back();
  double sum = 0.0;
  for (double s : samples_) sum += AngleDiff(s, ref);
  theta_ = WrapToPi(ref + sum / static_cast<double>(samples_.size()));
  return true;
}

}  // namespace formsim::control::inspection
