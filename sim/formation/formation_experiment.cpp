#include "sim/formation/formation_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace formsim::sim {

FORMSIM_REGISTER_EXPERIMENT("formation", FormationExperiment);

namespace {

using control::FormationLaw;
using control::LinkState;
using control::Twist;

constexpr double kMinL = 1e-3;  // a distance handed to a law is at least this (noisy raw l)

std::string Fmt(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace

FormationExperiment::FormationExperiment(const ExperimentSetup& setup, YamlReader& root)
    : Experiment(setup) {
  cfg_ = ReadFormationConfig(root, setup.dt);
  control_every_ = static_cast<int>(std::lround(cfg_.control_period / setup.dt));
  bearing_index_ = static_cast<int>(cfg_.bearing);
  gain_reading_index_ = static_cast<int>(cfg_.gain_reading);
  BuildWorld();
  RegisterParams();
  DeclareColumns();
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
    a.drive_mode = static_cast<int>(r.drive.mode);
    a.estimator = a.applied_estimator = static_cast<int>(r.follow.estimator);
  }
  // Links in topological order of their followers, leaders in declaration order.
  for (int j : cfg_.graph.order) {
    for (int i : cfg_.graph.leaders[j]) {
      const std::string name = cfg_.robots[i].body.name + "-" + cfg_.robots[j].body.name;
      links_.emplace_back(name, i, j, RelativeSensor(rng_, name));
      agents_[j].links.push_back(static_cast<int>(links_.size()) - 1);
    }
  }
  for (Link& l : links_) l.filter = control::LinkFilter::Make(FilterDef(agents_[l.follower]));
}

control::LinkFilterDef FormationExperiment::FilterDef(const Agent& a) const {
  const int j = static_cast<int>(&a - agents_.data());
  const FollowerDef& f = cfg_.robots[j].follow;
  const NoiseDef n = EffectiveNoise(cfg_, f);
  const UkfDef& u = cfg_.ukf;
  control::LinkFilterDef d;
  d.measure = f.measure;
  d.Tc = cfg_.control_period;
  d.L = cfg_.L;
  d.q = {u.q_l, u.q_phi, u.q_alpha};
  // R defaults to the sensor's variance, floored so that a noise-free sensor keeps Pyy > 0.
  auto r = [](double given, double sensor) { return std::max(given > 0 ? given : sensor, 1e-10); };
  d.r = {r(u.r_l, n.l.variance()), r(u.r_phi, n.phi.variance()), r(u.r_alpha, n.alpha.variance())};
  d.p0 = {u.p0_l, u.p0_phi, u.p0_alpha};
  d.scaling = {u.alpha, u.beta, u.kappa};
  return d;
}

void FormationExperiment::RegisterParams() {
  params_.AddChoice("formation.gain_reading", "Gains", "gain reading", &gain_reading_index_,
                    {"printed", "per_sample"});
  params_.AddChoice("formation.bearing", "Gains", "bearing convention", &bearing_index_,
                    {"das", "printed"});
  params_.AddDouble("formation.singular_threshold", "Gains", "l-l singular |sin|",
                    &cfg_.singular_threshold, 0.01, 0.5);
  params_.AddDouble("formation.L", "Gains", "control point L", &cfg_.L, 0.05, 0.5, "m");
  params_
      .AddDouble("formation.settle_time", "Gains", "settle time", &cfg_.settle_time, 0.0, 10.0, "s")
      .requires_reset = true;

  auto add_noise = [&](const std::string& prefix, const std::string& group, NoiseDef& n,
                       bool only_present) {
    auto one = [&](const std::string& name, NoiseValue& v) {
      if (only_present && !v.present) return;
      const std::string key = prefix + name + (v.is_variance ? "_variance" : "_sigma");
      const bool angle = name != "l";
      const std::string unit = v.is_variance ? (angle ? "rad²" : "m²") : (angle ? "rad" : "m");
      params_.AddDouble(key, group, name + (v.is_variance ? " variance" : " σ"), &v.value, 0.0,
                        v.is_variance ? 1e-2 : 0.1, unit);
    };
    one("l", n.l);
    one("phi", n.phi);
    one("alpha", n.alpha);
  };
  add_noise("noise.", "Noise/all links", cfg_.noise, false);

  UkfDef& u = cfg_.ukf;
  params_.AddDouble("ukf.q_l", "Estimation/UKF", "Q l", &u.q_l, 1e-12, 1e-2, "m²", true);
  params_.AddDouble("ukf.q_phi", "Estimation/UKF", "Q φ", &u.q_phi, 1e-12, 1e-2, "rad²", true);
  params_.AddDouble("ukf.q_alpha", "Estimation/UKF", "Q α", &u.q_alpha, 1e-12, 1e-2, "rad²", true);
  if (u.r_l > 0)
    params_.AddDouble("ukf.r_l", "Estimation/UKF", "R l", &u.r_l, 1e-12, 1e-2, "m²", true);
  if (u.r_phi > 0)
    params_.AddDouble("ukf.r_phi", "Estimation/UKF", "R φ", &u.r_phi, 1e-12, 1e-2, "rad²", true);
  if (u.r_alpha > 0)
    params_.AddDouble("ukf.r_alpha", "Estimation/UKF", "R α", &u.r_alpha, 1e-12, 1e-2, "rad²",
                      true);
  params_.AddDouble("ukf.p0_l", "Estimation/UKF", "P0 l", &u.p0_l, 1e-12, 1.0, "m²", true)
      .requires_reset = true;
  params_.AddDouble("ukf.p0_phi", "Estimation/UKF", "P0 φ", &u.p0_phi, 1e-12, 1.0, "rad²", true)
      .requires_reset = true;
  params_.AddDouble("ukf.p0_alpha", "Estimation/UKF", "P0 α", &u.p0_alpha, 1e-12, 1.0, "rad²", true)
      .requires_reset = true;
  params_.AddDouble("ukf.alpha", "Estimation/UKF", "sigma spread a", &u.alpha, 1e-3, 1.0)
      .requires_reset = true;
  params_.AddDouble("ukf.beta", "Estimation/UKF", "b", &u.beta, 0.0, 4.0).requires_reset = true;
  params_.AddDouble("ukf.kappa", "Estimation/UKF", "κ", &u.kappa, -2.0, 3.0).requires_reset = true;

  for (std::size_t i = 0; i < cfg_.robots.size(); ++i) {
    FormationRobotDef& r = cfg_.robots[i];
    Agent& a = agents_[i];
    const std::string base = "robots." + r.body.name + ".";
    const std::string gains = "Gains/" + r.body.name;
    if (r.node.law == FormationLaw::kRoot) {
      auto& s = r.schedule;
      if (s.kind != control::LeaderScheduleDef::Kind::kSegments) {
        params_.AddDouble(base + "schedule.v", gains, "leader v", &s.v, 0.0, 5.0, "m/s");
        if (s.kind == control::LeaderScheduleDef::Kind::kSpiral) {
          params_.AddDouble(base + "schedule.accel", gains, "spiral dv/dt", &s.accel, -0.5, 0.5,
                            "m/s²");
          params_.AddDouble(base + "schedule.r0", gains, "spiral R0", &s.r0, 0.2, 10.0, "m");
          params_.AddDouble(base + "schedule.r_rate", gains, "spiral dR/dt", &s.r_rate, 0.0, 2.0,
                            "m/s");
        } else {
          params_.AddDouble(base + "schedule.omega", gains, "leader ω amplitude", &s.omega, 0.0,
                            3.0, "rad/s");
        }
      }
    } else {
      const std::string fb = base + "follow.";
      const bool lphi = r.node.law == FormationLaw::kLPhi;
      params_.AddDouble(fb + "l_des", gains, lphi ? "l desired" : "l1 desired", &r.node.l_des, 0.1,
                        2.0, "m");
      if (lphi) {
        params_.AddDouble(fb + "phi_des", gains, "φ desired", &r.node.phi_des, -control::kPi,
                          2 * control::kPi, "rad");
      } else {
        params_.AddDouble(fb + "l2_des", gains, "l2 desired", &r.node.l2_des, 0.1, 2.0, "m");
      }
      params_.AddDouble(fb + "k_l", gains, lphi ? "k l" : "k l1", &r.follow.k1, 1e-3, 1.0, "",
                        true);
      params_.AddDouble(fb + (lphi ? "k_phi" : "k_l2"), gains, lphi ? "k φ" : "k l2", &r.follow.k2,
                        1e-3, 1.0, "", true);
      params_.AddChoice(fb + "estimator", "Estimation/" + r.body.name, "estimator", &a.estimator,
                        {"truth", "raw", "ukf"});
      add_noise(fb + "noise.", "Noise/" + r.body.name, r.follow.noise, true);
    }
    params_.AddChoice(base + "drive.mode", "Drive/" + r.body.name, "mode", &a.drive_mode,
                      {"ideal", "traction"});
    params_.AddDouble(base + "drive.v_max", "Drive/" + r.body.name, "v max", &a.drive->def().v_max,
                      0.1, 10.0, "m/s");
    params_.AddDouble(base + "drive.omega_max", "Drive/" + r.body.name, "ω max",
                      &a.drive->def().omega_max, 0.1, 20.0, "rad/s");
  }
}

void FormationExperiment::OnParamsChanged() {
  cfg_.gain_reading = static_cast<control::GainReading>(gain_reading_index_);
  cfg_.bearing = static_cast<control::BearingConvention>(bearing_index_);
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    Agent& a = agents_[i];
    a.drive->def().mode = static_cast<UnicycleDriveDef::Mode>(a.drive_mode);
    cfg_.robots[i].follow.estimator = static_cast<EstimatorMode>(a.estimator);
    // A follower switched to the UKF starts its filters from the current measurement.
    if (a.estimator != a.applied_estimator) {
      for (int li : a.links) links_[li].filter_ready = false;
      a.applied_estimator = a.estimator;
    }
    for (int li : a.links) links_[li].filter->Retune(FilterDef(a));
  }
}

