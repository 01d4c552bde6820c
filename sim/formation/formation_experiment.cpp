#include "sim/formation/formation_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "control/formation/link_predict_lanes.hpp"
#include "control/formation/link_update_lanes.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::sim::formation {

FORMSIM_REGISTER_EXPERIMENT("formation", FormationExperiment);

namespace {

using cf::FormationLaw;
using cf::LinkState;
using cf::Twist;

constexpr double kMinL = 1e-3;  // a distance handed to a law is at least this (noisy raw l)
// Parallel sections hand out at least this much work per task (a link's sensor and UKF is about
// a microsecond; an agent's law or sin_ll a tenth of that).
constexpr std::size_t kLinksPerTask = 16;
constexpr std::size_t kAgentsPerTask = 128;
// From this many links on (a task's worth), the filters' predictions run beside the Box2D step
// (see PredictItems). Below, handing them to another core costs more than it saves: a round trip
// between the two cores of the VM of docs/benchmarks.md is 0.5 µs and the filters' cache lines move
// with it, while three links predict in under a microsecond (the paper scenario ran 2.6 ms
// instead of 2.0 beside Box2D; 18 links, 10 robots, gained 12%).
constexpr std::size_t kPredictBesideLinks = kLinksPerTask;

}  // namespace

FormationExperiment::FormationExperiment(const ExperimentSetup& setup,
                                         const FormationConfig& config)
    : ExperimentOf(setup, config) {
  slots_ = cfg_.ShapeSlots(-1);
  slot_rates_.assign(slots_.size(), cf::SlotRates{});
  BuildWorld();
  DeclareChannels();
  Start();
}

void FormationExperiment::BuildWorld() {
  world_.SetDef(cfg_.world);
  for (const auto& o : cfg_.obstacles) world_.CreateObstacle(o);
  for (const auto& p : cfg_.patches) world_.CreatePatch(p);
  agents_.resize(cfg_.robots.size());
  for (std::size_t i = 0; i < cfg_.robots.size(); ++i) {
    const FormationRobotDef& r = cfg_.robots[i];
    Agent& a = agents_[i];
    a.robot = &world_.CreateRobot(r.body);
    auto drive = std::make_unique<UnicycleDrive>(r.drive);
    a.drive = drive.get();
    a.robot->SetDrive(std::move(drive));
    a.saturation = events_.DeclareCondition(event::kSaturation, r.body.name);
    a.trail.SetCapacity(static_cast<std::size_t>(cfg_.trail_length));
  }
  // Links in topological order of their followers, leaders in declaration order.
  for (int j : cfg_.graph.order) {
    const auto& leaders = cfg_.graph.leaders[j];
    for (std::size_t k = 0; k < leaders.size(); ++k) {
      const int i = leaders[k];
      const std::string name = cfg_.robots[i].body.name + "-" + cfg_.robots[j].body.name;
      links_.emplace_back(name, i, j);
      sensors_.emplace_back(rng_, name);
      link_fault_now_.push_back(0);
      link_faulty_.push_back(0);
      Link& l = links_.back();
      l.first = k == 0;
      l.fault = events_.DeclareCondition(event::kFilterFault, cfg_.robots[j].body.name, name);
      agents_[j].links.push_back(static_cast<int>(links_.size()) - 1);
    }
    if (leaders.size() == 2) {
      const std::string& f = cfg_.robots[j].body.name;
      agents_[j].singular = events_.DeclareCondition(
          event::kSingular,
          cfg_.robots[leaders[0]].body.name + "," + cfg_.robots[leaders[1]].body.name + "," + f, f);
    }
  }
  for (Link& l : links_) l.filter = cf::LinkFilter::Make(FilterDef(l.follower));
  LinkSettings();
}

void FormationExperiment::LinkSettings() {
  for (Link& l : links_) {
    const FormationRobotDef& r = cfg_.robots[static_cast<std::size_t>(l.follower)];
    const NoiseDef n = EffectiveNoise(cfg_, r.follow);
    l.mode = r.follow.estimator;
    l.lphi = r.node.law == FormationLaw::kLPhi;
    l.sigma_l = n.l.sigma(), l.sigma_phi = n.phi.sigma(), l.sigma_alpha = n.alpha.sigma();
  }
}

