// Metrics of the inspection run: summary.json's `results`, the table printed by `formsim run`
// and the GUI's summary tables, all from one tree.
#include <cmath>
#include <string>

#include "control/inspection/trilateration.hpp"
#include "sim/inspection/inspection_experiment.hpp"

namespace formsim::sim::inspection {

namespace ins = control::inspection;

namespace {

void SetStats(Metrics& m, const std::string& path, const ErrorStats& s) {
  m.Set(path + ".rms", s.rms());
  m.Set(path + ".max", s.max_abs);
  m.Set(path + ".samples", static_cast<double>(s.n));
}

// The summary tables: the errors of each estimate, the tracking errors, and the counts of
// scans, fixes and rejections.
void AddInspectionTables(Metrics& m) {
  // RMS, max and sample count of ErrorStats blocks, one row each.
  auto stats_table = [&m](const std::string& title, const std::string& row_header,
                          std::vector<std::pair<std::string, std::string>> rows) {
    Metrics::Table t;
    t.title = title;
    t.row_header = row_header;
    t.rows = std::move(rows);
    t.columns = {{"RMS", "rms", "%.3f"}, {"max", "max", "%.3f"}, {"n", "samples", "%.0f"}};
    m.AddTable(std::move(t));
  };
  stats_table("localisation error:", "estimate",
              {{"raw trilateration [m]", "localisation.position_error_m.raw"},
               {"limit + mean filter [m]", "localisation.position_error_m.classical"},
               {"per-axis Kalman [m]", "localisation.position_error_m.kalman"},
               {"dead reckoning only [m]", "localisation.position_error_m.dead_reckoning"},
               {"heading (limit + mean) [deg]", "localisation.heading_error_deg"}});
  stats_table("tracking (true robot vs route):", "error",
              {{"lateral offset, whole run [m]", "tracking.lateral_offset_m"},
               {"lateral offset, after start [m]", "tracking.lateral_offset_after_transient_m"},
               {"lateral offset, on the turn [m]", "tracking.lateral_offset_turn_m"},
               {"heading error, after start [deg]", "tracking.heading_error_after_transient_deg"}});

  Metrics::Table counts;
  counts.title = "localisation (scans, fixes and why a scan gave no fix):";
  counts.row_header = "";
  counts.rows = {{"count", "localisation"}};
  counts.columns = {{"scans", "scans", "%.0f"}, {"fixes", "fixes", "%.0f"}};
  for (int s = 1; s < 5; ++s) {
    const std::string status = ins::ToString(static_cast<ins::FixStatus>(s));
    counts.columns.push_back({status, "fix_status." + status, "%.0f"});
  }
  counts.columns.push_back({"KF gated", "kalman_fixes_gated", "%.0f"});
  counts.columns.push_back({"limit rejected", "limit_filter_rejections", "%.0f"});
  counts.columns.push_back({"heading rejected", "heading_rejections", "%.0f"});
  m.AddTable(std::move(counts));
}

// How runs compare (better low or high), the labels and units of the metrics, and the headline
// numbers.
void DeclareInspectionMetricMeaning(Metrics& m) {
  // Comparing runs (the GUI's pins, history, Monte Carlo): errors and faults are better low.
  for (const char* p : {"localisation.*.rms", "localisation.*.max", "tracking.*.rms",
                        "tracking.*.max", "localisation.filter_faults", "route.completion_time_s",
                        "control.no_rule_fired", "control.slip_fraction"})
    m.SetBetter(p, Better::kLower);
  for (const char* p :
       {"route.progress_m", "route.completed", "localisation.fix_rate", "tracking.within_bound"})
    m.SetBetter(p, Better::kHigher);
  // Labels (markup) and units: axes of sweep figures and tables.
  m.Describe("route.length_m", "route length", "m");
  m.Describe("route.progress_m", "route progress", "m");
  m.Describe("route.completion_time_s", "route completion time", "s");
  m.Describe("tracking.transient_m", "start transient left out", "m");
  m.Describe("tracking.lateral_bound_m", "lateral bound", "m");
  m.Describe("tracking.lateral_offset_m.*", "lateral offset {1}", "m");
  m.Describe("tracking.lateral_offset_after_transient_m.*",
             "lateral offset {1} after the transient", "m");
  m.Describe("tracking.lateral_offset_turn_m.*", "lateral offset {1} in turns", "m");
  m.Describe("tracking.heading_error_after_transient_deg.*",
             "heading error {1} after the transient", "deg");
  m.Describe("tracking.*.samples", "samples of {1}", "");
  m.Describe("localisation.position_error_m.*.*", "{1} position error {2}", "m");
  m.Describe("localisation.position_error_m.*.samples", "{1} position error samples", "");
  m.Describe("control.rate_hz", "control rate", "Hz");
  m.Describe("control.laser_rate_hz", "laser rate", "Hz");
  using C = Metrics::Combine;
  m.AddHeadline(
      {"lateral RMS [m]", "tracking.lateral_offset_after_transient_m.rms", C::kValue, "%.3f"});
  m.AddHeadline(
      {"lateral max [m]", "tracking.lateral_offset_after_transient_m.max", C::kValue, "%.3f"});
  m.AddHeadline(
      {"KF position RMS [m]", "localisation.position_error_m.kalman.rms", C::kValue, "%.3f"});
  m.AddHeadline({"progress [m]", "route.progress_m", C::kValue, "%.1f"});
}

}  // namespace

Metrics InspectionExperiment::Results() const {
  Metrics m;
  m.SetSetting("route.length_m", route_.length());
  m.Set("route.progress_m", progress_);
  m.SetFlag("route.completed", completed_);
  // null in summary.json while the route is not completed
  m.Set("route.completion_time_s", completed_ ? completion_time_ : std::nan(""));

  const std::string loc = "localisation.";
  m.Set(loc + "scans", static_cast<double>(scans_));
  m.Set(loc + "fixes", static_cast<double>(fixes_));
  m.Set(loc + "fix_rate",
        scans_ > 0 ? static_cast<double>(fixes_) / static_cast<double>(scans_) : 0.0);
  for (int s = 0; s < 5; ++s)
    m.Set(loc + "fix_status." + ins::ToString(static_cast<ins::FixStatus>(s)),
          static_cast<double>(status_counts_[s]));
  SetStats(m, loc + "position_error_m.raw", err_raw_);
  SetStats(m, loc + "position_error_m.classical", err_classic_);
  SetStats(m, loc + "position_error_m.kalman", err_kf_);
  SetStats(m, loc + "position_error_m.dead_reckoning", err_dr_);
  SetStats(m, loc + "kalman_error_x_m", err_kf_x_);
  SetStats(m, loc + "kalman_error_y_m", err_kf_y_);
  SetStats(m, loc + "heading_error_deg", err_heading_);
  m.Set(loc + "kalman_fixes_gated", static_cast<double>(kf_gated_));
  m.Set(loc + "kalman_reinitialised", static_cast<double>(kf_reinit_));
  m.Set(loc + "filter_faults", static_cast<double>(kf_faults_));
  m.Set(loc + "limit_filter_rejections", static_cast<double>(classic_.rejected()));
  m.Set(loc + "heading_rejections", static_cast<double>(heading_.rejected()));

  const std::string& source = NavSourceNames()[cfg_.source];
  m.SetText("tracking.controller_source", source);
  SetStats(m, "tracking.lateral_offset_m", lateral_);
  m.SetSetting("tracking.transient_m", cfg_.transient_m);
  SetStats(m, "tracking.lateral_offset_after_transient_m", lateral_tracking_);
  SetStats(m, "tracking.lateral_offset_turn_m", lateral_turn_);
  SetStats(m, "tracking.heading_error_after_transient_deg", dphi_tracking_);
  m.SetSetting("tracking.lateral_bound_m", cfg_.lateral_bound);
  const bool within = lateral_tracking_.n > 0 && lateral_tracking_.max_abs <= cfg_.lateral_bound;
  m.SetFlag("tracking.within_bound", within);

  const double t = time();
  const double rate = t > 0 ? static_cast<double>(control_updates_) / t : 0.0;
  const double laser_rate = t > 0 ? static_cast<double>(scans_) / t : 0.0;
  m.Set("control.rate_hz", rate);
  m.Set("control.updates", static_cast<double>(control_updates_));
  m.Set("control.laser_rate_hz", laser_rate);
  m.Set("control.no_rule_fired", static_cast<double>(no_rule_steps_));
  m.SetFlag("control.feedforward", cfg_.feedforward);
  m.Set("control.slip_fraction",
        sense_steps_ > 0 ? static_cast<double>(slip_steps_) / static_cast<double>(sense_steps_)
                         : 0.0);
  m.SetText("control.rule_base", fuzzy_.origin());

  m.AddNote("inspection robot, controller uses the " + source + " estimate");
  m.AddNote("  route " + Sprintf("%.1f", route_.length()) + " m: " +
            (completed_ ? "completed at t = " + Sprintf("%.1f", completion_time_) + " s"
                        : "NOT completed"));
  m.AddNote("  laser fixes " + std::to_string(fixes_) + " of " + std::to_string(scans_) +
            " scans (" + Sprintf("%.0f", scans_ > 0 ? 100.0 * fixes_ / scans_ : 0.0) + "%)");
  m.AddNote("  control " + Sprintf("%.2f", rate) + " Hz (" + std::to_string(control_updates_) +
            " updates), laser " + Sprintf("%.1f", laser_rate) + " Hz");

  AddInspectionTables(m);
  DeclareInspectionMetricMeaning(m);
  return m;
}

}  // namespace formsim::sim::inspection