double FormationExperiment::Gain(double k) const {
  return control::EffectiveGain(k, cfg_.gain_reading, cfg_.control_period);
}

LinkState FormationExperiment::ForControl(const Link& link) const {
  const EstimatorMode mode = cfg_.robots[link.follower].follow.estimator;
  LinkState s = mode == EstimatorMode::kTruth ? link.truth_conv
                : mode == EstimatorMode::kRaw ? link.measured
                                              : link.used;
  s.l = std::max(s.l, kMinL);
  return s;
}

void FormationExperiment::Control(double t) {
  if (steps() % control_every_ != 0) return;
  for (int j : cfg_.graph.order) {
    const FormationRobotDef& r = cfg_.robots[j];
    Agent& a = agents_[j];
    Twist cmd;
    if (r.node.law == FormationLaw::kRoot) {
      cmd = control::ScheduleAt(r.schedule, t);
    } else if (r.node.law == FormationLaw::kLPhi) {
      const Link& l = links_[a.links[0]];
      cmd = control::LPhiControl(ForControl(l), agents_[l.leader].cmd, r.node.l_des, r.node.phi_des,
                                 {Gain(r.follow.k1), Gain(r.follow.k2)}, cfg_.L);
    } else {
      const Link& l1 = links_[a.links[0]];
      const Link& l2 = links_[a.links[1]];
      const control::LLCommand c = control::LLControl(
          ForControl(l1), ForControl(l2), agents_[l1.leader].cmd, agents_[l2.leader].cmd,
          r.node.l_des, r.node.l2_des, {Gain(r.follow.k1), Gain(r.follow.k2)}, cfg_.L,
          cfg_.singular_threshold);
      cmd = c.cmd;
      // One event per entry into the singular band.
      if (c.singular && !a.singular) {
        AddEvent("singular",
                 cfg_.robots[l1.leader].body.name + "," + cfg_.robots[l2.leader].body.name + "," +
                     r.body.name,
                 r.body.name + " near the line through " + cfg_.robots[l1.leader].body.name +
                     " and " + cfg_.robots[l2.leader].body.name +
                     " (|sin| = " + Fmt("%.3f", std::abs(c.sin_angle)) + " < " +
                     Fmt("%.3g", cfg_.singular_threshold) + "), regularised inverse in use");
      }
      a.singular = c.singular;
    }
    a.drive->SetCommand(cmd.v, cmd.w);
    a.cmd = {a.drive->v_command(), a.drive->omega_command()};
  }
}

