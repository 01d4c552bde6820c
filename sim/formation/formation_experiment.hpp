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
///   with switching or avoidance: formation.error (the largest |e_l| and |e_φ| over the links of
///                  followers that are not avoiding, against the current desired values)
///   with avoidance, per follower j: j.avoiding (1 while on the obstacle law), j.obstacle_d
///                  (distance of its control point to the nearest obstacle; the reach,
///                  2 (d_s + hysteresis), when none is within it)
/// The estimator is a live tunable, so every follower has its estimate channels from the start.
///
/// Formation switching (switching:): a scheduled entry, the action `switch-formation` (next
/// shape) or `switch-formation:NAME` starts a transition of every slot (formation_switch.hpp);
/// the laws get the desired rates as feed-forward. Obstacle avoidance (avoidance:): each
/// follower's control point is checked against the obstacles' Box2D shapes every control
/// period; within the safety distance it follows obstacle_avoidance.hpp's law.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "control/formation/formation_laws.hpp"
#include "control/formation/link_filter.hpp"
#include "control/formation/link_update_lanes.hpp"
#include "sim/core/error_stats.hpp"
#include "sim/core/experiment.hpp"
#include "sim/core/ring_buffer.hpp"
#include "sim/core/unicycle_drive.hpp"
#include "sim/formation/formation_config.hpp"
#include "sim/formation/formation_edit.hpp"
#include "sim/formation/formation_editing.hpp"
#include "sim/formation/obstacle_distance.hpp"
#include "sim/formation/relative_sensor.hpp"

namespace formsim::sim::formation {

class FormationExperiment : public ExperimentOf<FormationConfig>, public FormationEditing {
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
  void FocusPoints(std::vector<Vec2>& bodies, std::vector<double>& radii,
                   std::vector<Vec2>& trails, double seconds) const override;
  bool TrailBox(double seconds, Vec2& lo, Vec2& hi) const override;
  Metrics Results() const override;
  // ---- FormationEditing (formation_editing.hpp; the changes: formation_edit.hpp) ----
  std::string PlacedText(const std::string& text) const override;
  std::string Restructured(const std::string& text, const StructureChange& change) const override;
  std::string StructureLocked() const override;
  std::vector<std::string> LeadersOf(const std::string& robot) const override;
  /// l-φ: l_des and φ_des of a control point at `p` seen from the leader now; l-l: the two
  /// distances to the leaders now.
  std::vector<std::pair<std::string, std::string>> SlotEdits(const std::string& robot,
                                                             Vec2 p) const override;

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
    ErrorStats nees_l;  ///< e_l² / P_ll after the settle time, while the filter is on
    int filter_faults = 0;
  };
  std::vector<LinkView> Links() const;

  std::vector<ActionSpec> Actions() const override;
  std::string RunAction(const std::string& id) override;

  /// Errors below this count as recovered after a switch (the 1e-2).
  static constexpr double kRecoveredError = 1e-2;
  /// A formation switch, or a follower leaving the obstacle law, and how the formation
  /// recovered from it: the error stayed below kRecoveredError from `time + recover` until the
  /// next switch (`end`).
  struct SwitchRecord {
    double time = 0.0;
    std::string kind;          ///< "formation" or "avoidance_end"
    std::string what;          ///< the target shape, or the follower
    double last_above = -1.0;  ///< last time the error was >= kRecoveredError
    double end = -1.0;         ///< when the next switch began (−1 while open)
    double Recover(double step) const { return last_above < time ? 0.0 : last_above - time + step; }
  };
  const std::vector<SwitchRecord>& switch_records() const { return switches_; }
  /// The shape in force (−1: initial) and whether a transition is running.
  int shape() const { return shape_; }
  bool in_transition() const { return in_transition_; }
  /// The current desired values of robot j.
  const cf::SlotValues& slot(int j) const { return slots_[static_cast<std::size_t>(j)]; }
  bool avoiding(int j) const { return agents_[static_cast<std::size_t>(j)].avoiding; }
  long collisions_after_transient() const { return collisions_after_; }

