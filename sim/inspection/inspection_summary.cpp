// Metrics of the inspection run: summary.json and the table printed by `formsim run`.
#include <cstdio>
#include <string>

#include "control/inspection/trilateration.hpp"
#include "sim/inspection/inspection_experiment.hpp"

namespace formsim::sim {

namespace {

Json Stats(const ErrorStats& s) {
  Json j = Json::Object();
  j["rms"] = s.rms();
  j["max"] = s.max_abs;
  j["samples"] = s.n;
  return j;
}

}  // namespace

Json InspectionExperiment::Summary() const {
  Json j = Json::Object();
  Json route = Json::Object();
  route["length_m"] = route_.length();
  route["progress_m"] = progress_;
  route["completed"] = completed_;
  route["completion_time_s"] = completed_ ? Json(completion_time_) : Json();
  j["route"] = route;

  Json loc = Json::Object();
  loc["scans"] = scans_;
  loc["fixes"] = fixes_;
  loc["fix_rate"] = scans_ > 0 ? static_cast<double>(fixes_) / static_cast<double>(scans_) : 0.0;
  Json status = Json::Object();
  for (int s = 0; s < 5; ++s)
    status[control::inspection::ToString(static_cast<control::inspection::FixStatus>(s))] =
        status_counts_[s];
  loc["fix_status"] = status;
  Json err = Json::Object();
  err["raw"] = Stats(err_raw_);
  err["classical"] = Stats(err_classic_);
  err["kalman"] = Stats(err_kf_);
  err["dead_reckoning"] = Stats(err_dr_);
  loc["position_error_m"] = err;
  loc["kalman_error_x_m"] = Stats(err_kf_x_);
  loc["kalman_error_y_m"] = Stats(err_kf_y_);
  loc["heading_error_deg"] = Stats(err_heading_);
  loc["kalman_fixes_gated"] = kf_gated_;
  loc["kalman_reinitialised"] = kf_reinit_;
  loc["filter_faults"] = kf_faults_;
  loc["limit_filter_rejections"] = classic_.rejected();
  loc["heading_rejections"] = heading_.rejected();
  j["localisation"] = loc;

  Json tr = Json::Object();
  tr["controller_source"] = NavSourceNames()[cfg_.source];
  tr["lateral_offset_m"] = Stats(lateral_);
  tr["transient_m"] = cfg_.transient_m;
  tr["lateral_offset_after_transient_m"] = Stats(lateral_tracking_);
  tr["heading_error_after_transient_deg"] = Stats(dphi_tracking_);
  tr["lateral_bound_m"] = cfg_.lateral_bound;
  tr["within_bound"] = lateral_tracking_.n > 0 && lateral_tracking_.max_abs <= cfg_.lateral_bound;
  j["tracking"] = tr;

  Json ctl = Json::Object();
  const double t = time();
  ctl["rate_hz"] = t > 0 ? static_cast<double>(control_updates_) / t : 0.0;
  ctl["updates"] = control_updates_;
  ctl["laser_rate_hz"] = t > 0 ? static_cast<double>(scans_) / t : 0.0;
  ctl["no_rule_fired"] = no_rule_;
  ctl["feedforward"] = cfg_.feedforward;
  ctl["slip_fraction"] =
      sense_steps_ > 0 ? static_cast<double>(slip_steps_) / static_cast<double>(sense_steps_) : 0.0;
  ctl["rule_base"] = fuzzy_.origin();
  j["control"] = ctl;
  return j;
}

std::string InspectionExperiment::SummaryTable() const {
  std::string out;
  char line[200];
  auto row = [&](const char* name, const ErrorStats& s, const char* unit) {
    std::snprintf(line, sizeof line, "  %-28s RMS %7.3f  max %7.3f %s  (n=%ld)\n", name, s.rms(),
                  s.max_abs, unit, s.n);
    out += line;
  };
  std::snprintf(line, sizeof line, "inspection robot, controller uses the %s estimate\n",
                NavSourceNames()[cfg_.source].c_str());
  out += line;
  std::snprintf(line, sizeof line, "  route %.1f m: %s", route_.length(),
                completed_ ? "completed" : "NOT completed");
  out += line;
  if (completed_) {
    std::snprintf(line, sizeof line, " at t = %.1f s", completion_time_);
    out += line;
  }
  out += "\n";
  std::snprintf(line, sizeof line, "  laser fixes %ld of %ld scans (%.0f%%)\n", fixes_, scans_,
                scans_ > 0 ? 100.0 * fixes_ / scans_ : 0.0);
  out += line;
  out += "localisation error (position, m):\n";
  row("raw trilateration", err_raw_, "m");
  row("limit + mean filter", err_classic_, "m");
  row("per-axis Kalman", err_kf_, "m");
  row("dead reckoning only", err_dr_, "m");
  row("heading (limit + mean)", err_heading_, "deg");
  out += "tracking (true robot vs route):\n";
  row("lateral offset, whole run", lateral_, "m");
  row("lateral offset, after start", lateral_tracking_, "m");
  row("heading error, after start", dphi_tracking_, "deg");
  std::snprintf(line, sizeof line, "  control %.2f Hz (%ld updates), laser %.1f Hz\n",
                time() > 0 ? control_updates_ / time() : 0.0, control_updates_,
                time() > 0 ? scans_ / time() : 0.0);
  out += line;
  return out;
}

}  // namespace formsim::sim