void FormationExperiment::InitFilter(Link& link, bool restart) {
  // Measured components start from the measurement; the others from the true value on the first
  // start (the paper gives s(0) as known; l optionally offset by l0_error) and from the last
  // estimate after a fault.
  const control::MeasurementSet m = cfg_.robots[link.follower].follow.measure;
  LinkState x0 = link.measured;
  if (m != control::MeasurementSet::kLPhiAlpha)
    x0.l = restart ? link.used.l : link.truth_conv.l + cfg_.ukf.l0_error;
  if (m == control::MeasurementSet::kAlpha) x0.phi = restart ? link.used.phi : link.truth_conv.phi;
  x0.l = std::max(x0.l, kMinL);
  const control::LinkFilterDef d = FilterDef(agents_[link.follower]);
  link.filter->Reset(x0, Eigen::Matrix3d(d.p0.asDiagonal()));
  link.filter_ready = true;
  link.used = link.filter->state();
}

void FormationExperiment::RunFilter(Link& link, double t) {
  if (!link.filter_ready) {
    InitFilter(link, false);
    return;
  }
  control::UkfStatus st =
      link.filter->Predict(agents_[link.leader].cmd, agents_[link.follower].cmd);
  if (st == control::UkfStatus::kOk) st = link.filter->Update(link.measured);
  if (st != control::UkfStatus::kOk) {
    // One event per entry into a run of faults; every fault is counted for the summary.
    ++link.fault_count;
    if (!link.fault_active)
      AddEvent("filter_fault", cfg_.robots[link.follower].body.name,
               "UKF of link " + link.name + " at t = " + Fmt("%.3f", t) +
                   " s: " + control::UkfStatusName(st) + "; restarted with P0");
    link.fault_active = true;
    InitFilter(link, true);
    return;
  }
  link.fault_active = false;
  link.used = link.filter->state();
}