 protected:
  void Control(double t) override;
  void Sense(double t) override;
  std::size_t PredictItems() const override;
  void Predict(std::size_t begin, std::size_t end) override;
  void DrawScene(DrawSink& draw) const override;
  void ApplyTunables(const FormationConfig& next) override;

 private:
  /// The robots' poses now, for the structural changes (carried into the text once running).
  FormationState EditState() const;
  struct Link {
    Link(std::string n, int i, int j) : name(std::move(n)), leader(i), follower(j) {}
    std::string name;
    int leader = -1, follower = -1;
    bool first = true;  ///< the follower's first link (l_des), else its second (l2_des)
    std::unique_ptr<cf::LinkFilter> filter;
    bool filter_ready = false;
    // The follower's settings this link reads every step, copied here by LinkSettings() so
    // that a step over ten thousand links does not visit ten thousand robot definitions.
    EstimatorMode mode = EstimatorMode::kTruth;
    bool lphi = false;  ///< the follower's law is l-φ
    double sigma_l = 0.0, sigma_phi = 0.0, sigma_alpha = 0.0;
    bool filter_ran = false;  ///< this step ran predict and update (their status below)
    bool predicted = false;   ///< Predict ran beside the world step (its status below)
    control::UkfStatus predict_status = control::UkfStatus::kOk;
    control::UkfStatus status = control::UkfStatus::kOk;
    EventLog::ConditionId fault = 0;
    int fault_count = 0;
    cf::LinkState truth;       ///< physical (Das) state
    cf::LinkState truth_conv;  ///< under the sensor's convention
    cf::LinkState measured, used;
    double nees = 0.0;
    ErrorStats nees_l;  ///< e_l² / P_ll after the settle time, while the filter is on
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
    // Obstacle avoidance (avoidance: enabled).
    bool avoiding = false;
    double avoid_since = 0.0;  ///< time of the last switch of mode
    ObstacleDistance near;     ///< nearest obstacle to the control point this period
    double slot_d = 0.0;       ///< distance of the desired slot's control point to it
  };

