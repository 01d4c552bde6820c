// Metrics of the velocity-control experiment (summary.json, the printed and GUI tables) and the
// estimator timing table.
#include <cmath>

#include "sim/core/number_format.hpp"
#include "sim/velocity/velocity_experiment.hpp"

namespace formsim::sim::velocity {

namespace {

// Speed-estimate RMSEs and the paper's control metrics of one robot on one floor (or overall),
// under `p` ("robots.R1." or "robots.R1.floors.wet.").
void SetFloor(Metrics& m, const std::string& p, const FloorStats& s, bool vi) {
  const double T = std::max(s.time, 1e-9);
  m.Set(p + "speed_rmse.odometry", s.odo.rms());
  m.Set(p + "speed_rmse.fused", s.fused.rms());
  if (vi) m.Set(p + "speed_rmse.vi_only", s.vi.rms());
  m.Set(p + "yaw_rate_rmse.odometry", s.w_odo.rms());
  m.Set(p + "yaw_rate_rmse.fused", s.w_fused.rms());
  if (vi) m.Set(p + "yaw_rate_rmse.vi_only", s.w_vi.rms());
  m.Set(p + "control.time", s.time);
  m.Set(p + "control.v_cmd_mean", s.v_cmd_int / T);
  m.Set(p + "control.v_true_mean", s.distance / T);
  // The paper's metrics: mean speed from the distance travelled (and mean yaw rate from the
  // angle turned) against the commanded ones.
  m.Set(p + "control.linear_error", std::abs(s.distance - s.v_cmd_int) / T);
  m.Set(p + "control.w_cmd_mean", s.w_cmd_int / T);
  m.Set(p + "control.w_true_mean", s.turn / T);
  m.Set(p + "control.angular_error", std::abs(s.turn - s.w_cmd_int) / T);
  m.Set(p + "control.speed_rms_error", s.v_ctrl.rms());
  m.Set(p + "control.yaw_rate_rms_error", s.w_ctrl.rms());
}

}  // namespace

Metrics VelocityExperiment::Results() const {
  Metrics m;
  const bool vi = cfg_.estimator.vi_baseline;
  m.SetSetting("settle_time", cfg_.settle_time);
  m.SetSetting("keyframe_period", keyframe_period());
  m.AddNote("velocity: metrics after t = " + Sprintf("%.1f", cfg_.settle_time) +
            " s (speed RMSE vs true forward speed)");
  Metrics::Table table;
  table.title = "Speed estimate RMSE and control error, overall and per floor (after settling)";
  table.row_header = "robot";
  table.columns = {{"feedback", "feedback", ""},
                   {"RMSE odo", "speed_rmse.odometry", "%.4f"},
                   {"RMSE fus", "speed_rmse.fused", "%.4f"},
                   {"RMSE VI", "speed_rmse.vi_only", "%.4f"},
                   {"v mean", "control.v_true_mean", "%.4f"},
                   {"Δv_c", "control.linear_error", "%.4f"},
                   {"Δω_c", "control.angular_error", "%.4f"},
                   {"time [s]", "control.time", "%.1f"},
                   {"faults", "estimator_faults", "%.0f"},
                   {"updates", "estimator_updates", "%.0f"}};
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    const std::string& name = u.spec.name;
    const std::string p = "robots." + name + ".";
    SetFloor(m, p, u.total, vi);
    m.SetText(p + "feedback", FeedbackNames()[u.spec.feedback]);
    table.rows.emplace_back(name, "robots." + name);
    for (const auto& [floor, s] : u.floors) {
      SetFloor(m, p + "floors." + floor + ".", s, vi);
      table.rows.emplace_back(name + " on " + floor, p + "floors." + floor);
    }
    const cv::KeyframeState& k = u.fused.latest();
    m.Set(p + "final_biases.odometry_speed", k.bv());
    m.Set(p + "final_biases.odometry_yaw_rate", k.bw());
    m.Set(p + "final_biases.gyro", k.bg());
    m.Set(p + "final_biases.gyro_true", u.imu.gyro_bias());
    m.Set(p + "estimator_updates", static_cast<double>(u.updates));
    m.Set(p + "estimator_faults", static_cast<double>(u.faults));
    m.Set(p + "events.slip", static_cast<double>(events_.CountForRobot("slip", name)));
    m.Set(p + "events.filter_fault",
          static_cast<double>(events_.CountForRobot(event::kFilterFault, name)));
  }
  m.AddTable(std::move(table));
  // Wall-clock cost of the fused estimator: printed, never in summary.json (which must be
  // reproducible).
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    m.AddNote(Sprintf(
        "%s fused estimator: %.2f ms mean, %.2f ms max per update, one update every %.0f ms",
        u.spec.name.c_str(), u.updates ? u.update_ms_sum / u.updates : 0.0, u.update_ms_max,
        1000.0 * keyframe_period()));
  }
  // Comparing runs (the GUI's pins, history, Monte Carlo): errors and faults are better low.
  for (const char* p : {"robots.*.speed_rmse.*", "robots.*.yaw_rate_rmse.*",
                        "robots.*.linear_error", "robots.*.angular_error", "robots.*_rms_error",
                        "robots.*.estimator_faults", "robots.*.events.*"})
    m.SetBetter(p, Better::kLower);
  // Labels (markup) and units: axes of sweep figures and tables.
  m.Describe("settle_time", "settling time", "s");
  m.Describe("keyframe_period", "keyframe period", "s");
  m.Describe("robots.*.speed_rmse.*", "RMS error of the {2} speed, {1}", "m/s");
  m.Describe("robots.*.yaw_rate_rmse.*", "RMS error of the {2} yaw rate, {1}", "rad/s");
  m.Describe("robots.*.control.linear_error", "\\Delta v_{c}, {1}", "m/s");
  m.Describe("robots.*.control.angular_error", "\\Delta \\omega_{c}, {1}", "rad/s");
  m.Describe("robots.*.control.speed_rms_error", "RMS speed control error, {1}", "m/s");
  m.Describe("robots.*.control.yaw_rate_rms_error", "RMS yaw-rate control error, {1}", "rad/s");
  m.Describe("robots.*.estimator_faults", "estimator faults, {1}", "");
  using C = Metrics::Combine;
  m.AddHeadline({"worst fused speed RMSE", "robots.*.speed_rmse.fused", C::kMax, "%.4f"});
  m.AddHeadline({"worst Δv_c", "robots.*.control.linear_error", C::kMax, "%.4f"});
  m.AddHeadline({"worst Δω_c", "robots.*.control.angular_error", C::kMax, "%.4f"});
  m.AddHeadline({"estimator faults", "robots.*.estimator_faults", C::kSum, "%.0f"});
  return m;
}

std::vector<TableSpec> VelocityExperiment::Tables() const {
  TableSpec timing;
  timing.title = "Estimator run time per update (wall clock)";
  timing.header = {"robot", "updates", "mean ms", "max ms", "period ms", "faults"};
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    timing.rows.push_back({u.spec.name, std::to_string(u.updates),
                           Sprintf("%.2f", u.updates ? u.update_ms_sum / u.updates : 0.0),
                           Sprintf("%.2f", u.update_ms_max), Sprintf("%.0f", 1000.0 * keyframe_period()),
                           std::to_string(u.faults)});
  }
  return {timing};
}

}  // namespace formsim::sim::velocity
