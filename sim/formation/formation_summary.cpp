// Metrics of the formation experiment: summary.json, the printed table, read-only link views.
#include <cstdio>
#include <map>

#include "sim/formation/formation_experiment.hpp"

namespace formsim::sim {
namespace {

using control::FormationLaw;

const char* EstimatorName(EstimatorMode m) {
  static const char* kNames[] = {"truth", "raw", "ukf"};
  return kNames[static_cast<int>(m)];
}

bool Mentions(const std::string& robots, const std::string& name) {
  std::size_t start = 0;
  while (start <= robots.size()) {
    const std::size_t end = robots.find(',', start);
    const std::string item = robots.substr(start, end == std::string::npos ? end : end - start);
    if (item == name) return true;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return false;
}

}  // namespace

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
    v.has_phi_target = l.c_e_phi >= 0;
    v.filter =
        cfg_.robots[l.follower].follow.estimator == EstimatorMode::kUkf ? l.filter.get() : nullptr;
    v.nees = l.nees;
    v.filter_faults = l.fault_count;
    out.push_back(v);
  }
  return out;
}

Json FormationExperiment::Summary() const {
  Json root = Json::Object();
  root["bearing"] = cfg_.bearing == control::BearingConvention::kDas ? "das" : "printed";
  root["gain_reading"] =
      cfg_.gain_reading == control::GainReading::kPrinted ? "printed" : "per_sample";
  root["control_period"] = cfg_.control_period;
  root["settle_time"] = cfg_.settle_time;
  Json links = Json::Object();
  for (const Link& l : links_) {
    const FormationRobotDef& r = cfg_.robots[l.follower];
    const std::string& leader = cfg_.robots[l.leader].body.name;
    Json j = Json::Object();
    j["law"] = r.node.law == FormationLaw::kLPhi ? "l_phi" : "l_l";
    j["estimator"] = EstimatorName(r.follow.estimator);
    auto block = [&](auto get) {
      Json b = Json::Object();
      b["l"] = get(l.e_l);
      if (l.c_e_phi >= 0) b["phi"] = get(l.e_phi);
      b["alpha"] = get(l.e_alpha);
      return b;
    };
    j["max_abs_error"] = block([](const SettledErrorStats& s) { return s.max_abs; });
    j["max_abs_error_after_settle"] =
        block([](const SettledErrorStats& s) { return s.max_abs_settled(); });
    j["rmse_after_settle"] = block([](const SettledErrorStats& s) { return s.rmse_settled(); });
    if (r.follow.estimator != EstimatorMode::kTruth) {
      Json e = Json::Object();
      e["l"] = l.est_l.rms();
      e["phi"] = l.est_phi.rms();
      e["alpha"] = l.est_alpha.rms();
      j["estimation_rmse"] = e;
      if (r.follow.estimator == EstimatorMode::kUkf) j["filter_fault_steps"] = l.fault_count;
    }
    // Events concerning this link: its follower (saturation, singular, filter faults,
    // collisions) or a collision between its two robots.
    std::map<std::string, int> counts = {
        {"collision", 0}, {"saturation", 0}, {"singular", 0}, {"filter_fault", 0}};
    for (const Event& ev : events_) {
      if (ev.kind == "filter_fault" && ev.message.find("link " + l.name + " ") == std::string::npos)
        continue;
      if (ev.kind == "singular") {
        if (ev.robots.substr(ev.robots.rfind(',') + 1) != r.body.name) continue;
      } else if (!Mentions(ev.robots, r.body.name) &&
                 !(ev.kind == "collision" && Mentions(ev.robots, leader))) {
        continue;
      }
      ++counts[ev.kind];
    }
    Json ev = Json::Object();
    for (const auto& kv : counts) ev[kv.first] = kv.second;
    j["events"] = ev;
    links[l.name] = j;
  }
  root["links"] = links;
  return root;
}

std::string FormationExperiment::SummaryTable() const {
  std::string out;
  char buf[256];
  std::snprintf(buf, sizeof buf, "formation: bearing %s, gains %s, errors after %.2g s\n",
                cfg_.bearing == control::BearingConvention::kDas ? "das" : "printed",
                cfg_.gain_reading == control::GainReading::kPrinted ? "as printed" : "per sample",
                cfg_.settle_time);
  out += buf;
  std::snprintf(buf, sizeof buf, "%-10s %-5s %-5s %11s %11s %11s %11s %11s\n", "link", "law", "est",
                "max|e_l|", "max|e_phi|", "max|e_alpha|", "rmse e_l", "est rms phi");
  out += buf;
  for (const Link& l : links_) {
    const FormationRobotDef& r = cfg_.robots[l.follower];
    char phi[32] = "-", est[32] = "-";
    if (l.c_e_phi >= 0) std::snprintf(phi, sizeof phi, "%.3e", l.e_phi.max_abs_settled());
    if (r.follow.estimator != EstimatorMode::kTruth)
      std::snprintf(est, sizeof est, "%.3e", l.est_phi.rms());
    std::snprintf(buf, sizeof buf, "%-10s %-5s %-5s %11.3e %11s %11.3e %11.3e %11s\n",
                  l.name.c_str(), r.node.law == FormationLaw::kLPhi ? "l-phi" : "l-l",
                  EstimatorName(r.follow.estimator), l.e_l.max_abs_settled(), phi,
                  l.e_alpha.max_abs_settled(), l.e_l.rmse_settled(), est);
    out += buf;
  }
  std::map<std::string, int> counts;
  for (const Event& e : events_) ++counts[e.kind];
  if (!counts.empty()) {
    out += "events:";
    for (const auto& kv : counts) out += " " + kv.first + " " + std::to_string(kv.second);
    out += "\n";
  }
  return out;
}

}  // namespace formsim::sim
