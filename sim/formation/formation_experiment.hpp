#pragma once
/// \file The cascade leader-follower formation of paper 000 as an Experiment (type "formation"):
/// root leaders on open-loop schedules, followers with the l-φ or l-l law, a relative sensor and
/// (optionally) a UKF per link, any graph.
///
/// Step order: Control(t) prepares every follower's law from its links' states (in parallel),
/// then computes commands in topological order (a follower uses its leaders' commands of the
/// same step as feed-forward) from the link states chosen by each follower's
/// estimator mode; the world steps; Sense(t+dt) samples every link sensor and, on filter steps,
/// runs each link UKF (predict with the commands applied during the last period, update with the
/// new measurement), so the recorded row at t holds truth, measurement and estimate of the same
/// instant.
///
/// Recorder channels (names are stable; declared in DeclareChannels):
///   t
///   per robot R:   R.x R.y R.theta (true pose)   R.v_cmd R.w_cmd (command after the drive's
///                  limits)   R.sat (1 when the drive limited the command or slipped)
///                  followers: R.x_est R.y_est R.theta_est (the pose implied by the estimate of
///                  the link to the first leader and that leader's true pose; empty while the
///                  follower uses the truth)
///   per link i-j:  .l .phi .alpha (true; φ always in the Das convention, i.e. the physical
///                  bearing in the leader's frame)   .l_des (.phi_des for l-φ)
///                  .e_l = l_des − l   (.e_phi = wrap(φ_des − φ) for l-φ)   .e_alpha = α
///                  (the paper's error definitions, section 2.2)
///                  .l_est .phi_est .alpha_est (what the controller used) and .l_est_err
///                  .phi_est_err .alpha_est_err (estimate − truth under the sensor's
///                  convention): while the estimator is raw or ukf
///                  .l_sd .phi_sd .alpha_sd (square roots of the diagonal of P) and .nees
///                  (normalised estimation error squared, 3 dof): while the estimator is ukf
///   per l-l follower j: j.sin_ll (sin(γ_kj − γ_ij) of the law; 0 on the singular line)
///   more links than the figures show (kManyLinks):  links.max_abs_e_l, links.median_abs_e_l
///                  (over every link), and links.max_abs_e_phi over the l-φ links
/// The estimator is a live tunable, so every follower has its estimate channels from the start.

#include <memory>
#include <string>
#include <vector>

#include "control/formation/formation_laws.hpp"
#include "control/formation/link_filter.hpp"
#include "sim/core/error_stats.hpp"
#include "sim/core/experiment.hpp"
#include "sim/core/ring_buffer.hpp"
#include "sim/core/unicycle_drive.hpp"
#include "sim/formation/formation_config.hpp"
#include "sim/formation/relative_sensor.hpp"

namespace formsim::sim::formation {

class FormationExperiment : public ExperimentOf<FormationConfig> {
 public:
  /// Figures show at most this many robots' or links' series; a larger formation also records
  /// the largest and median errors over all its links (and plots them).
  static constexpr std::size_t kManyLinks = 12;
  static FormationConfig ReadConfig(YamlReader& root, const ExperimentSetup& setup) {
    return ReadFormationConfig(root, setup.dt);
  }
  FormationExperiment(const ExperimentSetup& setup, const FormationConfig& config);

  std::vector<FigureSpec> Figures() const override;
  void Bounds(Vec2& lo, Vec2& hi) const override;
  Metrics Results() const override;

  /// Read-only views for tests and benchmarks.
  struct LinkView {
    std::string name;  ///< "R1-R2"
    int leader = -1, follower = -1;
    cf::LinkState truth, measured, used;
    SettledErrorStats e_l, e_phi, e_alpha;
    ErrorStats est_l, est_phi, est_alpha;
    bool has_phi_target = false;
    const cf::LinkFilter* filter = nullptr;
    double nees = 0.0;
    int filter_faults = 0;
  };
  std::vector<LinkView> Links() const;

 protected:
  void Control(double t) override;
  void Sense(double t) override;
  void DrawScene(DrawSink& draw) const override;
  void ApplyTunables(const FormationConfig& next) override;

 private:
  struct Link {
    Link(std::string n, int i, int j, RelativeSensor s)
        : name(std::move(n)), leader(i), follower(j), sensor(std::move(s)) {}
    std::string name;
    int leader = -1, follower = -1;
    bool first = true;  ///< the follower's first link (l_des), else its second (l2_des)
    RelativeSensor sensor;
    std::unique_ptr<cf::LinkFilter> filter;
    bool filter_ready = false;
    bool filter_ran = false;  ///< this step ran predict and update (their status below)
    control::UkfStatus status = control::UkfStatus::kOk;
    EventLog::ConditionId fault = 0;
    int fault_count = 0;
    cf::LinkState truth;       ///< physical (Das) state
    cf::LinkState truth_conv;  ///< under the sensor's convention
    cf::LinkState measured, used;
    double nees = 0.0;
    SettledErrorStats e_l, e_phi, e_alpha;
    ErrorStats est_l, est_phi, est_alpha;
    bool ever_ukf = false;
  };
  struct Agent {
    Robot* robot = nullptr;
    UnicycleDrive* drive = nullptr;
    std::vector<int> links;  ///< indices into links_, in leader order
    cf::Twist cmd;           ///< command of the current period (after the drive's limits)
    cf::LPhiPrepared lphi;   ///< this period's law before the leaders' commands (l-φ)
    cf::LLPrepared ll;       ///< (l-l)
    bool saturated = false;
    EventLog::ConditionId saturation = 0, singular = 0;
    double sin_ll = 1.0;
    RingBuffer<Vec2> trail;
  };

  void BuildWorld();
  void DeclareChannels();
  EstimatorMode Mode(int robot) const { return cfg_.robots[robot].follow.estimator; }
  cf::LinkFilterDef FilterDef(int follower) const;
  /// Starts (or restarts after a fault) a link filter: measured components from the
  /// measurement, the others from the truth (first start) or the last estimate (restart).
  void InitFilter(Link& link, bool restart);
  void RunFilter(Link& link);
  /// Everything a step does for one link alone (sensor, filter, statistics): links run in
  /// parallel; events are raised afterwards in link order.
  void SenseLink(Link& link, double t, bool filter_step);
  void Accumulate(Link& link, double t);
  double Gain(double k) const;
  double DesiredL(const Link& l) const;
  Pose2 EstimatedPose(const Agent& a) const;
  Pose2 DesiredPose(int robot) const;
  cf::LinkState ForControl(const Link& link) const;

  std::vector<Agent> agents_;
  std::vector<Link> links_;
  long sense_count_ = 0;
  std::vector<double> error_scratch_;  ///< the links' errors of a recorded row
};

}  // namespace formsim::sim::formation