cf::LinkFilterDef FormationExperiment::FilterDef(int follower) const {
  const FollowerDef& f = cfg_.robots[follower].follow;
  const NoiseDef n = EffectiveNoise(cfg_, f);
  const UkfDef& u = cfg_.ukf;
  cf::LinkFilterDef d;
  d.measure = f.measure;
  d.Tc = cfg_.control_period;
  d.substeps = u.substeps;
  d.L = cfg_.L;
  d.q = {u.q_l, u.q_phi, u.q_alpha};
  // R defaults to the sensor's variance, floored so that a noise-free sensor keeps Pyy > 0.
  auto r = [](double given, double sensor) { return std::max(given > 0 ? given : sensor, 1e-10); };
  d.r = {r(u.r_l, n.l.variance()), r(u.r_phi, n.phi.variance()), r(u.r_alpha, n.alpha.variance())};
  d.p0 = {u.p0_l, u.p0_phi, u.p0_alpha};
  d.scaling = {u.alpha, u.beta, u.kappa};
  return d;
}

void FormationExperiment::ApplyTunables(const FormationConfig& next) {
  std::vector<EstimatorMode> before;
  for (const auto& r : cfg_.robots) before.push_back(r.follow.estimator);
  cfg_ = next;
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    agents_[i].drive->def() = cfg_.robots[i].drive;
    // A follower switched to an estimator starts its filters from the next measurement.
    if (Mode(static_cast<int>(i)) != before[i])
      for (int li : agents_[i].links) links_[li].filter_ready = false;
  }
  for (Link& l : links_) l.filter->Retune(FilterDef(l.follower));
  LinkSettings();
  // Without switching the slots are the follow: values, which are live tunables.
  if (!cfg_.switching.enabled())
    for (std::size_t j = 0; j < slots_.size(); ++j) slots_[j] = cf::SlotOf(cfg_.robots[j].node);
}

double FormationExperiment::Gain(double k) const {
  return cf::EffectiveGain(k, cfg_.gain_reading, cfg_.control_period);
}

double FormationExperiment::DesiredL(const Link& l) const {
  const cf::SlotValues& n = slots_[static_cast<std::size_t>(l.follower)];
  return l.first ? n.l_des : n.l2_des;
}

LinkState FormationExperiment::ForControl(const Link& link) const {
  const EstimatorMode mode = link.mode;
  LinkState s = mode == EstimatorMode::kTruth ? link.truth_conv
                : mode == EstimatorMode::kRaw ? link.measured
                                              : link.used;
  s.l = std::max(s.l, kMinL);
  return s;
}