void FormationExperiment::Sense(double t) {
  const bool filter_step = steps() % control_every_ == 0;
  for (Agent& a : agents_) {
    a.saturated = a.drive->saturated();
    if (a.saturated && !a.was_saturated)
      AddEvent("saturation", a.robot->name(),
               a.drive->slipping() ? a.robot->name() + " slips (traction limit)"
                                   : a.robot->name() + " command clamped to the drive limits");
    a.was_saturated = a.saturated;
    if (cfg_.trail_length > 0 && sense_count_ % cfg_.trail_every == 0) {
      a.trail.push_back(a.robot->pose().p());
      while (static_cast<int>(a.trail.size()) > cfg_.trail_length) a.trail.pop_front();
    }
  }
  for (Link& l : links_) {
    const Pose2 pi = agents_[l.leader].robot->pose(), pj = agents_[l.follower].robot->pose();
    const EstimatorMode mode = cfg_.robots[l.follower].follow.estimator;
    if (mode == EstimatorMode::kTruth) {
      // Nobody reads the measurement: skip the noise draws (this link's stream only).
      l.truth_conv = control::ComputeLinkState(pi, pj, cfg_.L, cfg_.bearing);
      l.measured = l.truth_conv;
    } else {
      const NoiseDef n = EffectiveNoise(cfg_, cfg_.robots[l.follower].follow);
      l.measured = l.sensor.Sample(pi, pj, cfg_.L, cfg_.bearing, n.l.sigma(), n.phi.sigma(),
                                   n.alpha.sigma(), l.truth_conv);
    }
    l.truth = cfg_.bearing == control::BearingConvention::kDas
                  ? l.truth_conv
                  : control::ComputeLinkState(pi, pj, cfg_.L, control::BearingConvention::kDas);
    if (filter_step) {
      if (mode == EstimatorMode::kUkf)
        RunFilter(l, t);
      else if (mode == EstimatorMode::kRaw)
        l.used = l.measured;
      else
        l.used = l.truth_conv;
    }
    Accumulate(l, t);
  }
  // The l-l determinant sin(γ_kj − γ_ij) from the states the law will use (recorded as sin_ll).
  for (Agent& a : agents_) {
    if (a.links.size() != 2) continue;
    a.sin_ll =
        std::sin(ForControl(links_[a.links[1]]).gamma() - ForControl(links_[a.links[0]]).gamma());
  }
  ++sense_count_;
}

