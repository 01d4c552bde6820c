// Metrics of the formation experiment (summary.json, the printed and GUI tables) and the
// read-only link views.
#include <algorithm>

#include "sim/core/number_format.hpp"
#include "sim/formation/formation_experiment.hpp"

namespace formsim::sim::formation {

using cf::FormationLaw;

std::vector<FormationExperiment::LinkView> FormationExperiment::Links() const {
  std::vector<LinkView> out;
  for (const Link& l : links_) {
    LinkView v;
    v.name = l.name;
    v.leader = l.leader;
    v.follower = l.follower;
    v.truth = l.truth;
    v.measured = l.measured;
    v.used = l.used;
    v.e_l = l.e_l;
    v.e_phi = l.e_phi;
    v.e_alpha = l.e_alpha;
    v.est_l = l.est_l;
    v.est_phi = l.est_phi;
    v.est_alpha = l.est_alpha;
    v.has_phi_target = cfg_.robots[l.follower].node.law == FormationLaw::kLPhi;
    v.filter = Mode(l.follower) == EstimatorMode::kUkf ? l.filter.get() : nullptr;
    v.nees = l.nees;
    v.filter_faults = l.fault_count;
    out.push_back(v);
  }
  return out;
}

namespace {

// What the formation's metrics mean: which way is better, their labels and units (axes of sweep
// figures and tables), and the headline metrics.
void DescribeFormationResults(Metrics& m) {
  // Comparing runs (the GUI's pins, history, Monte Carlo): errors and event counts are better low.
  for (const char* p :
       {"links.*.max_abs_error*", "links.*.rmse_after_settle.*", "links.*.estimation_rmse.*",
        "links.*.filter_fault_steps", "links.*.events.*"})
    m.SetBetter(p, Better::kLower);
  // Labels (markup) and units: axes of sweep figures and tables.
  m.Describe("control_period", "control period", "s");
  m.Describe("settle_time", "settling time", "s");
  // Per link component: its path name, its symbol (markup) and unit.
  const char* const parts[][3] = {
      {"l", "l", "m"}, {"phi", "\\phi", "rad"}, {"alpha", "\\alpha", "rad"}};
  for (const auto& [q, sym, unit] : parts) {
    const std::string e = std::string("e_{") + sym + "}", tail = std::string(".") + q;
    m.Describe("links.*.max_abs_error" + tail, "max|" + e + "| over the run, link {1}", unit);
    m.Describe("links.*.max_abs_error_after_settle" + tail,
               "max|" + e + "| after settling, link {1}", unit);
    m.Describe("links.*.rmse_after_settle" + tail, "RMS " + e + " after settling, link {1}", unit);
    m.Describe("links.*.estimation_rmse" + tail,
               std::string("RMS error of the estimated ") + sym + ", link {1}", unit);
  }
  m.Describe("links.*.filter_fault_steps", "filter fault steps, link {1}", "");
  m.Describe("links.*.events.*", "{2} events, link {1}", "");
  m.Describe("switches.collisions_after_transient", "collisions after the transient", "");
  m.Describe("switches.max_formation_error_after_settle", "max formation error after settling",
             "m");
  m.Describe("switches.tolerance", "recovery tolerance", "m");
  m.Describe("switches.max_recover_s", "longest recovery", "s");
  m.Describe("switches.not_recovered", "switches not recovered", "");
  using C = Metrics::Combine;
  // The worst link of each (the table has one row per link).
  m.AddHeadline({"max|e_l| [m]", "links.*.max_abs_error_after_settle.l", C::kMax, "%.3g"});
  m.AddHeadline({"max|e_phi| [rad]", "links.*.max_abs_error_after_settle.phi", C::kMax, "%.3g"});
  m.AddHeadline({"rmse e_l [m]", "links.*.rmse_after_settle.l", C::kMax, "%.3g"});
  // A contact counts once (summary.json's event count), not once per link of each robot in it.
  m.AddHeadline({"collisions", "events.collision", C::kValue, "%.0f"});
}

}  // namespace

Metrics FormationExperiment::Results() const {
  Metrics m;
  const bool das = cfg_.bearing == cf::BearingConvention::kDas;
  const bool printed = cfg_.gain_reading == cf::GainReading::kPrinted;
  m.SetText("bearing", das ? "das" : "printed");
  m.SetText("gain_reading", printed ? "printed" : "per_sample");
  m.SetSetting("control_period", cfg_.control_period);
  m.SetSetting("settle_time", cfg_.settle_time);
  m.AddNote(Sprintf("formation: bearing %s, gains %s, errors after %.2g s", das ? "das" : "printed",
                    printed ? "as printed" : "per sample", cfg_.settle_time));
  AddLinkResults(m);
  // Contacts: each collision once, whatever robots and links it involves (the event log's one
  // definition); the links' events.collision count the contacts of their follower.
  m.Set("events.collision", static_cast<double>(events_.Count(event::kCollision)));
  m.SetBetter("events.collision", Better::kLower);
  if (cfg_.switching.enabled() || cfg_.avoidance.present) AddSwitchResults(m);
  DescribeFormationResults(m);
  return m;
}

void FormationExperiment::AddLinkResults(Metrics& m) const {
  Metrics::Table table;
  table.row_header = "link";
  table.columns = {{"law", "law", ""},
                   {"est", "estimator", ""},
                   {"max|e_l| [m]", "max_abs_error_after_settle.l", "%.3e"},
                   {"max|e_phi| [rad]", "max_abs_error_after_settle.phi", "%.3e"},
                   {"max|e_alpha| [rad]", "max_abs_error_after_settle.alpha", "%.3e"},
                   {"rmse e_l [m]", "rmse_after_settle.l", "%.3e"},
                   {"est rms phi [rad]", "estimation_rmse.phi", "%.3e"}};
  for (const Link& l : links_) {
    const FormationRobotDef& r = cfg_.robots[l.follower];
    const std::string p = "links." + l.name + ".";
    const bool lphi = r.node.law == FormationLaw::kLPhi;
    m.SetText(p + "law", cf::LawName(r.node.law));
    m.SetText(p + "estimator", EstimatorModeNames()[static_cast<int>(r.follow.estimator)]);
    auto block = [&](const std::string& name, auto get) {
      m.Set(p + name + ".l", get(l.e_l));
      if (lphi) m.Set(p + name + ".phi", get(l.e_phi));
      m.Set(p + name + ".alpha", get(l.e_alpha));
    };
    block("max_abs_error", [](const SettledErrorStats& s) { return s.max_abs; });
    block("max_abs_error_after_settle",
          [](const SettledErrorStats& s) { return s.max_abs_settled(); });
    block("rmse_after_settle", [](const SettledErrorStats& s) { return s.rmse_settled(); });
    // Estimation metrics exist when an estimator ran at some time of the run (the estimator can
    // be switched live).
    if (l.est_l.n > 0) {
      m.Set(p + "estimation_rmse.l", l.est_l.rms());
      m.Set(p + "estimation_rmse.phi", l.est_phi.rms());
      m.Set(p + "estimation_rmse.alpha", l.est_alpha.rms());
    }
    if (l.ever_ukf) m.Set(p + "filter_fault_steps", l.fault_count);
    // Consistency of the filter on l (e_l² / P_ll averaged after the settle time; 1 when the
    // filter's variance matches its error).
    if (l.nees_l.n > 0) m.Set(p + "nees_l_mean", l.nees_l.mean());
    const std::string& f = r.body.name;
    m.Set(p + "events.collision", static_cast<double>(events_.CountForRobot(event::kCollision, f)));
    m.Set(p + "events.saturation",
          static_cast<double>(events_.CountForRobot(event::kSaturation, f)));
    m.Set(p + "events.singular", static_cast<double>(events_.CountForSubject(event::kSingular, f)));
    m.Set(p + "events.filter_fault",
          static_cast<double>(events_.CountForSubject(event::kFilterFault, l.name)));
    table.rows.emplace_back(l.name, "links." + l.name);
  }
  m.AddTable(std::move(table));
}

void FormationExperiment::AddSwitchResults(Metrics& m) const {
  // Switching and avoidance: collisions after the initial transient (settle_time), the largest
  // formation error after it, and per switch how long the error took to stay below 1e-2.
  m.Set("switches.collisions_after_transient", static_cast<double>(collisions_after_));
  m.Set("switches.max_formation_error_after_settle", max_error_settled_);
  m.SetSetting("switches.tolerance", kRecoveredError);
  m.Set("switches.avoidance_entries", static_cast<double>(avoid_entries_));
  double worst = 0.0;
  int not_recovered = 0;
  for (std::size_t k = 0; k < switches_.size(); ++k) {
    const SwitchRecord& r = switches_[k];
    const std::string p = "switches.list." + std::to_string(k) + ".";
    const double end = r.end >= 0.0 ? r.end : time();
    const double rec = r.Recover(dt());
    // Recovered: the error stayed below the tolerance for the rest of the switch's window.
    const bool ok = r.last_above < end - 0.5 * dt() || r.last_above < r.time;
    m.Set(p + "time", r.time);
    m.SetText(p + "kind", r.kind);
    m.SetText(p + "what", r.what);
    m.Set(p + "recover_s", rec);
    m.Set(p + "recovered", ok ? 1.0 : 0.0);
    worst = std::max(worst, rec);
    if (!ok) ++not_recovered;
  }
  m.Set("switches.count", static_cast<double>(switches_.size()));
  m.Set("switches.max_recover_s", worst);
  m.Set("switches.not_recovered", static_cast<double>(not_recovered));
  for (const char* p :
       {"switches.collisions_after_transient", "switches.max_formation_error_after_settle",
        "switches.max_recover_s", "switches.not_recovered"})
    m.SetBetter(p, Better::kLower);
}

}  // namespace formsim::sim::formation