void FormationExperiment::Control(double t) {
  if (steps() % cfg_.control_every != 0) return;
  if (cfg_.switching.enabled()) UpdateSlots(t);
  const bool avoid = cfg_.avoidance.enabled && !world_.obstacles().empty();
  const double reach = AvoidanceReach();
  // What each follower's law needs except its leaders' commands (the sines, cosines and errors
  // of its links' states, the desired rates of a moving slot), for every follower at once; with
  // avoidance also its distance to the nearest obstacle (Box2D queries, read-only).
  pool().ParallelFor(
      agents_.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
          const FormationRobotDef& r = cfg_.robots[j];
          Agent& a = agents_[j];
          const cf::FormationGains gains{Gain(r.follow.k1), Gain(r.follow.k2)};
          const cf::SlotValues& s = slots_[j];
          const cf::SlotRates& rate = slot_rates_[j];
          if (r.node.law == FormationLaw::kLPhi) {
            a.lphi = cf::PrepareLPhi(ForControl(links_[a.links[0]]), s.l_des, s.phi_des, gains);
            if (in_transition_) a.lphi.e1 += rate.l_des, a.lphi.e2 += rate.phi_des;
          } else if (r.node.law == FormationLaw::kLL) {
            a.ll = cf::PrepareLL(ForControl(links_[a.links[0]]), ForControl(links_[a.links[1]]),
                                 s.l_des, s.l2_des, gains, cfg_.singular_threshold);
            if (in_transition_) a.ll.e1 += rate.l_des, a.ll.e2 += rate.l2_des;
          }
          if (avoid && r.node.law != FormationLaw::kRoot) {
            a.near = NearestObstacle(world_, cf::ControlPoint(a.robot->pose(), cfg_.L), reach);
            if (a.near.obstacle >= 0) {
              const Pose2 g = DesiredPose(static_cast<int>(j));
              a.slot_d = std::isfinite(g.x) ? DistanceToObstacle(world_, a.near.obstacle,
                                                                 cf::ControlPoint(g, cfg_.L))
                                            : 0.0;
            }
          }
        }
      },
      kAgentsPerTask);
  // Then in cascade order: a follower uses its leaders' commands of this step as feed-forward.
  for (int j : cfg_.graph.order) {
    const FormationRobotDef& r = cfg_.robots[j];
    Agent& a = agents_[j];
    Twist cmd;
    if (r.node.law == FormationLaw::kRoot) {
      cmd = cf::ScheduleAt(r.schedule, t);
    } else if (r.node.law == FormationLaw::kLPhi) {
      cmd = cf::FinishLPhi(a.lphi, agents_[links_[a.links[0]].leader].cmd, cfg_.L);
    } else {
      const Link& l1 = links_[a.links[0]];
      const Link& l2 = links_[a.links[1]];
      const cf::LLCommand c =
          cf::FinishLL(a.ll, agents_[l1.leader].cmd, agents_[l2.leader].cmd, cfg_.L);
      cmd = c.cmd;
      // One event per entry into the singular band.
      events_.Update(a.singular, t, c.singular, [&](std::string& m) {
        m += r.body.name;
        m += " near the line through ";
        m += cfg_.robots[l1.leader].body.name;
        m += " and ";
        m += cfg_.robots[l2.leader].body.name;
        AppendSprintf(m, " (|sin| = %.3f < %.3g), regularised inverse in use",
                      std::abs(c.sin_angle), cfg_.singular_threshold);
      });
    }
    if (cfg_.avoidance.present && r.node.law != FormationLaw::kRoot) cmd = Avoid(j, t, cmd);
    a.drive->SetCommand(cmd.v, cmd.w);
    a.cmd = {a.drive->v_command(), a.drive->omega_command()};
  }
}

void FormationExperiment::InitFilter(Link& link, bool restart) {
  // Measured components start from the measurement; the others from the true value on the first
  // start (the paper gives s(0) as known; l optionally offset by l0_error) and from the last
  // estimate after a fault.
  const cf::MeasurementSet m = cfg_.robots[link.follower].follow.measure;
  LinkState x0 = link.measured;
  if (m != cf::MeasurementSet::kLPhiAlpha)
    x0.l = restart ? link.used.l : link.truth_conv.l + cfg_.ukf.l0_error;
  if (m == cf::MeasurementSet::kAlpha) x0.phi = restart ? link.used.phi : link.truth_conv.phi;
  x0.l = std::max(x0.l, kMinL);
  const cf::LinkFilterDef d = FilterDef(link.follower);
  link.filter->Reset(x0, Eigen::Matrix3d(d.p0.asDiagonal()));
  link.filter_ready = true;
  link.used = link.filter->state();
}

void FormationExperiment::RunFilter(Link& link, cf::LinkUpdateBatch& updates) {
  link.ever_ukf = true;
  link.filter_ran = false;
  if (!link.filter_ready) {
    InitFilter(link, false);
    return;
  }
  link.filter_ran = true;
  const control::UkfStatus st =
      link.predicted ? link.predict_status
                     : link.filter->Predict(agents_[link.leader].cmd, agents_[link.follower].cmd);
  link.predicted = false;
  link.status = st;
  if (st == control::UkfStatus::kOk) updates.Add(*link.filter, link.measured, &link.status);
}

void FormationExperiment::FinishFilter(Link& link) {
  if (!link.filter_ran) return;
  const control::UkfStatus st = link.status;
  if (st != control::UkfStatus::kOk) {
    ++link.fault_count;
    InitFilter(link, true);
    return;
  }
  link.used = link.filter->state();
}

