// The papers' cases, tables and figures for `formsim reproduce`. Each table's first rows are the
// paper's method as the paper describes it; additions of ours are separate rows labelled "(ours)".
#include "app/reproduce_cases.hpp"

#include <stdexcept>

namespace formsim::app {
namespace {

using sim::CellStat;
using sim::ReproCase;
using sim::ReproColumn;
using sim::ReproFigure;
using sim::ReproPaper;
using sim::ReproRow;
using sim::ReproTable;

// Column builders: a header, a metric ("{}": the row's key), how to show it.
ReproColumn Stat(const std::string& header, const std::string& metric, CellStat stat,
                 double scale = 1.0, int digits = 1) {
  ReproColumn c;
  c.header = header;
  c.metric = metric;
  c.stat = stat;
  c.scale = scale;
  c.digits = digits;
  return c;
}
ReproColumn Sci(const std::string& header, const std::string& metric) {
  ReproColumn c = Stat(header, metric, CellStat::kMeanStd, 1.0, 2);
  c.sci = true;
  return c;
}
ReproColumn Count(const std::string& header, const std::string& metric) {
  return Stat(header, metric, CellStat::kCount);
}
ReproColumn Below(const std::string& header, const std::string& metric, const std::string& versus) {
  ReproColumn c = Stat(header, metric, CellStat::kBelow);
  c.versus = versus;
  return c;
}
ReproColumn InCase(ReproColumn c, const std::string& case_id) {
  c.case_id = case_id;
  return c;
}
ReproRow Row(std::vector<std::string> labels, const std::string& case_id,
             const std::string& key = "", std::vector<std::string> texts = {}) {
  return ReproRow{std::move(labels), case_id, key, std::move(texts)};
}
ReproRow TextRow(std::vector<std::string> labels, std::vector<std::string> texts) {
  return ReproRow{std::move(labels), "", "", std::move(texts)};
}

std::string Str(double v) {
  std::string s = std::to_string(v);
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s;
}

// ---- Paper 000: cascade formation ----
ReproPaper Formation() {
  ReproPaper p;
  p.name = "formation";
  p.title = "Cascade formation (paper 000, Han, Sun, Zhi 2015)";
  // The paper's angle noise h = 0.9186e-4 rad² on φ and α; 3 mm σ on l in raw mode (ours).
  const std::vector<std::string> noise = {"noise.l_sigma=0.003", "noise.phi_variance=0.9186e-4",
                                          "noise.alpha_variance=0.9186e-4"};
  ReproTable t;
  t.id = "errors";
  t.title = "Formation errors after a 1 s settle time (max over the run; e_l and α: worst link)";
  t.label_headers = {"traj", "gains", "estimator"};
  auto over_links = [](const std::string& what) {
    std::string s;
    for (const char* l : {"R1-R2", "R1-R3", "R2-R3"})
      s += (s.empty() ? "" : ",") + std::string("links.") + l + ".max_abs_error_after_settle." +
           what;
    return s;
  };
  t.columns = {Sci("max\\|e_φ12\\| [rad]", "links.R1-R2.max_abs_error_after_settle.phi"),
               Sci("max\\|e_l\\| [m]", over_links("l")),
               Sci("max\\|α\\| [rad]", over_links("alpha")),
               Sci("φ12 estimate RMS [rad]", "links.R1-R2.estimation_rmse.phi")};
  const char* paper[3][4] = {{"0.0064", "~1e-4", "0.0137", ""},
                             {"0.021", "~1e-4", "0.0472", ""},
                             {"\"almost zero\"", "~1e-3", "converges by 3 s", ""}};
  for (int traj = 1; traj <= 3; ++traj) {
    const std::string tr = std::to_string(traj);
    t.rows.push_back(TextRow({"paper " + tr, "", "UKF"},
                             {paper[traj - 1][0], paper[traj - 1][1], paper[traj - 1][2], ""}));
    for (const std::string gains : {"printed", "per_sample"}) {
      for (const std::string est : {"truth", "raw", "ukf"}) {
        ReproCase c;
        c.id = "traj" + tr + "_" + gains + "_" + est;
        c.scenario = "formation_traj" + tr + (gains == "printed" ? "" : "_per_sample");
        if (est != "truth") {
          c.sets = noise;
          c.sets.push_back("robots.R2.follow.estimator=" + est);
          c.sets.push_back("robots.R3.follow.estimator=" + est);
        }
        p.cases.push_back(c);
        t.rows.push_back(Row(
            {tr, gains == "printed" ? "printed" : "per-sample", est == "ukf" ? "UKF" : est}, c.id));
      }
    }
  }
  t.note =
      "Gains as printed (k = 0.15, 0.08 used as continuous gains) and per sample (k/Tc). Truth: "
      "exact link states, no noise (every seed gives the same run). Raw and UKF: the paper's "
      "angle noise; the UKF measures [φ, α] as in the paper.";
  p.tables.push_back(t);
  return p;
}

// ---- Paper 002: Mecanum AGV ----
ReproPaper Agv() {
  ReproPaper p;
  p.name = "agv";
  p.title = "Omnidirectional Mecanum AGV (paper 002)";
  auto add = [&](const std::string& id, const std::string& scenario,
                 std::vector<std::string> sets) {
    p.cases.push_back({id, scenario, sets});
  };
  const std::string plain = "estimation.gate=false";
  add("odometry", "agv_odometry_only", {});
  add("beacon", "agv_beacon_only", {});
  add("plain_kf", "agv_fused", {plain});
  add("gate", "agv_fused", {});
  add("gate_adaptive", "agv_fused", {"estimation.adaptive_r=true"});
  for (const char* rate : {"0", "0.01"}) {
    add(std::string("plain_kf_outliers_") + rate, "agv_fused",
        {plain, std::string("beacon.outlier_probability=") + rate});
    add(std::string("gate_outliers_") + rate, "agv_fused",
        {std::string("beacon.outlier_probability=") + rate});
  }
  for (double sigma : {0.02, 0.03, 0.05}) {
    const std::string s = Str(sigma), mm = Str(sigma * 1000);
    add("sigma_" + mm + "_r_sigma", "agv_fused", {"beacon.sigma_xy=" + s, "estimation.r_xy=" + s});
    add("sigma_" + mm + "_r_10", "agv_fused", {"beacon.sigma_xy=" + s});
  }
  add("r_small", "agv_fused", {"beacon.sigma_xy=0.03", "estimation.r_xy=0.003"});
  add("r_small_adaptive", "agv_fused",
      {"beacon.sigma_xy=0.03", "estimation.r_xy=0.003", "estimation.adaptive_r=true"});
  add("slippery_plain_kf", "agv_slippery_corner", {plain});
  add("slippery_gate", "agv_slippery_corner", {});

  const ReproColumn rms = Stat("cross-track RMS [mm]", "cross_track.rms_m", CellStat::kMeanStdRange,
                               1000.0),
                    max = Stat("cross-track max [mm]", "cross_track.max_m", CellStat::kMeanStdRange,
                               1000.0),
                    loops = Count("loop completed", "loop_completed"),
                    jumps =
                        Stat("estimate jumps > 5 cm", "localisation.{}.jumps", CellStat::kMeanStd);
  ReproTable loc;
  loc.id = "localisation";
  loc.title = "AGV, true cross-track error by localisation (cf. Fig. 6): 5% beacon outliers";
  loc.label_headers = {"localisation", "paper"};
  loc.columns = {rms, max, loops, jumps,
                 Stat("loop rate [Hz]", "control.rate_hz", CellStat::kMeanStd, 1.0, 2)};
  loc.rows = {
      Row({"odometry only", "fails"}, "odometry", "odometry"),
      Row({"beacon only (Fig. 6(a))", "jumpy"}, "beacon", "beacon"),
      Row({"fused, the paper's plain KF (Fig. 6(b))", "within ~10 mm"}, "plain_kf", "fused"),
      Row({"fused, KF + χ² gate (ours; shipped `agv_fused`)", ""}, "gate", "fused"),
      Row({"fused, KF + χ² gate + adaptive R (ours)", ""}, "gate_adaptive", "fused")};
  loc.note =
      "Beacon σ 10 mm / 0.01 rad every 0.1 s, 5% outliers of 0.2-0.6 m, 5% dropouts; "
      "estimation.r_xy = 10 mm. Jumps: steps of the estimate the controller uses (odometry, "
      "beacon or fused) larger than 5 cm. Loop rate: control iterations per simulated second.";
  p.tables.push_back(loc);

  ReproTable out;
  out.id = "outliers";
  out.title = "AGV, fused localisation against the beacon's outlier rate";
  out.label_headers = {"filter", "outliers"};
  out.columns = {rms, max, loops, jumps};
  out.rows = {Row({"the paper's plain KF", "0%"}, "plain_kf_outliers_0", "fused"),
              Row({"the paper's plain KF", "1%"}, "plain_kf_outliers_0.01", "fused"),
              Row({"the paper's plain KF", "5%"}, "plain_kf", "fused"),
              Row({"KF + χ² gate (ours)", "0%"}, "gate_outliers_0", "fused"),
              Row({"KF + χ² gate (ours)", "1%"}, "gate_outliers_0.01", "fused"),
              Row({"KF + χ² gate (ours)", "5%"}, "gate", "fused")};
  p.tables.push_back(out);

  ReproTable sens;
  sens.id = "sensitivity";
  sens.title =
      "AGV, beacon noise against the R the filter assumes (estimation.r_xy), KF + χ² gate (ours)";
  sens.label_headers = {"beacon σ", "estimation.r_xy"};
  sens.columns = {rms, max, loops};
  sens.rows = {Row({"10 mm", "10 mm (= σ)"}, "gate")};
  for (double sigma : {0.02, 0.03, 0.05}) {
    const std::string mm = Str(sigma * 1000);
    sens.rows.push_back(Row({mm + " mm", mm + " mm (= σ)"}, "sigma_" + mm + "_r_sigma"));
  }
  for (double sigma : {0.02, 0.03, 0.05}) {
    const std::string mm = Str(sigma * 1000);
    sens.rows.push_back(Row({mm + " mm", "10 mm (too small)"}, "sigma_" + mm + "_r_10"));
  }
  sens.note =
      "5% outliers. The fused figures at σ 20-50 mm hold only with estimation.r_xy set to the "
      "beacon's σ; left at 10 mm (rows \"too small\") the filter trusts the beacon too much. The "
      "gate's threshold follows R.";
  p.tables.push_back(sens);

  ReproTable adapt;
  adapt.id = "adaptive";
  adapt.title = "AGV, R ten times too small (beacon σ 30 mm, estimation.r_xy 3 mm), KF + χ² gate";
  adapt.label_headers = {"R"};
  adapt.columns = {
      rms, max, loops,
      Stat("R in use at the end [mm]", "filter.r_xy_in_use_m", CellStat::kMeanStdRange, 1000.0)};
  adapt.rows = {Row({"fixed (3 mm)"}, "r_small"), Row({"adaptive R (ours)"}, "r_small_adaptive")};
  p.tables.push_back(adapt);

  ReproTable slip;
  slip.id = "slippery";
  slip.title = "AGV, a wet patch (μ 0.05) on the first corner (`agv_slippery_corner`)";
  slip.label_headers = {"filter"};
  slip.columns = {rms, max, loops,
                  Stat("odometry estimate max error [mm]", "localisation.odometry.position_max_m",
                       CellStat::kMeanStdRange, 1000.0)};
  slip.rows = {Row({"the paper's plain KF"}, "slippery_plain_kf"),
               Row({"KF + χ² gate (ours)"}, "slippery_gate")};
  p.tables.push_back(slip);
  return p;
}

// ---- Paper 003: substation inspection robot ----
ReproPaper Inspection() {
  ReproPaper p;
  p.name = "inspection";
  p.title = "Substation inspection robot (paper 003)";
  p.cases = {{"paper", "inspection_u_route", {}},
             {"no_kalman", "inspection_no_kalman", {}},
             {"feedforward", "inspection_u_route_feedforward", {}}};
  auto cm = [](const std::string& h, const std::string& m) {
    return Stat(h, m, CellStat::kMeanStdRange, 100.0);
  };
  ReproTable tr;
  tr.id = "tracking";
  tr.title =
      "Inspection robot, lateral offset of the true robot from the route after the first 6 m";
  tr.label_headers = {"controller"};
  tr.columns = {cm("lateral RMS [cm]", "tracking.lateral_offset_after_transient_m.rms"),
                cm("lateral max [cm]", "tracking.lateral_offset_after_transient_m.max"),
                cm("on the turn, RMS [cm]", "tracking.lateral_offset_turn_m.rms"),
                Stat("route time [s]", "route.completion_time_s", CellStat::kMeanStd),
                Count("route completed", "route.completed")};
  tr.rows = {
      Row({"the paper's fuzzy controller, Kalman fixes (`inspection_u_route`)"}, "paper"),
      Row({"the same with limit + mean instead of Kalman (`inspection_no_kalman`)"}, "no_kalman"),
      Row({"+ turn feed-forward (ours; `inspection_u_route_feedforward`)"}, "feedforward")};
  p.tables.push_back(tr);

  ReproTable loc;
  loc.id = "localisation";
  loc.title = "Inspection robot, position error of each estimate (`inspection_u_route`)";
  loc.label_headers = {"estimate", "paper"};
  loc.columns = {cm("RMS [cm]", "localisation.position_error_m.{}.rms"),
                 cm("max [cm]", "localisation.position_error_m.{}.max")};
  loc.rows = {Row({"per-axis Kalman", "about 10 cm (field data)"}, "paper", "kalman"),
              Row({"limit + mean filter", "Fig. 8-9: smoother"}, "paper", "classical"),
              Row({"raw trilateration", "Fig. 8-9: noisy"}, "paper", "raw"),
              Row({"dead reckoning alone", "drifts"}, "paper", "dead_reckoning")};
  loc.note = "Our simulated laser is cleaner than the paper's field data.";
  p.tables.push_back(loc);

  ReproTable rate;
  rate.id = "rates";
  rate.title = "Inspection robot, measured rates (`inspection_u_route`)";
  rate.label_headers = {"loop", "paper"};
  rate.columns = {Stat("measured [Hz]", "control.{}", CellStat::kMeanStd, 1.0, 2)};
  rate.rows = {Row({"fuzzy control", "about 5 Hz"}, "paper", "rate_hz"),
               Row({"laser scans", "–"}, "paper", "laser_rate_hz")};
  p.tables.push_back(rate);
  return p;
}

// ---- Paper 004: velocity control from fused camera, odometry and IMU ----
ReproPaper Velocity() {
  ReproPaper p;
  p.name = "velocity";
  p.title = "Velocity control from fused camera, odometry and IMU (paper 004)";
  // The paper's estimator: one inverse depth per feature along its anchor's measured bearing,
  // no side-slip constraint. Ours: (ψ, ρ) and the no-side-slip constraint (the shipped default).
  const std::vector<std::string> paper = {"estimator.landmarks=inverse_depth_1d",
                                          "estimator.nonholonomic=false"};
  p.cases = {{"paper", "velocity_constant", paper},
             {"paper_nhc", "velocity_constant", {"estimator.landmarks=inverse_depth_1d"}},
             {"psi_rho", "velocity_constant", {"estimator.nonholonomic=false"}},
             {"shipped", "velocity_constant", {}},
             {"world_points", "velocity_constant", {"estimator.landmarks=world_point"}}};

  const std::string rmse = "robots.{}.speed_rmse.";
  auto ms = [](const std::string& h, const std::string& m) {
    return Stat(h, m, CellStat::kMeanStd, 1.0, 4);
  };
  ReproTable f6;
  f6.id = "fig6";
  f6.title =
      "Velocity, Fig. 5-6: speed-estimate RMSE [m/s] at a constant 0.445 m/s over tile, wet, "
      "gravel and asphalt (`velocity_constant`)";
  f6.label_headers = {"estimator", "robot (speed loop fed by)"};
  f6.columns = {ms("odometry", rmse + "odometry"),
                ms("visual-inertial only", rmse + "vi_only"),
                ms("fused", rmse + "fused"),
                Below("fused < odometry", rmse + "fused", rmse + "odometry"),
                Below("fused < VI only", rmse + "fused", rmse + "vi_only"),
                ms("speed error from distance [m/s]", "robots.{}.control.linear_error")};
  const std::string paper_est = "the paper's: one inverse depth along the anchor's bearing";
  f6.rows = {Row({paper_est, "R_fused (fused)"}, "paper", "R_fused"),
             Row({paper_est, "R_odo (odometry)"}, "paper", "R_odo"),
             Row({"the paper's + no-side-slip constraint (ours)", "R_fused (fused)"}, "paper_nhc",
                 "R_fused"),
             Row({"(ψ, ρ) inverse depth (ours)", "R_fused (fused)"}, "psi_rho", "R_fused"),
             Row({"(ψ, ρ) + no-side-slip constraint (ours; shipped)", "R_fused (fused)"}, "shipped",
                 "R_fused"),
             Row({"(ψ, ρ) + no-side-slip constraint (ours; shipped)", "R_odo (odometry)"},
                 "shipped", "R_odo"),
             Row({"world points + no-side-slip constraint (ours)", "R_fused (fused)"},
                 "world_points", "R_fused")};
  f6.note =
      "Each run drives R_fused and R_odo side by side; each runs the fused and the "
      "visual-inertial-only estimators. The paper reports fused < visual-inertial < odometry "
      "without printing numbers. Speed error from distance: |distance travelled - commanded| / "
      "time after the settle time (the paper's control metric).";
  p.tables.push_back(f6);

  ReproTable floors;
  floors.id = "floors";
  floors.title = "Velocity, speed-estimate RMSE [m/s] per floor, R_fused (`velocity_constant`)";
  floors.label_headers = {"floor", "estimator"};
  const std::string fr = "robots.R_fused.floors.{}.speed_rmse.";
  floors.columns = {ms("odometry", fr + "odometry"), ms("visual-inertial only", fr + "vi_only"),
                    ms("fused", fr + "fused"),
                    Below("fused < odometry", fr + "fused", fr + "odometry")};
  for (const auto& [label, key] :
       std::vector<std::pair<std::string, std::string>>{{"tile μ 0.8", "floor"},
                                                        {"wet μ 0.15", "wet"},
                                                        {"gravel μ 0.55", "gravel"},
                                                        {"asphalt μ 0.9", "asphalt"}}) {
    floors.rows.push_back(Row({label, "the paper's"}, "paper", key));
    floors.rows.push_back(Row({label, "(ψ, ρ) + no-side-slip (ours; shipped)"}, "shipped", key));
  }
  p.tables.push_back(floors);

  ReproFigure fig;
  fig.id = "fig6_speed_rmse";
  fig.table = "fig6";
  fig.title = "Fig. 6: speed-estimate RMSE per floor, R_fused, mean ± std";
  fig.y_label = "speed RMSE [m/s]";
  fig.categories = {{"all", ""},
                    {"tile", "floors.floor."},
                    {"wet", "floors.wet."},
                    {"gravel", "floors.gravel."},
                    {"asphalt", "floors.asphalt."}};
  fig.series = {
      {"odometry", "shipped", "robots.R_fused.{}speed_rmse.odometry"},
      {"visual-inertial only, (ψ, ρ) (ours)", "shipped", "robots.R_fused.{}speed_rmse.vi_only"},
      {"fused, the paper's estimator", "paper", "robots.R_fused.{}speed_rmse.fused"},
      {"fused, (ψ, ρ) + no-side-slip (ours; shipped)", "shipped",
       "robots.R_fused.{}speed_rmse.fused"}};
  p.figures.push_back(fig);

  // Tables 2-3: speed and yaw-rate control over a grid of commands on two floors; each case
  // with the paper's estimator and with ours. The odometry-fed robot does not use the estimator.
  auto control_table = [&](const std::string& id, const std::string& title, const std::string& kind,
                           const std::string& key, const std::vector<double>& values,
                           const std::string& metric, const std::string& unit) {
    ReproTable t;
    t.id = id;
    t.title = title;
    t.label_headers = {"floor", unit};
    const std::string fused = "robots.R_fused.control." + metric,
                      odo = "robots.R_odo.control." + metric;
    t.columns = {InCase(ms("fused-fed, the paper's estimator", fused), "{}_paper"),
                 InCase(ms("fused-fed, shipped estimator (ours)", fused), "{}"),
                 InCase(ms("odometry-fed", odo), "{}"),
                 InCase(Below("paper's fused-fed better", fused, odo), "{}_paper"),
                 InCase(Below("shipped fused-fed better (ours)", fused, odo), "{}")};
    for (const auto& [floor, label] : std::vector<std::pair<std::string, std::string>>{
             {"high", "asphalt μ 0.9"}, {"low", "wet μ 0.15"}}) {
      for (double v : values) {
        const std::string c = kind + "_" + floor + "_" + Str(v);
        const std::string scenario = "velocity_" + kind + "_" + floor;
        p.cases.push_back({c + "_paper", scenario, {key + "=" + Str(v), paper[0], paper[1]}});
        p.cases.push_back({c, scenario, {key + "=" + Str(v)}});
        t.rows.push_back(Row({label, Str(v)}, "", c));
      }
    }
    t.note =
        "Control error: |distance (angle) travelled - commanded| / time after the settle time"
        " (`velocity_" +
        kind + "_{high,low}` with --set " + key + "=...).";
    p.tables.push_back(t);
  };
  control_table("table2", "Velocity, Table 2: linear-speed control error Δv [m/s]", "linear",
                "command.v", {0.2, 0.35, 0.5, 0.65, 0.8}, "linear_error", "v [m/s]");
  control_table("table3", "Velocity, Table 3: yaw-rate control error Δω [rad/s] at v = 0.5 m/s",
                "angular", "command.omega", {0.2, 0.4, 0.6, 0.8, 1.0}, "angular_error",
                "ω [rad/s]");
  return p;
}

}  // namespace

const std::vector<sim::ReproPaper>& ReproPapers() {
  static const std::vector<sim::ReproPaper> papers = [] {
    std::vector<sim::ReproPaper> v = {Formation(), Agv(), Inspection(), Velocity()};
    for (const sim::ReproPaper& p : v) sim::CheckPaper(p);
    return v;
  }();
  return papers;
}

const sim::ReproPaper& FindReproPaper(const std::string& name) {
  std::string names;
  for (const sim::ReproPaper& p : ReproPapers()) {
    if (p.name == name) return p;
    names += (names.empty() ? "" : ", ") + p.name;
  }
  throw std::runtime_error("formsim reproduce: no paper '" + name + "' (papers: " + names + ")");
}

}  // namespace formsim::app
