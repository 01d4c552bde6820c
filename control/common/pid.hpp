#pragma once
/// \file PID controllers: positional with clamping anti-windup, and incremental (velocity form).

#include <algorithm>
#include <cmath>
#include <limits>

namespace formsim::control {

/// Gains and limits of a PID loop.
struct PidGains {
  double kp = 1.0;
  double ki = 0.0;
  double kd = 0.0;
  double out_min = -std::numeric_limits<double>::infinity();
  double out_max = std::numeric_limits<double>::infinity();
  double integral_limit = std::numeric_limits<double>::infinity();  ///< |ki * integral| bound
};

/// Positional PID u = kp e + ki ∫e + kd de/dt. Anti-windup: the integral stops growing while the
/// output is saturated in the direction of the error (conditional integration) and is clamped.
class Pid {
 public:
  Pid() = default;
  explicit Pid(const PidGains& g) : gains_(g) {}
  void SetGains(const PidGains& g) { gains_ = g; }
  const PidGains& gains() const { return gains_; }
  void Reset() {
    integral_ = 0.0;
    prev_error_ = 0.0;
    has_prev_ = false;
  }

  /// One step with error e over dt seconds. Returns the saturated output.
  double Step(double e, double dt) {
    const double de = has_prev_ && dt > 0.0 ? (e - prev_error_) / dt : 0.0;
    prev_error_ = e;
    has_prev_ = true;
    const double candidate_integral = integral_ + e * dt;
    const double unsat = gains_.kp * e + gains_.ki * candidate_integral + gains_.kd * de;
    const double out = std::clamp(unsat, gains_.out_min, gains_.out_max);
    const bool pushing_further = (unsat > gains_.out_max && e > 0) || (unsat < gains_.out_min && e < 0);
    if (!pushing_further) integral_ = candidate_integral;
    if (gains_.ki != 0.0 && std::isfinite(gains_.integral_limit)) {
      const double lim = gains_.integral_limit / std::abs(gains_.ki);
      integral_ = std::clamp(integral_, -lim, lim);
    }
    saturated_ = unsat != out;
    return out;
  }
  bool saturated() const { return saturated_; }
  double integral() const { return integral_; }

 private:
  PidGains gains_;
  double integral_ = 0.0;
  double prev_error_ = 0.0;
  bool has_prev_ = false;
  bool saturated_ = false;
};

/// Incremental (velocity-form) PID: Δu(k) = kp (e_k - e_{k-1}) + ki e_k + kd (e_k - 2e_{k-1} + e_{k-2});
/// u(k) = clamp(u(k-1) + Δu(k)). Gains are per sample (ki already includes the sample time).
/// Windup cannot happen because the stored output is the clamped one.
class IncrementalPid {
 public:
  IncrementalPid() = default;
  explicit IncrementalPid(const PidGains& g) : gains_(g) {}
  void SetGains(const PidGains& g) { gains_ = g; }
  const PidGains& gains() const { return gains_; }
  void Reset(double u0 = 0.0) {
    u_ = u0;
    e1_ = e2_ = 0.0;
  }
  double Step(double e) {
    const double du = gains_.kp * (e - e1_) + gains_.ki * e + gains_.kd * (e - 2.0 * e1_ + e2_);
    e2_ = e1_;
    e1_ = e;
    u_ = std::clamp(u_ + du, gains_.out_min, gains_.out_max);
    return u_;
  }
  double output() const { return u_; }
  /// Adds `delta` to the stored past errors. When the feedback signal jumps by -delta between
  /// two samples (e.g. an estimator update re-references it), the proportional and derivative
  /// increments then see no jump; the integral term still acts on the new error.
  void ShiftErrorHistory(double delta) {
    e1_ += delta;
    e2_ += delta;
  }

 private:
  PidGains gains_;
  double u_ = 0.0, e1_ = 0.0, e2_ = 0.0;
};

}  // namespace formsim::control