std::size_t FormationExperiment::PredictItems() const {
  // The coming Sense runs the filters when the step now taken ends on a control step; a link
  // not predicted here (too few links, a filter not ready) is predicted in RunFilter.
  if (links_.size() < kPredictBesideLinks) return 0;
  return (steps() + 1) % cfg_.control_every == 0 ? links_.size() : 0;
}

void FormationExperiment::Predict(std::size_t begin, std::size_t end) {
  // The time update from this step's commands, exactly what RunFilter would do first, several
  // links at a time in SIMD lanes (the same bits as one by one).
  cf::LinkPredictBatch batch;
  for (std::size_t i = begin; i < end; ++i) {
    Link& l = links_[i];
    l.predicted = l.mode == EstimatorMode::kUkf && l.filter_ready;
    if (l.predicted)
      batch.Add(*l.filter, agents_[l.leader].cmd, agents_[l.follower].cmd, &l.predict_status);
  }
  batch.Flush();
}

void FormationExperiment::SenseLink(std::size_t i, bool filter_step, cf::LinkUpdateBatch& updates) {
  Link& l = links_[i];
  link_fault_now_[i] = 0;
  const Pose2 pi = agents_[l.leader].robot->pose(), pj = agents_[l.follower].robot->pose();
  const EstimatorMode mode = l.mode;
  if (mode == EstimatorMode::kTruth) {
    // Nobody reads the measurement: skip the noise draws (this link's stream only).
    l.truth_conv = cf::ComputeLinkState(pi, pj, cfg_.L, cfg_.bearing);
    l.measured = l.truth_conv;
  } else {
    l.measured = sensors_[i].Sample(pi, pj, cfg_.L, cfg_.bearing, l.sigma_l, l.sigma_phi,
                                    l.sigma_alpha, l.truth_conv);
  }
  l.truth = cfg_.bearing == cf::BearingConvention::kDas
                ? l.truth_conv
                : cf::ComputeLinkState(pi, pj, cfg_.L, cf::BearingConvention::kDas);
  l.filter_ran = false;
  if (filter_step) {
    if (mode == EstimatorMode::kUkf)
      RunFilter(l, updates);
    else if (mode == EstimatorMode::kRaw)
      l.used = l.measured;
    else
      l.used = l.truth_conv;
  }
}

void FormationExperiment::FinishLink(std::size_t i, double t, bool filter_step) {
  Link& l = links_[i];
  if (filter_step && l.mode == EstimatorMode::kUkf) FinishFilter(l);
  link_fault_now_[i] = l.filter_ran && l.status != control::UkfStatus::kOk;
  Accumulate(l, t);
}

void FormationExperiment::Sense(double t) {
  const bool filter_step = steps() % cfg_.control_every == 0;
  // Fewer links than PredictItems hands to the pool beside Box2D: their time updates run here,
  // together in SIMD lanes, before the sensors (they read only the commands and the estimates).
  if (filter_step && links_.size() < kPredictBesideLinks) Predict(0, links_.size());
  for (Agent& a : agents_) {
    a.saturated = a.drive->saturated();
    events_.Update(a.saturation, t, a.saturated, [&](std::string& m) {
      m += a.robot->name();
      m += a.drive->slipping() ? " slips (traction limit)" : " command clamped to the drive limits";
    });
    if (cfg_.trail_length > 0 && sense_count_ % cfg_.trail_every == 0)
      a.trail.Push(a.robot->pose().p());
  }
  // Each link's sensor (its own noise stream), filter and statistics touch that link only.
  pool().ParallelFor(
      links_.size(),
      [&](std::size_t b, std::size_t e) {
        // The measurement updates of the range together, four links at a time in SIMD lanes
        // (the same bits as one by one), then what follows each.
        {
          cf::LinkUpdateBatch updates;
          for (std::size_t i = b; i < e; ++i) SenseLink(i, filter_step, updates);
        }
        for (std::size_t i = b; i < e; ++i) FinishLink(i, t, filter_step);
      },
      kLinksPerTask);
  // Filter faults, one event per entry into a run of faults, raised in link order so that the
  // log does not depend on the threads; every fault is counted for the summary. The links are
  // visited only while faulty or when their run of faults ends (link_faulty_ is a byte per link:
  // a pass over ten thousand Link structs is ten thousand cache misses).
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const bool faulty = link_fault_now_[i] != 0;
    if (!faulty && link_faulty_[i] == 0) continue;
    Link& link = links_[i];
    if (!link.filter_ran) continue;
    const control::UkfStatus st = link.status;
    events_.Update(link.fault, t, faulty, [&](std::string& m) {
      m += "UKF of link ";
      m += link.name;
      AppendSprintf(m, " at t = %.3f s: %s; restarted with P0", t, control::UkfStatusName(st));
    });
    link_faulty_[i] = faulty;
  }
  // The l-l determinant sin(γ_kj − γ_ij) from the states the law will use (recorded as sin_ll).
  pool().ParallelFor(
      agents_.size(),
      [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
          Agent& a = agents_[i];
          if (a.links.size() != 2) continue;
          a.sin_ll = control::SinCosOf(ForControl(links_[a.links[1]]).gamma() -
                                       ForControl(links_[a.links[0]]).gamma())
                         .s;
        }
      },
      kAgentsPerTask);
  if (cfg_.switching.enabled() || cfg_.avoidance.present) TrackSwitches(t);
  ++sense_count_;
}

