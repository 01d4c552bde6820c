#pragma once
/// \file The paper's "classical" filters (section 1.3 and Fig. 8-9): a limit (amplitude) filter
/// that rejects samples jumping too far from the last accepted one, and a moving-average (mean)
/// filter. Used for the comparison curves of x and y and, motion-compensated, for the heading,
/// which the paper does not Kalman-filter.

#include <cstddef>
#include <deque>

#include "control/common/geometry.hpp"

namespace formsim::control::inspection {

/// Limit filter settings: a sample is accepted when |z − last| ≤ max_step + max_rate·Δt, where
/// Δt is the time since the last accepted sample (so a gap in the fixes does not lock it out).
struct LimitFilterDef {
  double max_step = 0.3;     ///< allowed jump between consecutive samples
  double max_rate = 1.0;     ///< extra allowance per second since the last accepted sample
  int reacquire_after = 10;  ///< after this many consecutive rejections the next sample is taken
};

/// Moving average over the last `window` samples.
class MeanFilter {
 public:
  explicit MeanFilter(int window = 5) : window_(window < 1 ? 1 : window) {}
  void SetWindow(int window);
  void Reset() { samples_.clear(); }
  double Filter(double z);
  double value() const;
  bool empty() const { return samples_.empty(); }

 private:
  std::size_t window_;
  std::deque<double> samples_;
};

/// Limit then mean filter on a position fix (the paper's classical chain). The limit applies to
/// the jump of both coordinates together (a fix with one wild coordinate is a wild fix); the
/// mean filters x and y separately.
class ClassicPositionFilter {
 public:
  ClassicPositionFilter(const LimitFilterDef& limit = LimitFilterDef{}, int window = 5);
  void Configure(const LimitFilterDef& limit, int window);
  void Reset();
  /// Filters one fix taken at time t. Returns false when the limit filter rejected it (the
  /// output then keeps its previous value).
  bool Filter(const Vec2& z, double t);
  Vec2 value() const { return {mx_.value(), my_.value()}; }
  bool has_value() const { return !mx_.empty(); }
  long rejected() const { return rejected_total_; }

 private:
  LimitFilterDef limit_;
  bool has_last_ = false;
  Vec2 last_;
  double t_last_ = 0.0;
  int rejected_in_row_ = 0;
  long rejected_total_ = 0;
  MeanFilter mx_, my_;
};

/// Heading filter: laser headings are limit-filtered against the current estimate and averaged
/// over the last `window` accepted ones. Between scans the estimate follows the encoder heading
/// increments, and so do the stored samples (motion compensation), so the mean does not lag in
/// turns and the heading survives stretches without a fix. Angles in the paper convention.
struct HeadingFilterDef {
  double limit = 0.17;       ///< reject laser headings further than this from the estimate, rad
  int window = 5;            ///< mean filter length
  int reacquire_after = 10;  ///< consecutive rejections after which the estimate is re-seeded
};

class HeadingFilter {
 public:
  explicit HeadingFilter(const HeadingFilterDef& def = HeadingFilterDef{}) : def_(def) {}
  void SetDef(const HeadingFilterDef& def);
  void Reset(double theta);
  /// Adds an encoder heading increment to the estimate and the stored samples.
  void Propagate(double dtheta);
  /// Offers a laser heading; returns true when accepted.
  bool Update(double theta_measured);
  double value() const { return theta_; }
  long rejected() const { return rejected_total_; }

 private:
  HeadingFilterDef def_;
  double theta_ = 0.0;
  std::deque<double> samples_;
  int rejected_in_row_ = 0;
  long rejected_total_ = 0;
};

}  // namespace formsim::control::inspection
