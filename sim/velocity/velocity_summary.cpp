// Metrics of the velocity-control experiment: summary.json and the printed table.
#include <cmath>
#include <cstdio>

#include "sim/velocity/velocity_experiment.hpp"

namespace formsim::sim::vio {

namespace {

Json FloorJson(const FloorStats& s, bool vi) {
  Json j = Json::Object();
  const double T = std::max(s.time, 1e-9);
  Json rmse = Json::Object();
  rmse["odometry"] = s.odo.rms();
  rmse["fused"] = s.fused.rms();
  if (vi) rmse["vi_only"] = s.vi.rms();
  j["speed_rmse"] = rmse;
  Json wr = Json::Object();
  wr["odometry"] = s.w_odo.rms();
  wr["fused"] = s.w_fused.rms();
  if (vi) wr["vi_only"] = s.w_vi.rms();
  j["yaw_rate_rmse"] = wr;
  Json c = Json::Object();
  c["time"] = s.time;
  c["v_cmd_mean"] = s.v_cmd_int / T;
  c["v_true_mean"] = s.distance / T;
  // The paper's metrics: mean speed from the distance travelled (and mean yaw rate from the
  // angle turned) against the commanded ones.
  c["linear_error"] = std::abs(s.distance - s.v_cmd_int) / T;
  c["w_cmd_mean"] = s.w_cmd_int / T;
  c["w_true_mean"] = s.turn / T;
  c["angular_error"] = std::abs(s.turn - s.w_cmd_int) / T;
  c["speed_rms_error"] = s.v_ctrl.rms();
  c["yaw_rate_rms_error"] = s.w_ctrl.rms();
  j["control"] = c;
  return j;
}

}  // namespace

Json VelocityExperiment::Summary() const {
  Json j = Json::Object();
  j["settle_time"] = cfg_.settle_time;
  j["keyframe_period"] = keyframe_period();
  Json robots = Json::Object();
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    Json r = FloorJson(u.total, cfg_.estimator.vi_baseline);
    r["feedback"] = FeedbackNames()[u.spec.feedback];
    Json floors = Json::Object();
    for (const auto& [name, s] : u.floors) floors[name] = FloorJson(s, cfg_.estimator.vi_baseline);
    r["floors"] = floors;
    const control::vio::KeyframeState& k = u.fused.latest();
    Json b = Json::Object();
    b["odometry_speed"] = k.bv();
    b["odometry_yaw_rate"] = k.bw();
    b["gyro"] = k.bg();
    b["gyro_true"] = u.imu.gyro_bias();
    r["final_biases"] = b;
    r["estimator_updates"] = static_cast<long>(u.updates);
    r["estimator_faults"] = static_cast<long>(u.faults);
    robots[u.spec.name] = r;
  }
  j["robots"] = robots;
  return j;
}

std::string VelocityExperiment::SummaryTable() const {
  std::string out;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "velocity_control: metrics after t = %.1f s (speed RMSE vs true forward speed)\n"
                "%-10s %-9s %9s %9s %9s %9s %9s %10s %10s\n",
                cfg_.settle_time, "robot", "feedback", "RMSE odo", "RMSE fus", "RMSE VI", "v mean",
                "Δv_c", "Δω_c", "fault/upd");
  out += buf;
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    const FloorStats& s = u.total;
    const double T = std::max(s.time, 1e-9);
    std::snprintf(buf, sizeof buf, "%-10s %-9s %9.4f %9.4f %9.4f %9.4f %9.4f %10.4f %4ld/%-5ld\n",
                  u.spec.name.c_str(), FeedbackNames()[u.spec.feedback].c_str(), s.odo.rms(),
                  s.fused.rms(), cfg_.estimator.vi_baseline ? s.vi.rms() : NAN, s.distance / T,
                  std::abs(s.distance - s.v_cmd_int) / T, std::abs(s.turn - s.w_cmd_int) / T,
                  u.faults, u.updates);
    out += buf;
    for (const auto& [name, f] : u.floors) {
      const double Tf = std::max(f.time, 1e-9);
      std::snprintf(buf, sizeof buf, "  on %-14s %9.4f %9.4f %9.4f %9.4f %9.4f %10.4f  (%.1f s)\n",
                    name.c_str(), f.odo.rms(), f.fused.rms(),
                    cfg_.estimator.vi_baseline ? f.vi.rms() : NAN, f.distance / Tf,
                    std::abs(f.distance - f.v_cmd_int) / Tf, std::abs(f.turn - f.w_cmd_int) / Tf,
                    f.time);
      out += buf;
    }
  }
  // Wall-clock cost of the fused estimator (not in summary.json, which must be reproducible).
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    std::snprintf(buf, sizeof buf,
                  "%s fused estimator: %.2f ms mean, %.2f ms max per update, one update every "
                  "%.0f ms\n",
                  u.spec.name.c_str(), u.updates ? u.update_ms_sum / u.updates : 0.0,
                  u.update_ms_max, 1000.0 * keyframe_period());
    out += buf;
  }
  return out;
}

}  // namespace formsim::sim::vio