void FormationExperiment::Accumulate(Link& l, double t) {
  const bool settled = t >= cfg_.settle_time - 1e-9;
  l.e_l.Add(DesiredL(l) - l.truth.l, settled);
  if (l.lphi)
    l.e_phi.Add(
        control::WrapToPi(slots_[static_cast<std::size_t>(l.follower)].phi_des - l.truth.phi),
        settled);
  l.e_alpha.Add(l.truth.alpha, settled);
  const EstimatorMode mode = l.mode;
  if (mode == EstimatorMode::kTruth || steps() % cfg_.control_every != 0) return;
  const Eigen::Vector3d e(l.used.l - l.truth_conv.l,
                          control::WrapToPi(l.used.phi - l.truth_conv.phi),
                          control::WrapToPi(l.used.alpha - l.truth_conv.alpha));
  l.est_l.Add(e(0));
  l.est_phi.Add(e(1));
  l.est_alpha.Add(e(2));
  if (mode == EstimatorMode::kUkf) {
    l.nees = l.filter->Mahalanobis2(e);
    // The l component alone, e_l² / P_ll: 1 on average when the filter is consistent on l.
    const double p_ll = l.filter->cov()(0, 0);
    if (p_ll > 0.0 && t >= cfg_.settle_time - 1e-9) l.nees_l.Add(e(0) * e(0) / p_ll);
  }
}

Pose2 FormationExperiment::EstimatedPose(const Agent& a) const {
  const Link& l = links_[a.links[0]];
  return cf::FollowerPoseFromLink(agents_[l.leader].robot->pose(), l.used, cfg_.L);
}

