// The inspection kind's paper for `formsim reproduce inspection`: cases, tables and bar charts.
#include <string>
#include <utility>
#include <vector>

#include "sim/study/reproduction_builders.hpp"
#include "sim/study/reproduction_registry.hpp"

namespace formsim::sim::inspection {
namespace {

using namespace sim::repro;  // NOLINT: the table builders

// ---- Paper 003: substation inspection robot ----
ReproPaper InspectionPaper() {
  ReproPaper p;
  p.name = "inspection";
  p.number = 3;
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
  ReproFigure tr_fig;
  tr_fig.id = "tracking_lateral";
  tr_fig.table = "tracking";
  tr_fig.title = "Inspection robot, lateral offset after the first 6 m, mean ± std";
  tr_fig.y_label = "lateral offset [cm]";
  tr_fig.categories = {{"Kalman (paper)", "paper"},
                       {"limit + mean", "no_kalman"},
                       {"+ feed-forward (ours)", "feedforward"}};
  tr_fig.series = {{"RMS", "{}", "tracking.lateral_offset_after_transient_m.rms"},
                   {"max", "{}", "tracking.lateral_offset_after_transient_m.max"},
                   {"RMS on the turn", "{}", "tracking.lateral_offset_turn_m.rms"}};
  tr_fig.scale = 100.0;
  p.figures.push_back(tr_fig);

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
  ReproFigure loc_fig;
  loc_fig.id = "localisation_error";
  loc_fig.table = "localisation";
  loc_fig.title = "Inspection robot, position error of each estimate, mean ± std";
  loc_fig.y_label = "position error [cm]";
  loc_fig.categories = {{"per-axis Kalman", "kalman"},
                        {"limit + mean", "classical"},
                        {"raw trilateration", "raw"},
                        {"dead reckoning", "dead_reckoning"}};
  loc_fig.series = {{"RMS", "paper", "localisation.position_error_m.{}.rms"},
                    {"max", "paper", "localisation.position_error_m.{}.max"}};
  loc_fig.scale = 100.0;
  p.figures.push_back(loc_fig);

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

}  // namespace

FORMSIM_REGISTER_PAPER(InspectionPaper);

}  // namespace formsim::sim::inspection