void FormationExperiment::Accumulate(Link& l, double t) {
  const FormationRobotDef& r = cfg_.robots[l.follower];
  const bool settled = t >= cfg_.settle_time - 1e-9;
  const bool first = agents_[l.follower].links[0] == static_cast<int>(&l - links_.data());
  const double l_des = first ? r.node.l_des : r.node.l2_des;
  l.e_l.Add(l_des - l.truth.l, settled);
  if (r.node.law == FormationLaw::kLPhi)
    l.e_phi.Add(control::WrapToPi(r.node.phi_des - l.truth.phi), settled);
  l.e_alpha.Add(l.truth.alpha, settled);
  const EstimatorMode mode = r.follow.estimator;
  if (mode == EstimatorMode::kTruth || steps() % control_every_ != 0) return;
  const Eigen::Vector3d e(l.used.l - l.truth_conv.l,
                          control::WrapToPi(l.used.phi - l.truth_conv.phi),
                          control::WrapToPi(l.used.alpha - l.truth_conv.alpha));
  l.est_l.Add(e(0));
  l.est_phi.Add(e(1));
  l.est_alpha.Add(e(2));
  if (mode == EstimatorMode::kUkf) {
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(l.filter->cov());
    l.nees = e.dot(ldlt.solve(e));
  }
}

void FormationExperiment::DeclareColumns() {
  recorder_.AddColumn("t");
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    Agent& a = agents_[i];
    const std::string& n = a.robot->name();
    a.c_x = recorder_.AddColumn(n + ".x");
    recorder_.AddColumn(n + ".y");
    recorder_.AddColumn(n + ".theta");
    a.c_v = recorder_.AddColumn(n + ".v_cmd");
    recorder_.AddColumn(n + ".w_cmd");
    a.c_sat = recorder_.AddColumn(n + ".sat");
    const FormationRobotDef& r = cfg_.robots[i];
    if (r.node.law != FormationLaw::kRoot && r.follow.estimator != EstimatorMode::kTruth) {
      a.c_est = recorder_.AddColumn(n + ".x_est");
      recorder_.AddColumn(n + ".y_est");
      recorder_.AddColumn(n + ".theta_est");
    }
    if (r.node.law == FormationLaw::kLL) a.c_sin = recorder_.AddColumn(n + ".sin_ll");
  }
  for (Link& l : links_) {
    const FormationRobotDef& r = cfg_.robots[l.follower];
    const std::string& n = l.name;
    l.c_l = recorder_.AddColumn(n + ".l");
    l.c_phi = recorder_.AddColumn(n + ".phi");
    l.c_alpha = recorder_.AddColumn(n + ".alpha");
    l.c_l_des = recorder_.AddColumn(n + ".l_des");
    if (r.node.law == FormationLaw::kLPhi) l.c_phi_des = recorder_.AddColumn(n + ".phi_des");
    l.c_e_l = recorder_.AddColumn(n + ".e_l");
    if (r.node.law == FormationLaw::kLPhi) l.c_e_phi = recorder_.AddColumn(n + ".e_phi");
    l.c_e_alpha = recorder_.AddColumn(n + ".e_alpha");
    if (r.follow.estimator != EstimatorMode::kTruth) {
      l.c_est = recorder_.AddColumn(n + ".l_est");
      recorder_.AddColumn(n + ".phi_est");
      recorder_.AddColumn(n + ".alpha_est");
      l.c_est_err = recorder_.AddColumn(n + ".l_est_err");
      recorder_.AddColumn(n + ".phi_est_err");
      recorder_.AddColumn(n + ".alpha_est_err");
    }
    if (r.follow.estimator == EstimatorMode::kUkf) {
      l.c_sd = recorder_.AddColumn(n + ".l_sd");
      recorder_.AddColumn(n + ".phi_sd");
      recorder_.AddColumn(n + ".alpha_sd");
      l.c_nees = recorder_.AddColumn(n + ".nees");
    }
  }
}