void FormationExperiment::DeclareChannels() {
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    const Agent* a = &agents_[i];
    const std::string& n = a->robot->name();
    recorder_.AddGroup({n + ".x", n + ".y", n + ".theta"}, [a](double* o) {
      const Pose2 p = a->robot->pose();
      o[0] = p.x, o[1] = p.y, o[2] = p.theta;
    });
    recorder_.AddGroup({n + ".v_cmd", n + ".w_cmd"},
                       [a](double* o) { o[0] = a->cmd.v, o[1] = a->cmd.w; });
    recorder_.Add(n + ".sat", [a] { return a->saturated ? 1.0 : 0.0; });
    const FormationRobotDef& r = cfg_.robots[i];
    if (r.node.law != FormationLaw::kRoot) {
      const int j = static_cast<int>(i);
      recorder_.AddGroup({n + ".x_est", n + ".y_est", n + ".theta_est"}, [this, a, j](double* o) {
        if (Mode(j) == EstimatorMode::kTruth) return;  // not sampled
        const Pose2 e = EstimatedPose(*a);
        o[0] = e.x, o[1] = e.y, o[2] = e.theta;
      });
    }
    if (r.node.law == FormationLaw::kLL) recorder_.Add(n + ".sin_ll", [a] { return a->sin_ll; });
    if (cfg_.avoidance.present && r.node.law != FormationLaw::kRoot) {
      recorder_.Add(n + ".avoiding", [a] { return a->avoiding ? 1.0 : 0.0; });
      // Beyond reach (nothing within 2 (d_s + h)) the distance reads as the reach.
      recorder_.Add(n + ".obstacle_d", [this, a] {
        return a->near.obstacle >= 0 ? std::min(a->near.distance, AvoidanceReach())
                                     : AvoidanceReach();
      });
    }
  }
  if (cfg_.switching.enabled() || cfg_.avoidance.present)
    recorder_.Add("formation.error", [this] { return formation_error_; });
  if (links_.size() > kManyLinks) {
    // Over all links, computed when a row is recorded.
    recorder_.AddGroup({"links.max_abs_e_l", "links.median_abs_e_l"}, [this](double* o) {
      std::vector<double>& e = error_scratch_;
      e.clear();
      for (const Link& l : links_) e.push_back(std::abs(DesiredL(l) - l.truth.l));
      const auto mid = e.begin() + static_cast<long>(e.size() / 2);
      std::nth_element(e.begin(), mid, e.end());
      o[1] = *mid;
      o[0] = *std::max_element(mid, e.end());
    });
    recorder_.Add("links.max_abs_e_phi", [this] {
      double worst = 0.0;
      for (const Link& l : links_)
        if (cfg_.robots[l.follower].node.law == FormationLaw::kLPhi)
          worst = std::max(
              worst, std::abs(control::WrapToPi(
                         slots_[static_cast<std::size_t>(l.follower)].phi_des - l.truth.phi)));
      return worst;
    });
  }
  for (const Link& link : links_) {
    const Link* l = &link;
    const std::string& n = l->name;
    const bool lphi = cfg_.robots[l->follower].node.law == FormationLaw::kLPhi;
    recorder_.AddGroup({n + ".l", n + ".phi", n + ".alpha"}, [l](double* o) {
      o[0] = l->truth.l, o[1] = l->truth.phi, o[2] = l->truth.alpha;
    });
    recorder_.Add(n + ".l_des", [this, l] { return DesiredL(*l); });
    if (lphi)
      recorder_.Add(n + ".phi_des",
                    [this, l] { return slots_[static_cast<std::size_t>(l->follower)].phi_des; });
    recorder_.Add(n + ".e_l", [this, l] { return DesiredL(*l) - l->truth.l; });
    if (lphi)
      recorder_.Add(n + ".e_phi", [this, l] {
        return control::WrapToPi(slots_[static_cast<std::size_t>(l->follower)].phi_des -
                                 l->truth.phi);
      });
    recorder_.Add(n + ".e_alpha", [l] { return l->truth.alpha; });
    recorder_.AddGroup({n + ".l_est", n + ".phi_est", n + ".alpha_est", n + ".l_est_err",
                        n + ".phi_est_err", n + ".alpha_est_err"},
                       [this, l](double* o) {
                         if (Mode(l->follower) == EstimatorMode::kTruth) return;
                         o[0] = l->used.l, o[1] = l->used.phi, o[2] = l->used.alpha;
                         o[3] = l->used.l - l->truth_conv.l;
                         o[4] = control::WrapToPi(l->used.phi - l->truth_conv.phi);
                         o[5] = control::WrapToPi(l->used.alpha - l->truth_conv.alpha);
                       });
    recorder_.AddGroup({n + ".l_sd", n + ".phi_sd", n + ".alpha_sd", n + ".nees"},
                       [this, l](double* o) {
                         if (Mode(l->follower) != EstimatorMode::kUkf || !l->filter_ready) return;
                         const Eigen::Matrix3d P = l->filter->cov();
                         for (int k = 0; k < 3; ++k) o[k] = std::sqrt(std::max(0.0, P(k, k)));
                         o[3] = l->nees;
                       });
  }
}

}  // namespace formsim::sim::formation
