// The AGV kind's paper for `formsim reproduce agv`: cases, tables and bar charts.
#include <string>
#include <utility>
#include <vector>

#include "sim/study/reproduction_builders.hpp"
#include "sim/study/reproduction_registry.hpp"

namespace formsim::sim::agv {
namespace {

using namespace sim::repro;  // NOLINT: the table builders

// ---- Paper 002: Mecanum AGV ----

// The runs: one per localisation, outlier rate, beacon noise and R, and the wet corner.
void AddAgvCases(ReproPaper& p) {
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
}

// The columns most of the paper's tables share.
struct AgvColumns {
  ReproColumn rms =
      Stat("cross-track RMS [mm]", "cross_track.rms_m", CellStat::kMeanStdRange, 1000.0);
  ReproColumn max =
      Stat("cross-track max [mm]", "cross_track.max_m", CellStat::kMeanStdRange, 1000.0);
  ReproColumn loops = Count("loop completed", "loop_completed");
  ReproColumn jumps = Stat("estimate jumps > 5 cm", "localisation.{}.jumps", CellStat::kMeanStd);
};

// Fig. 6: the true cross-track error of each localisation (table and bar chart).
void AddAgvLocalisation(ReproPaper& p, const AgvColumns& c) {
  ReproTable loc;
  loc.id = "localisation";
  loc.title = "AGV, true cross-track error by localisation (cf. Fig. 6): 5% beacon outliers";
  loc.label_headers = {"localisation", "paper"};
  loc.columns = {c.rms, c.max, c.loops, c.jumps,
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
  ReproFigure loc_fig;
  loc_fig.id = "localisation_cross_track";
  loc_fig.table = "localisation";
  loc_fig.title = "AGV cross-track error by localisation (cf. Fig. 6), mean ± std";
  loc_fig.y_label = "cross-track error [mm]";
  loc_fig.categories = {{"odometry", "odometry"},
                        {"beacon", "beacon"},
                        {"plain KF (paper)", "plain_kf"},
                        {"KF + χ² gate (ours)", "gate"},
                        {"gate + adaptive R (ours)", "gate_adaptive"}};
  loc_fig.series = {{"RMS", "{}", "cross_track.rms_m"}, {"max", "{}", "cross_track.max_m"}};
  loc_fig.scale = 1000.0;
  p.figures.push_back(loc_fig);
}

// The fused filters against the beacon's outlier rate (table and bar chart).
void AddAgvOutliers(ReproPaper& p, const AgvColumns& c) {
  ReproTable out;
  out.id = "outliers";
  out.title = "AGV, fused localisation against the beacon's outlier rate";
  out.label_headers = {"filter", "outliers"};
  out.columns = {c.rms, c.max, c.loops, c.jumps};
  out.rows = {Row({"the paper's plain KF", "0%"}, "plain_kf_outliers_0", "fused"),
              Row({"the paper's plain KF", "1%"}, "plain_kf_outliers_0.01", "fused"),
              Row({"the paper's plain KF", "5%"}, "plain_kf", "fused"),
              Row({"KF + χ² gate (ours)", "0%"}, "gate_outliers_0", "fused"),
              Row({"KF + χ² gate (ours)", "1%"}, "gate_outliers_0.01", "fused"),
              Row({"KF + χ² gate (ours)", "5%"}, "gate", "fused")};
  p.tables.push_back(out);
  ReproFigure out_fig;
  out_fig.id = "outliers_cross_track";
  out_fig.table = "outliers";
  out_fig.title = "AGV fused cross-track RMS against the beacon's outlier rate, mean ± std";
  out_fig.y_label = "cross-track RMS [mm]";
  out_fig.categories = {{"0% outliers", "_outliers_0"}, {"1%", "_outliers_0.01"}, {"5%", ""}};
  out_fig.series = {{"the paper's plain KF", "plain_kf{}", "cross_track.rms_m"},
                    {"KF + χ² gate (ours)", "gate{}", "cross_track.rms_m"}};
  out_fig.scale = 1000.0;
  p.figures.push_back(out_fig);
}

// Beacon noise against the R the filter assumes.
void AddAgvSensitivity(ReproPaper& p, const AgvColumns& c) {
  ReproTable sens;
  sens.id = "sensitivity";
  sens.title =
      "AGV, beacon noise against the R the filter assumes (estimation.r_xy), KF + χ² gate (ours)";
  sens.label_headers = {"beacon σ", "estimation.r_xy"};
  sens.columns = {c.rms, c.max, c.loops};
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
}

// A fixed R ten times too small against the adaptive R.
void AddAgvAdaptive(ReproPaper& p, const AgvColumns& c) {
  ReproTable adapt;
  adapt.id = "adaptive";
  adapt.title = "AGV, R ten times too small (beacon σ 30 mm, estimation.r_xy 3 mm), KF + χ² gate";
  adapt.label_headers = {"R"};
  adapt.columns = {
      c.rms, c.max, c.loops,
      Stat("R in use at the end [mm]", "filter.r_xy_in_use_m", CellStat::kMeanStdRange, 1000.0)};
  adapt.rows = {Row({"fixed (3 mm)"}, "r_small"), Row({"adaptive R (ours)"}, "r_small_adaptive")};
  p.tables.push_back(adapt);
}

// A wet patch on the first corner.
void AddAgvSlippery(ReproPaper& p, const AgvColumns& c) {
  ReproTable slip;
  slip.id = "slippery";
  slip.title = "AGV, a wet patch (μ 0.05) on the first corner (`agv_slippery_corner`)";
  slip.label_headers = {"filter"};
  slip.columns = {c.rms, c.max, c.loops,
                  Stat("odometry estimate max error [mm]", "localisation.odometry.position_max_m",
                       CellStat::kMeanStdRange, 1000.0)};
  slip.rows = {Row({"the paper's plain KF"}, "slippery_plain_kf"),
               Row({"KF + χ² gate (ours)"}, "slippery_gate")};
  p.tables.push_back(slip);
}

ReproPaper AgvPaper() {
  ReproPaper p;
  p.name = "agv";
  p.number = 2;
  p.title = "Omnidirectional Mecanum AGV (paper 002)";
  AddAgvCases(p);
  const AgvColumns columns;
  AddAgvLocalisation(p, columns);
  AddAgvOutliers(p, columns);
  AddAgvSensitivity(p, columns);
  AddAgvAdaptive(p, columns);
  AddAgvSlippery(p, columns);
  return p;
}

}  // namespace

FORMSIM_REGISTER_PAPER(AgvPaper);

}  // namespace formsim::sim::agv
