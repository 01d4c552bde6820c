// Results of the Mecanum AGV experiment: summary.json's `results`, the printed and GUI tables.
#include <cmath>

#include "sim/agv/agv_experiment.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::sim::agv {

namespace {

void SetStats(Metrics& m, const std::string& p, const EstimateStats& s) {
  m.Set(p + ".position_rms_m", s.position.rms());
  m.Set(p + ".position_max_m", s.position.max_abs);
  m.Set(p + ".position_final_m", s.final_position_error);
  m.Set(p + ".heading_rms_rad", s.heading.rms());
  m.Set(p + ".heading_max_rad", s.heading.max_abs);
  m.Set(p + ".jumps", static_cast<double>(s.jumps));
}

}  // namespace

Metrics AgvExperiment::Results() const {
  Metrics m;
  // Flags are 1 (true) or 0 (false): the results tree holds numbers and texts.
  m.SetText("localisation_mode", ModeName(cfg_.mode));
  m.SetSetting("path_length_m", cfg_.path.length());
  m.SetFlag("tracking_finished", tracking_done_);
  m.Set("tracking_time_s", done_time_);
  m.SetFlag("loop_completed", completed());
  m.SetSetting("completion_tolerance_m", cfg_.completion_tolerance);
  m.Set("cross_track.rms_m", cross_track_.rms());
  m.Set("cross_track.max_m", cross_track_.max_abs);
  m.Set("cross_track.final_m", true_cross_);
  const ca::PathPoint end = cfg_.path.At(tracker_.goal_s());
  m.Set("final_distance_to_goal_m", (robot_->pose().p() - end.p).Norm());
  SetStats(m, "localisation.odometry", stats_odo_);
  SetStats(m, "localisation.beacon", stats_beacon_);
  SetStats(m, "localisation.fused", stats_fused_);
  const BeaconCounts& c = counts_;
  m.Set("beacon.samples", static_cast<double>(c.samples));
  m.Set("beacon.dropouts", static_cast<double>(c.dropouts));
  m.Set("beacon.outliers", static_cast<double>(c.outliers));
  m.Set("beacon.accepted", static_cast<double>(c.accepted));
  m.Set("beacon.rejected", static_cast<double>(c.rejected));
  m.Set("beacon.rejected_outliers", static_cast<double>(c.rejected_outliers));
  m.Set("beacon.accepted_outliers", static_cast<double>(c.accepted_outliers));
  m.Set("beacon.rejected_good", static_cast<double>(c.rejected - c.rejected_outliers));
  m.Set("beacon.reinitialisations", static_cast<double>(c.reinitialisations));
  m.Set("beacon.faults", static_cast<double>(c.faults));
  m.Set("beacon.nis_mean", c.accepted ? c.nis_sum / c.accepted : 0.0);
  // The loop as it ran (not the setting): iterations per simulated second, and the beacon
  // samples that arrived per second.
  const double T = time();
  m.Set("control.updates", static_cast<double>(control_updates_));
  m.Set("control.rate_hz", T > 0.0 ? static_cast<double>(control_updates_) / T : 0.0);
  m.SetSetting("control.rate_setting_hz", cfg_.control_rate);
  m.Set("beacon.rate_hz", T > 0.0 ? static_cast<double>(counts_.samples) / T : 0.0);
  m.SetFlag("filter.gate", cfg_.filter.gate);
  m.SetFlag("filter.adaptive_r", cfg_.filter.adaptive_r);
  m.Set("filter.r_xy_in_use_m", std::sqrt(filter_.measurement_cov()(0, 0)));
  m.Set("filter.r_theta_in_use_rad", std::sqrt(filter_.measurement_cov()(2, 2)));

  m.AddNote(Sprintf("Mecanum AGV, %s localisation, path %.2f m: %s",
                    ModeName(cfg_.mode).c_str(), cfg_.path.length(),
                    !tracking_done_ ? "did not finish (duration too short?)"
                    : completed()   ? "completed"
                                    : "finished in its own belief, but off the path"));
  m.AddNote(Sprintf("true cross-track error: RMS %.1f mm, max %.1f mm (tolerance %.0f mm)",
                    cross_track_.rms() * 1000, cross_track_.max_abs * 1000,
                    cfg_.completion_tolerance * 1000));
  // Wall-clock cost of one loop: printed, never in summary.json (which must be reproducible).
  m.AddNote(Sprintf(
      "control loop: %.2f Hz measured (%ld iterations in %.1f s); one iteration "
      "(estimators + tracker) %.1f us mean, %.1f us max of wall clock",
      T > 0.0 ? static_cast<double>(control_updates_) / T : 0.0, control_updates_, T,
      control_updates_ ? 1000.0 * loop_ms_sum_ / static_cast<double>(control_updates_) : 0.0,
      1000.0 * loop_ms_max_));

  Metrics::Table loc;
  loc.title = "Localisation against the truth";
  loc.row_header = "estimate";
  loc.rows = {{"odometry", "localisation.odometry"},
              {"beacon (raw)", "localisation.beacon"},
              {"fused (KF)", "localisation.fused"}};
  loc.columns = {{"RMS [m]", "position_rms_m", "%.4f"},
                 {"max [m]", "position_max_m", "%.4f"},
                 {"final [m]", "position_final_m", "%.4f"},
                 {"heading RMS [rad]", "heading_rms_rad", "%.4f"},
                 {"jumps", "jumps", "%.0f"}};
  m.AddTable(std::move(loc));

  Metrics::Table beacon;
  beacon.title =
      std::string("Beacon samples and the gate (") + (cfg_.filter.gate ? "on" : "off") + ")";
  beacon.rows = {{"beacon", "beacon"}};
  for (const char* k : {"samples", "dropouts", "outliers", "accepted", "rejected",
                        "rejected_outliers", "accepted_outliers", "reinitialisations", "faults"})
    beacon.columns.push_back({k, k, "%.0f"});
  m.AddTable(std::move(beacon));
  // Comparing runs (the GUI's pins, history, Monte Carlo): errors and faults are better low.
  for (const char* p : {"cross_track.*", "final_distance_to_goal_m", "tracking_time_s",
                        "localisation.*", "beacon.faults", "beacon.accepted_outliers",
                        "beacon.rejected_good", "beacon.reinitialisations"})
    m.SetBetter(p, Better::kLower);
  for (const char* p : {"tracking_finished", "loop_completed"}) m.SetBetter(p, Better::kHigher);
  // Labels (markup) and units: axes of sweep figures and tables.
  m.Describe("path_length_m", "path length", "m");
  m.Describe("completion_tolerance_m", "completion tolerance", "m");
  m.Describe("control.rate_setting_hz", "control rate setting", "Hz");
  m.Describe("tracking_time_s", "tracking time", "s");
  m.Describe("cross_track.rms_m", "cross-track RMS error", "m");
  m.Describe("cross_track.max_m", "cross-track max error", "m");
  m.Describe("cross_track.final_m", "final cross-track error", "m");
  m.Describe("final_distance_to_goal_m", "final distance to the goal", "m");
  m.Describe("localisation.*.position_rms_m", "{1} position RMS error", "m");
  m.Describe("localisation.*.position_max_m", "{1} position max error", "m");
  m.Describe("localisation.*.position_final_m", "{1} final position error", "m");
  m.Describe("localisation.*.heading_rms_rad", "{1} heading RMS error", "rad");
  m.Describe("localisation.*.heading_max_rad", "{1} heading max error", "rad");
  m.Describe("localisation.*.jumps", "{1} position jumps", "");
  m.Describe("beacon.*", "beacon {1}", "");
  m.Describe("beacon.rate_hz", "beacon rate", "Hz");
  m.Describe("control.rate_hz", "control rate", "Hz");
  using C = Metrics::Combine;
  m.AddHeadline({"cross-track RMS [m]", "cross_track.rms_m", C::kValue, "%.4f"});
  m.AddHeadline({"cross-track max [m]", "cross_track.max_m", C::kValue, "%.4f"});
  m.AddHeadline({"fused RMS [m]", "localisation.fused.position_rms_m", C::kValue, "%.4f"});
  m.AddHeadline({"to goal [m]", "final_distance_to_goal_m", C::kValue, "%.4f"});
  return m;
}

}  // namespace formsim::sim::agv
