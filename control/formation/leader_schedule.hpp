#pragma once
/// \file Open-loop (v, ω) schedules of a formation's root leader (paper 000, section 3.1).
///  - kSegments: piecewise-constant segments, each valid until its end time (the last holds);
///    with ramp > 0 each change of (v, ω) is linear over the first `ramp` seconds of the new
///    segment (so a large formation can follow: no step in the turn rate of the root means no
///    step in the speeds its far robots need).
///  - kLineCurve (trajectory 1): v, ω = 0 on [0, 2) and (6, 8], −ω_a on [2, 6], +ω_a on (8, 17],
///    ω_a = π/5 in the paper; after 17 s ω stays +ω_a.
///  - kFigureEight (trajectory 2): ω = −ω_a on [0, 5.5], +ω_a on (5.5, 11], ω_a = π/3; after 11 s
///    the pattern repeats with period 11 s.
///  - kSpiral (trajectory 3; the paper omits its functions, this is our choice): the speed grows
///    linearly, v(t) = v0 + a t, on a circle whose radius grows linearly, R(t) = R0 + b t, so
///    ω(t) = v(t) / R(t) (an outward spiral; with the defaults v0 = 2.5 m/s, a = 0.05 m/s²,
///    R0 = 2 m, b = 0.2 m/s, ω falls from 1.25 to 0.65 rad/s over 15 s).

#include <string>
#include <vector>

#include "control/formation/link_kinematics.hpp"

namespace formsim::control::formation {

/// One constant piece of a segments schedule.
struct ScheduleSegment {
  double until = 0.0;  ///< end time, s (inclusive)
  double v = 0.0;      ///< m/s
  double w = 0.0;      ///< rad/s
};

/// Definition of a schedule (Box2D-style struct with defaults).
struct LeaderScheduleDef {
  enum class Kind { kSegments, kLineCurve, kFigureEight, kSpiral } kind = Kind::kLineCurve;
  double v = 2.5;          ///< forward speed (v0 for the spiral), m/s
  double omega = kPi / 5;  ///< turn-rate amplitude ω_a for line-curve and figure eight, rad/s
  double accel = 0.05;     ///< spiral: dv/dt, m/s²
  double r0 = 2.0;         ///< spiral: initial radius, m
  double r_rate = 0.2;     ///< spiral: dR/dt, m/s
  std::vector<ScheduleSegment> segments;
  double ramp = 0.0;  ///< segments: duration of each change, s (at most any segment's length)
};

/// The command of a leader at time t.
inline Twist ScheduleAt(const LeaderScheduleDef& d, double t) {
  using Kind = LeaderScheduleDef::Kind;
  switch (d.kind) {
    case Kind::kSegments: {
      if (d.segments.empty()) return {};
      std::size_t k = 0;
      while (k + 1 < d.segments.size() && t > d.segments[k].until) ++k;
      const ScheduleSegment& s = d.segments[k];
      if (k == 0 || d.ramp <= 0.0) return {s.v, s.w};
      // Within the ramp into segment k: linear from the previous segment's values.
      const ScheduleSegment& p = d.segments[k - 1];
      const double f = (t - p.until) / d.ramp;
      if (f >= 1.0) return {s.v, s.w};
      return {p.v + f * (s.v - p.v), p.w + f * (s.w - p.w)};
    }
    case Kind::kLineCurve: {
      double w = 0.0;
      if (t >= 2.0 && t <= 6.0)
        w = -d.omega;
      else if (t > 8.0)
        w = d.omega;
      return {d.v, w};
    }
    case Kind::kFigureEight: {
      const double tau = t - 11.0 * std::floor(t / 11.0);
      return {d.v, tau <= 5.5 && !(t > 0.0 && tau == 0.0) ? -d.omega : d.omega};
    }
    case Kind::kSpiral: {
      const double v = d.v + d.accel * t;
      return {v, v / (d.r0 + d.r_rate * t)};
    }
  }
  return {};
}

/// Names used in scenarios: "segments", "line_curve", "figure_eight", "spiral".
inline std::vector<std::string> ScheduleKindNames() {
  return {"segments", "line_curve", "figure_eight", "spiral"};
}

}  // namespace formsim::control::formation
