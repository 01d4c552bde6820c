#pragma once
/// \file The cascade leader-follower formation of paper 000 as an Experiment (type "formation"):
/// root leaders on open-loop schedules, followers with the l-φ or l-l law, a relative sensor and
/// (optionally) a UKF per link, any graph.
///
/// Step order: Control(t) computes commands in topological order (a follower uses its leaders'
/// commands of the same step as feed-forward) from the link states chosen by each follower's
/// estimator mode; the world steps; Sense(t+dt) samples every link sensor and, on filter steps,
/// runs each link UKF (predict with the commands applied during the last period, update with the
/// new measurement), so the recorded row at t holds truth, measurement and estimate of the same
/// instant.
///
/// Recorder columns (names are stable; documented here once):
///   t
///   per robot R:   R.x R.y R.theta (true pose)   R.v_cmd R.w_cmd (command after the drive's
///                  limits)   R.sat (1 when the drive limited the command or slipped)
///                  R.x_est R.y_est R.theta_est (followers with estimator raw|ukf: the pose
///                  implied by the estimate of the link to the first leader and that leader's
///                  true pose)
///   per link i-j:  .l .phi .alpha (true; φ always in the Das convention, i.e. the physical
///                  bearing in the leader's frame)   .l_des (.phi_des for l-φ)
///                  .e_l = l_des − l   (.e_phi = wrap(φ_des − φ) for l-φ)   .e_alpha = α
///                  (the paper's error definitions, section 2.2)
///                  raw|ukf only: .l_est .phi_est .alpha_est (what the controller used) and
///                  .l_est_err .phi_est_err .alpha_est_err (estimate − truth under the sensor's
///                  convention)
///                  ukf only: .l_sd .phi_sd .alpha_sd (square roots of the diagonal of P) and
///                  .nees (normalised estimation error squared, 3 dof)
///   per l-l follower j: j.sin_ll (sin(γ_kj − γ_ij) of the law; 0 on the singular line)

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "control/formation/formation_laws.hpp"
#include "control/formation/link_filter.hpp"
#include "sim/core/error_stats.hpp"
#include "sim/core/experiment.hpp"
#include "sim/core/unicycle_drive.hpp"
#include "sim/formation/formation_config.hpp"
#include "sim/formation/relative_sensor.hpp"

namespace formsim::sim {

class FormationExperiment : public Experiment {
 public:
  FormationExperiment(const ExperimentSetup& setup, YamlReader& root);

  std::vector<FigureSpec> Figures() const override;
  std::vector<TableSpec> Tables() const override;
  void Bounds(Vec2& lo, Vec2& hi) const override;
  Json Summary() const override;
  std::string SummaryTable() const override;

  /// Read-only views for tests and benchmarks.
  struct LinkView {
    std::string name;  ///< "R1-R2"
    int leader = -1, follower = -1;
    control::LinkState truth, measured, used;
    SettledErrorStats e_l, e_phi, e_alpha;
    ErrorStats est_l, est_phi, est_alpha;
    bool has_phi_target = false;
    const control::LinkFilter* filter = nullptr;
    double nees = 0.0;
    int filter_faults = 0;
  };
  std::vector<LinkView> Links() const;
  const FormationConfig& config() const { return cfg_; }

 protected:
  void Control(double t) override;
  void Sense(double t) override;
  void Record(Recorder& rec) override;
  void DrawScene(DrawSink& draw) const override;
  void OnParamsChanged() override;

 private:
  struct Link {
    Link(std::string n, int i, int j, RelativeSensor s)
        : name(std::move(n)), leader(i), follower(j), sensor(std::move(s)) {}
    std::string name;
    int leader = -1, follower = -1;
    RelativeSensor sensor;
    std::unique_ptr<control::LinkFilter> filter;
    bool filter_ready = false;
    bool fault_active = false;  ///< the last filter step faulted (events on entry only)
    int fault_count = 0;
    control::LinkState truth;       ///< physical (Das) state
    control::LinkState truth_conv;  ///< under the sensor's convention
    control::LinkState measured, used;
    double nees = 0.0;
    SettledErrorStats e_l, e_phi, e_alpha;
    ErrorStats est_l, est_phi, est_alpha;
    // Recorder columns.
    int c_l = -1, c_phi = -1, c_alpha = -1, c_l_des = -1, c_phi_des = -1, c_e_l = -1, c_e_phi = -1,
        c_e_alpha = -1;
    int c_est = -1, c_est_err = -1, c_sd = -1, c_nees = -1;  ///< first of 3 (1 for nees)
  };
  struct Agent {
    Robot* robot = nullptr;
    UnicycleDrive* drive = nullptr;
    std::vector<int> links;  ///< indices into links_, in leader order
    control::Twist cmd;      ///< command of the current period (after the drive's limits)
    bool saturated = false, was_saturated = false;
    bool singular = false;
    double sin_ll = 1.0;
    int drive_mode = 0;  ///< mirror of the drive mode for the parameter table
    int estimator = 0;   ///< mirror of follow.estimator for the parameter table
    int applied_estimator = 0;
    std::deque<Vec2> trail;
    int c_x = -1, c_v = -1, c_sat = -1, c_est = -1, c_sin = -1;
  };

  void BuildWorld();
  void RegisterParams();
  void DeclareColumns();
  control::LinkFilterDef FilterDef(const Agent& a) const;
  /// Starts (or restarts after a fault) a link filter: measured components from the
  /// measurement, the others from the truth (first start) or the last estimate (restart).
  void InitFilter(Link& link, bool restart);
  void RunFilter(Link& link, double t);
  void Accumulate(Link& link, double t);
  double Gain(double k) const;
  Pose2 EstimatedPose(const Agent& a) const;
  Pose2 DesiredPose(int robot) const;
  control::LinkState ForControl(const Link& link) const;

  FormationConfig cfg_;
  std::vector<Agent> agents_;
  std::vector<Link> links_;
  int control_every_ = 1;
  long sense_count_ = 0;
  int bearing_index_ = 0, gain_reading_index_ = 0;
};

}  // namespace formsim::sim
