// The velocity kind's paper for `formsim reproduce velocity`: cases, tables and figures.
#include <string>
#include <utility>
#include <vector>

#include "sim/study/reproduction_builders.hpp"
#include "sim/study/reproduction_registry.hpp"

namespace formsim::sim::velocity {
namespace {

using namespace sim::repro;  // NOLINT: the table builders

// ---- Paper 004: velocity control from fused camera, odometry and IMU ----

// The paper's estimator: one inverse depth per feature along its anchor's measured bearing, no
// side-slip constraint. Ours: (ψ, ρ) and the no-side-slip constraint (the shipped default).
const std::vector<std::string>& VelocityPaperEstimator() {
  static const std::vector<std::string> settings = {"estimator.landmarks=inverse_depth_1d",
                                                    "estimator.nonholonomic=false"};
  return settings;
}

// A cell of the tables: mean ± standard deviation over the seeds.
ReproColumn VelocityMeanStd(const std::string& header, const std::string& metric) {
  return Stat(header, metric, CellStat::kMeanStd, 1.0, 4);
}

// Fig. 5-6: the speed estimate's RMSE of each estimator, with the paper's and ours.
ReproTable VelocitySpeedTable() {
  const std::string rmse = "robots.{}.speed_rmse.";
  const auto ms = VelocityMeanStd;
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
  return f6;
}

// The speed estimate's RMSE floor by floor.
ReproTable VelocityFloorsTable() {
  const auto ms = VelocityMeanStd;
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
  return floors;
}

// Fig. 6: the speed estimate's RMSE per floor as bars.
ReproFigure VelocitySpeedFigure() {
  ReproFigure fig;
  fig.id = "fig6_speed_rmse";
  fig.table = "fig6";
  fig.title = "Fig. 6: speed-estimate RMSE per floor, R_{fused}, mean ± std";
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
  return fig;
}

// One of Tables 2-3: a grid of commands (key = each of values) on two floors.
struct VelocityControlSweep {
  std::string id, title, kind, key;
  std::vector<double> values;
  std::string metric, unit;
};

// Tables 2-3: speed and yaw-rate control over a grid of commands on two floors; each case with
// the paper's estimator and with ours. The odometry-fed robot does not use the estimator.
void AddVelocityControlTable(ReproPaper& p, const VelocityControlSweep& sweep) {
  const std::vector<std::string>& paper = VelocityPaperEstimator();
  const auto ms = VelocityMeanStd;
  const std::string& kind = sweep.kind;
  const std::string& key = sweep.key;
  ReproTable t;
  t.id = sweep.id;
  t.title = sweep.title;
  t.label_headers = {"floor", sweep.unit};
  const std::string fused = "robots.R_fused.control." + sweep.metric,
                    odo = "robots.R_odo.control." + sweep.metric;
  t.columns = {InCase(ms("fused-fed, the paper's estimator", fused), "{}_paper"),
               InCase(ms("fused-fed, shipped estimator (ours)", fused), "{}"),
               InCase(ms("odometry-fed", odo), "{}"),
               InCase(Below("paper's fused-fed better", fused, odo), "{}_paper"),
               InCase(Below("shipped fused-fed better (ours)", fused, odo), "{}")};
  for (const auto& [floor, label] : std::vector<std::pair<std::string, std::string>>{
           {"high", "asphalt μ 0.9"}, {"low", "wet μ 0.15"}}) {
    for (double v : sweep.values) {
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
}

ReproPaper VelocityPaper() {
  ReproPaper p;
  p.name = "velocity";
  p.number = 4;
  p.title = "Velocity control from fused camera, odometry and IMU (paper 004)";
  p.cases = {{"paper", "velocity_constant", VelocityPaperEstimator()},
             {"paper_nhc", "velocity_constant", {"estimator.landmarks=inverse_depth_1d"}},
             {"psi_rho", "velocity_constant", {"estimator.nonholonomic=false"}},
             {"shipped", "velocity_constant", {}},
             {"world_points", "velocity_constant", {"estimator.landmarks=world_point"}}};
  p.tables.push_back(VelocitySpeedTable());
  p.tables.push_back(VelocityFloorsTable());
  p.figures.push_back(VelocitySpeedFigure());
  AddVelocityControlTable(p, {"table2",
                              "Velocity, Table 2: linear-speed control error Δv [m/s]",
                              "linear",
                              "command.v",
                              {0.2, 0.35, 0.5, 0.65, 0.8},
                              "linear_error",
                              "v [m/s]"});
  AddVelocityControlTable(p, {"table3",
                              "Velocity, Table 3: yaw-rate control error Δω [rad/s] at v = 0.5 m/s",
                              "angular",
                              "command.omega",
                              {0.2, 0.4, 0.6, 0.8, 1.0},
                              "angular_error",
                              "ω [rad/s]"});
  return p;
}

}  // namespace

FORMSIM_REGISTER_PAPER(VelocityPaper);

}  // namespace formsim::sim::velocity
