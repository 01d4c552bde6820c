// The formation kind's paper for `formsim reproduce formation`: cases, tables and bar charts.
#include <string>
#include <utility>
#include <vector>

#include "sim/study/reproduction_builders.hpp"
#include "sim/study/reproduction_registry.hpp"

namespace formsim::sim::formation {
namespace {

using namespace sim::repro;  // NOLINT: the table builders

// ---- Paper 000: cascade formation ----
ReproPaper FormationPaper() {
  ReproPaper p;
  p.name = "formation";
  p.number = 0;
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

  // The bearing error of the first link per trajectory and estimator, one chart per gain reading.
  for (const std::string gains : {"printed", "per_sample"}) {
    ReproFigure fig;
    fig.id = "errors_phi12_" + gains;
    fig.table = "errors";
    fig.title = std::string("max|e_{\\phi}| after settling, link R1-R2, gains ") +
                (gains == "printed" ? "as printed" : "per sample") + ", mean ± std";
    fig.y_label = "max|e_{\\phi}| [rad]";
    fig.categories = {{"trajectory 1", "1"}, {"trajectory 2", "2"}, {"trajectory 3", "3"}};
    for (const std::string est : {"truth", "raw", "ukf"})
      fig.series.push_back({est == "ukf" ? "UKF" : est, "traj{}_" + gains + "_" + est,
                            "links.R1-R2.max_abs_error_after_settle.phi"});
    p.figures.push_back(fig);
  }
  return p;
}

}  // namespace

FORMSIM_REGISTER_PAPER(FormationPaper);

}  // namespace formsim::sim::formation