  void BuildWorld();
  /// Copies each follower's estimator mode, law and sensor noise into its links (after the
  /// configuration changed).
  void LinkSettings();
  /// Fires due scheduled switches and sets every slot (and its rate) for time t.
  void UpdateSlots(double t);
  /// Starts a transition to `shape` now; "" or why not.
  std::string StartSwitch(int shape, double t, double duration, const std::string& why);
  void OpenRecord(double t, const std::string& kind, const std::string& what);
  /// Avoidance: the command of follower j given its nominal one; raises the switch events.
  cf::Twist Avoid(int j, double t, const cf::Twist& nominal);
  double FormationError() const;
  /// Obstacles are looked for this far from a control point, 2 (d_s + hysteresis): beyond it
  /// they cannot matter.
  double AvoidanceReach() const {
    return 2.0 * (cfg_.avoidance.def.safety_distance + cfg_.avoidance.def.hysteresis);
  }
  void TrackSwitches(double t);
  void DeclareChannels();
  EstimatorMode Mode(int robot) const { return cfg_.robots[robot].follow.estimator; }
  cf::LinkFilterDef FilterDef(int follower) const;
  /// Starts (or restarts after a fault) a link filter: measured components from the
  /// measurement, the others from the truth (first start) or the last estimate (restart).
  void InitFilter(Link& link, bool restart);
  /// A filter step up to its measurement update, which `updates` runs (several links at once in
  /// SIMD lanes); FinishFilter takes its result.
  void RunFilter(Link& link, cf::LinkUpdateBatch& updates);
  void FinishFilter(Link& link);
  /// Everything a step does for one link alone (sensor, filter, statistics), in two halves
  /// around the batched measurement updates: links run in parallel; events are raised
  /// afterwards in link order.
  void SenseLink(std::size_t i, bool filter_step, cf::LinkUpdateBatch& updates);
  void FinishLink(std::size_t i, double t, bool filter_step);
  void Accumulate(Link& link, double t);
  double Gain(double k) const;
  double DesiredL(const Link& l) const;
  Pose2 EstimatedPose(const Agent& a) const;
  Pose2 DesiredPose(int robot) const;
  /// Figures' estimation error of link `n` with its ±2σ band (from the recorded σ).
  void AddEstimationSeries(FigureSpec& est, const std::string& n, int color) const;
  /// Figures' switching and avoidance figures: formation error, distance to obstacles.
  void AddSwitchingFigures(std::vector<FigureSpec>& figs, std::size_t n_robots) const;
  /// Results' per-link metrics and table (errors, estimation, events).
  void AddLinkResults(Metrics& m) const;
  /// Results' switching and avoidance metrics (collisions after the transient, recoveries).
  void AddSwitchResults(Metrics& m) const;
  // The layers of DrawScene, bottom to top (body_px: a body's size on screen; in_view: a point
  // is in the view or near enough to it to be drawn).
  void DrawTrails(DrawSink& draw, double body_px) const;
  /// Desired slots (ghosts) and the leader -> control point links.
  void DrawSlotsAndLinks(DrawSink& draw, double body_px,
                         const std::function<bool(Vec2)>& in_view) const;
  /// Control points M and the links' labels (l, and φ for l-φ links).
  void DrawControlPointsAndLinkLabels(DrawSink& draw, double body_px,
                                      const std::function<bool(Vec2)>& in_view) const;
  /// Each follower's active law (and, while it avoids, its virtual leader).
  void DrawLawTags(DrawSink& draw, double body_px, const std::function<bool(Vec2)>& in_view) const;
  /// Estimated positions and the UKF's 2σ position ellipses.
  void DrawEstimatedPoses(DrawSink& draw, double body_px,
                          const std::function<bool(Vec2)>& in_view) const;
  /// Rings around the robots of recent events.
  void DrawEventFlashes(DrawSink& draw) const;
  /// The optional layers of "what the law sees" (measured arcs, error vectors, l-l triangles,
  /// feed-forward / feedback velocity, formation graph), each when the sink Shows() it.
  void DrawLawOverlays(DrawSink& draw, double body_px,
                       const std::function<bool(Vec2)>& in_view) const;
  // The layers of DrawLawOverlays; j is a follower and m its control point M.
  /// An arrow from each leader to each follower, with the law on the edge.
  void DrawFormationGraph(DrawSink& draw, const std::function<bool(Vec2)>& in_view) const;
  /// The measured l and φ of j's links as arcs (and the estimates the law uses).
  void DrawMeasuredLinks(DrawSink& draw, std::size_t j, Vec2 m) const;
  /// An arrow from M to where M should be, with its length.
  void DrawErrorVector(DrawSink& draw, std::size_t j, Vec2 m) const;
  /// An l-l follower's triangle with its leaders and their singular line, coloured by |sin|.
  void DrawSingularTriangle(DrawSink& draw, const Agent& a, Vec2 m) const;
  /// M's velocity split into feed-forward and feedback arrows.
  void DrawCommandSplit(DrawSink& draw, std::size_t j, Vec2 m) const;
  cf::LinkState ForControl(const Link& link) const;

  std::vector<Agent> agents_;
  std::vector<Link> links_;
  /// Each link's sensor, beside links_ rather than in it: its noise stream's state (2.5 kB)
  /// would spread ten thousand links over ten times the cache lines.
  std::vector<RelativeSensor> sensors_;
  /// Per link: the filter faulted in this step's Sense (written by its task), and its run of
  /// faults is open in the event log.
  std::vector<unsigned char> link_fault_now_, link_faulty_;
  long sense_count_ = 0;
  std::vector<double> error_scratch_;  ///< the links' errors of a recorded row
  // Formation switching.
  std::vector<cf::SlotValues> slots_;  ///< desired values of each robot now
  std::vector<cf::SlotRates> slot_rates_;
  cf::SlotTransition transition_;
  bool in_transition_ = false;
  int shape_ = -1, target_ = -1;  ///< shape in force, shape of the running transition
  std::size_t next_switch_ = 0;   ///< schedule entry armed next
  // Switch records and the metrics of switching and avoidance.
  std::vector<SwitchRecord> switches_;
  long collisions_after_ = 0;
  long avoid_entries_ = 0;
  double formation_error_ = 0.0, max_error_settled_ = 0.0;
};

}  // namespace formsim::sim::formation