Pose2 FormationExperiment::EstimatedPose(const Agent& a) const {
  const Link& l = links_[a.links[0]];
  return control::FollowerPoseFromLink(agents_[l.leader].robot->pose(), l.used, cfg_.L);
}

void FormationExperiment::Record(Recorder& rec) {
  rec.Set(0, time());
  for (const Agent& a : agents_) {
    const Pose2 p = a.robot->pose();
    rec.Set(a.c_x, p.x);
    rec.Set(a.c_x + 1, p.y);
    rec.Set(a.c_x + 2, p.theta);
    rec.Set(a.c_v, a.cmd.v);
    rec.Set(a.c_v + 1, a.cmd.w);
    rec.Set(a.c_sat, a.saturated ? 1.0 : 0.0);
    if (a.c_est >= 0) {
      const Pose2 e = EstimatedPose(a);
      rec.Set(a.c_est, e.x);
      rec.Set(a.c_est + 1, e.y);
      rec.Set(a.c_est + 2, e.theta);
    }
    if (a.c_sin >= 0) rec.Set(a.c_sin, a.sin_ll);
  }
  for (const Link& l : links_) {
    const FormationRobotDef& r = cfg_.robots[l.follower];
    const bool first = agents_[l.follower].links[0] == static_cast<int>(&l - links_.data());
    const double l_des = first ? r.node.l_des : r.node.l2_des;
    rec.Set(l.c_l, l.truth.l);
    rec.Set(l.c_phi, l.truth.phi);
    rec.Set(l.c_alpha, l.truth.alpha);
    rec.Set(l.c_l_des, l_des);
    rec.Set(l.c_e_l, l_des - l.truth.l);
    rec.Set(l.c_e_alpha, l.truth.alpha);
    if (l.c_phi_des >= 0) {
      rec.Set(l.c_phi_des, r.node.phi_des);
      rec.Set(l.c_e_phi, control::WrapToPi(r.node.phi_des - l.truth.phi));
    }
    if (l.c_est >= 0) {
      rec.Set(l.c_est, l.used.l);
      rec.Set(l.c_est + 1, l.used.phi);
      rec.Set(l.c_est + 2, l.used.alpha);
      rec.Set(l.c_est_err, l.used.l - l.truth_conv.l);
      rec.Set(l.c_est_err + 1, control::WrapToPi(l.used.phi - l.truth_conv.phi));
      rec.Set(l.c_est_err + 2, control::WrapToPi(l.used.alpha - l.truth_conv.alpha));
    }
    if (l.c_sd >= 0) {
      const Eigen::Matrix3d P = l.filter->cov();
      for (int k = 0; k < 3; ++k) rec.Set(l.c_sd + k, std::sqrt(std::max(0.0, P(k, k))));
      rec.Set(l.c_nees, l.nees);
    }
  }
}

}  // namespace formsim::sim
