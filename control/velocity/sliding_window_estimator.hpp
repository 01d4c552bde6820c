#pragma once
/// \file Sliding-window nonlinear least-squares fusion of camera bearings, wheel odometry and
/// IMU (paper 004, section 1; VINS-Mono structure), planar.
///
/// Variables: for each keyframe in the window a KeyframeState (pose x, y, θ; world velocity;
/// gyro and accelerometer biases; odometry speed and yaw-rate biases), and for every landmark
/// tracked since a keyframe still in the window either its inverse-depth form (the default;
/// the paper, like VINS-Mono, holds feature inverse depths) or its 2-D world position
/// (`landmarks`). Residuals: IMU pre-integration and odometry pre-integration between
/// consecutive keyframes (with bias random walks), bearings of the landmarks, an optional
/// non-holonomic (no side-slip) constraint, and a marginalisation prior. The window is solved by
/// Levenberg-Marquardt on the dense normal equations with exact analytic Jacobians (checked
/// against finite differences in the tests).
///
/// Inverse depth: a landmark is anchored at the first keyframe in the window that saw it and
/// held as (ψ, ρ), the bearing of its ray from the anchor's camera and the inverse of its
/// distance along it (Civera, Davison and Montiel's parameterisation, in the plane); every
/// bearing, the anchor's too, is a residual. Before the anchor keyframe is marginalised the
/// landmark moves to the next keyframe in the window that saw it, by an exact change of
/// variables (the point does not move); if the prior already holds its (ψ, ρ), the prior is
/// carried over by the same change of variables, linearised. VINS-Mono's one-number form (ρ
/// along the anchor's measured bearing, the anchor's bearing taken as exact) was tried first:
/// in this planar, constant-speed setting, where neither the IMU nor the biased odometry
/// observes scale, each change of anchor re-used a noisy bearing as exact and the visual scale
/// shrank in proportion to the bearing noise: by 10-30 % over 30 s at 2 mrad (visual-inertial,
/// straight synthetic run; VINS-Mono's marginalise-the-depth-with-its-anchor scheme and the
/// re-anchoring above respectively), and velocity_constant's fused speed RMSE went from 0.005 to
/// 0.035-0.14 m/s.
///
/// The paper's one-number form ships as `kInverseDepth1d`, as VINS-Mono does it: ρ along the
/// anchor's measured bearing (the anchor's own bearing is no residual); when the anchor keyframe
/// is marginalised, the ρ of the landmarks it anchors are marginalised with it (their
/// information goes into the prior on the keyframes), and a landmark still tracked restarts at
/// the next keyframe that saw it, along that keyframe's measured bearing at the depth (along the
/// optical axis) of its last estimate, with no prior (VINS-Mono's removeBackShiftDepth).
///
/// Marginalisation (VINS-Mono's "marginalise old"): when the window is full, the oldest keyframe
/// is removed; every factor touching it (the prior, IMU and odometry to the next keyframe, its
/// non-holonomic constraint and its bearings) is linearised and folded by a Schur complement
/// into a Gaussian prior on the variables it was connected to (keyframes and landmarks):
///   H* = H_kk - H_km H_mm⁺ H_mk,   g* = g_k - H_km H_mm⁺ g_m,
/// kept as (H*, g*, x_lin) and applied as g* + H* (x - x_lin). Landmarks therefore live on as
/// long as they are tracked (their depth keeps improving with the baseline, which is what holds
/// the visual scale); a landmark the window no longer sees is marginalised out of the prior.
/// H* is symmetrised as ½(H* + H*ᵀ) only: a Schur complement of a positive semi-definite matrix
/// is positive semi-definite, and the round-off that could make an eigenvalue slightly negative
/// is far below the information every direction also gets from the window's factors (tests
/// check the prior's spectrum over long runs and the prior against the dense Schur complement).
///
/// Why hand-written rather than Ceres: the problem is planar and small (≤ 10 keyframes × 10
/// states + a few dozen landmarks of two numbers each, about 200 unknowns), so a dense LDLT
/// solve costs well under a millisecond; the angles are plain numbers (SO(2) is commutative, no
/// local parameterisation needed); and the marginalisation prior needs the same linearised H and g
/// that the solver already builds. Ceres would add a large dependency (and its build time on
/// CI) for an automatic-differentiation and sparse-solver machinery this size does not need.
/// The result is the same Gauss-Newton / LM step Ceres' dense solver would take.

#include <deque>
#include <map>
#include <string>
#include <vector>

#include "control/velocity/imu_preintegration.hpp"
#include "control/velocity/keyframe_state.hpp"
#include "control/velocity/odometry_preintegration.hpp"

namespace formsim::control::velocity {

/// One camera measurement: the bearing (rad, in the camera frame, CCW from the optical axis)
/// of landmark `id` (the tracker's association).
struct BearingObservation {
  int id = 0;
  double bearing = 0.0;
};

/// How the window holds landmarks.
enum class LandmarkParam {
  kInverseDepth,   ///< (ψ, ρ): ray bearing and inverse depth from the anchor keyframe
  kWorldPoint,     ///< 2-D world position
  kInverseDepth1d  ///< ρ alone, along the anchor's measured bearing (the paper's, VINS-Mono's)
};

/// Estimator settings, Box2D-style with defaults.
struct SlidingWindowDef {
  int window_size = 8;           ///< keyframes kept after each update
  bool use_odometry = true;      ///< false: visual-inertial only (the VINS-Mono baseline)
  bool use_nonholonomic = true;  ///< lateral body velocity ≈ 0 (wheeled robot)
  LandmarkParam landmarks = LandmarkParam::kInverseDepth;
  ImuNoise imu;
  OdometryNoise odometry;
  double bearing_sigma = 0.003;      ///< rad
  double camera_offset = 0.0;        ///< camera ahead of the body origin, m
  double nonholonomic_sigma = 0.05;  ///< m/s
  double min_parallax = 0.05;        ///< rad, to initialise a landmark
  double min_depth = 0.2;            ///< m
  double max_landmark_range = 20.0;  ///< m
  int max_iterations = 10;
  double initial_lambda = 0.0;  ///< LM damping of the first step (0: Gauss-Newton)
  /// Re-integrate a pre-integration when the bias estimate moved more than this from its
  /// linearisation point (gyro rad/s, accelerometer m/s², odometry m/s and rad/s).
  double repropagate_gyro_bias = 0.01, repropagate_accel_bias = 0.05;
  double repropagate_speed_bias = 0.05, repropagate_yaw_rate_bias = 0.05;
  /// Prior on the first keyframe (the start state is known up to these standard deviations).
  double prior_position_sigma = 1e-3, prior_heading_sigma = 1e-3, prior_velocity_sigma = 0.01;
  double prior_gyro_bias_sigma = 0.02, prior_accel_bias_sigma = 0.1;
  double prior_speed_bias_sigma = 0.1, prior_yaw_rate_bias_sigma = 0.1;
};
inline SlidingWindowDef DefaultSlidingWindowDef() {
  return SlidingWindowDef{};
}

/// What one update did.
struct UpdateReport {
  bool ok = true;
  std::string message;  ///< the fault when !ok
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;
  int landmarks = 0;     ///< landmarks in the optimisation
  int observations = 0;  ///< bearing residuals in the optimisation
  bool marginalised = false;
};

class SlidingWindowEstimator {
 public:
  explicit SlidingWindowEstimator(const SlidingWindowDef& def = DefaultSlidingWindowDef());

  /// Starts (or restarts) the window with a first keyframe whose state is known up to the prior
  /// sigmas of the definition, with the bearings observed at that instant.
  void Initialize(const KeyframeState& first, const std::vector<BearingObservation>& obs);
  bool initialized() const { return !frames_.empty(); }

  /// High-rate inputs, accumulated since the newest keyframe. Each sample covers the `dt`
  /// seconds before it arrives. When a keyframe falls inside a sample's interval, the last
  /// sample is held up to the keyframe time and the next one counts only after it, so sensor
  /// rates need not divide the keyframe rate.
  void AddImu(double dt, double gyro, const Vec2d& accel);
  void AddOdometry(double dt, double speed, double yaw_rate);

  /// Adds a keyframe at time t with its bearings, optimises the window and marginalises the
  /// oldest keyframe when the window is full. On a numerical fault the window restarts from
  /// the last good estimate and the report says why (never NaN states).
  UpdateReport AddKeyframe(double t, const std::vector<BearingObservation>& obs);

  /// Runs the solver again on the current window without new data (diagnostics and tests: right
  /// after a converged update and its marginalisation, this must not move the estimate).
  UpdateReport Reoptimize();

  const KeyframeState& latest() const { return frames_.back(); }
  /// The newest keyframe propagated with the IMU samples received since (VINS-style output).
  KeyframeState Propagated() const;
  const std::deque<KeyframeState>& window() const { return frames_; }

  /// A landmark for display: its position when initialised, and whether the newest keyframe saw it.
  struct LandmarkView {
    int id = 0;
    bool initialized = false;
    Vec2d position = Vec2d::Zero();
    int observations = 0;
    bool seen_in_latest = false;
  };
  std::vector<LandmarkView> Landmarks() const;

  /// Settings; noise edits take effect for the factors built from now on. The landmark
  /// parameterisation may only change before Initialize().
  SlidingWindowDef& def() { return def_; }
  const SlidingWindowDef& def() const { return def_; }

 private:
  friend struct SlidingWindowProbe;  ///< tests: the normal equations and the prior

  struct Track {
    std::vector<std::pair<long, double>> obs;  ///< (keyframe id, bearing), ordered by id
    bool initialized = false;
    Vec2d position = Vec2d::Zero();  ///< world-point parameterisation
    long anchor = -1;                ///< inverse depth: the anchor keyframe's id
    /// Inverse depth: the ray's bearing from the anchor, rad (one-number form: the measured one).
    double psi = 0.0;
    double inv_depth = 0.0;  ///< inverse depth: ρ along that ray, 1/m
  };
  /// A variable of the marginalisation prior: a keyframe (by id) or a landmark (by track id).
  struct PriorVar {
    bool frame = true;
    long id = 0;
    int dim = 0;
    Eigen::VectorXd x_lin;  ///< linearisation point
  };
  struct Prior {
    std::vector<PriorVar> vars;
    Eigen::MatrixXd H;
    Eigen::VectorXd g;
    int dim() const { return static_cast<int>(g.size()); }
  };
  /// Variable offsets in the normal equations: per window slot (-1: not a variable) and per
  /// initialised landmark.
  struct Layout {
    std::vector<int> frame_offset;
    std::map<int, int> landmark_offset;
    int dim = 0;
  };
  enum class Selection { kAll, kMarginalisation };

  void AddObservations(long frame_id, const std::vector<BearingObservation>& obs);
  void InitialiseLandmarks();
  /// (ψ, ρ): the ray's bearing is estimated with the inverse depth.
  bool inverse_depth() const { return def_.landmarks == LandmarkParam::kInverseDepth; }
  /// ρ alone along the anchor's measured bearing.
  bool one_depth() const { return def_.landmarks == LandmarkParam::kInverseDepth1d; }
  /// Either inverse-depth form: the landmark lives in its anchor keyframe's coordinates.
  bool anchored() const { return inverse_depth() || one_depth(); }
  /// Numbers estimated per landmark: (ψ, ρ), (x, y), or ρ.
  int landmark_dim() const { return one_depth() ? 1 : 2; }
  /// One-number form: landmarks anchored at the oldest keyframe, marginalised with it (they
  /// restart at the next keyframe that saw them, ShiftAnchorsOfOldest).
  std::vector<int> AnchoredAtOldest() const;
  void ShiftAnchorsOfOldest(const std::vector<int>& ids);
  /// A landmark's estimated variables ((ψ, ρ) or the world position) and its world position.
  Eigen::VectorXd LandmarkValue(const Track& t) const;
  Vec2d Position(const std::deque<KeyframeState>& frames, const Track& t) const;
  const KeyframeState& FrameById(const std::deque<KeyframeState>& frames, long id) const {
    return frames[static_cast<std::size_t>(id - frames.front().id)];
  }
  /// The variables of the whole window: every keyframe and every initialised landmark.
  Layout FullLayout() const;
  /// Inverse depth: moves every landmark anchored before keyframe `keep_from` to the first
  /// keyframe from `keep_from` on that saw it, without moving the point (its prior, if any, by
  /// the linearised change of variables); a landmark behind its new anchor leaves the window.
  void ReanchorLandmarks(long keep_from);
  struct Reanchoring {
    int id = 0;  ///< landmark
    long old_anchor = 0, new_anchor = 0;
    Eigen::Vector2d old_value;  ///< (ψ, ρ) at the old anchor, at the current estimate
    Eigen::Vector2d new_value;  ///< (ψ, ρ) at the new anchor (the prior's new linearisation point)
    /// ∂(ψ, ρ)_old / ∂(old anchor, new anchor, (ψ, ρ)_new) at the current estimate.
    Eigen::Matrix<double, 2, KeyframeState::kDim> Ja, Jb;
    Eigen::Matrix2d Jl;
  };
  void ReanchorPrior(const std::vector<Reanchoring>& moves);
  void RepropagateIfNeeded();
  /// Where Linearize adds its terms: the cost, and the normal equations H and g (both null when
  /// only the cost is wanted).
  struct LinearTerms {
    Eigen::MatrixXd* H;
    Eigen::VectorXd* g;
    double cost;
  };
  /// Adds the marginalisation prior: cost gᵀdx + ½ dxᵀ H dx about its linearisation point.
  void LinearizePrior(const std::deque<KeyframeState>& frames, const std::map<int, Track>& tracks,
                      const Layout& layout, LinearTerms& out) const;
  /// Adds IMU and odometry between consecutive keyframes and the no-side-slip constraint (only
  /// the oldest keyframe's when marginalising).
  void LinearizeMotion(const std::deque<KeyframeState>& frames, const Layout& layout, bool marg,
                       LinearTerms& out) const;
  /// Adds the bearings of initialised landmarks (only the residuals that touch the oldest
  /// keyframe when marginalising; with inverse depth, every residual of a landmark anchored
  /// there); returns how many.
  int LinearizeBearings(const std::deque<KeyframeState>& frames, const std::map<int, Track>& tracks,
                        const Layout& layout, bool marg, LinearTerms& out) const;
  /// The bearings of one landmark in an inverse-depth form, at variable offset `ol`. In the
  /// one-number form the anchor's own bearing is taken as exact, no residual.
  int LinearizeAnchoredBearings(const std::deque<KeyframeState>& frames, const Layout& layout,
                                const Track& track, int ol, bool marg, LinearTerms& out) const;
  /// Cost ½Σ‖r‖² of the selected factors at the given states; fills H and g when non-null.
  double Linearize(const std::deque<KeyframeState>& frames, const std::map<int, Track>& tracks,
                   const Layout& layout, Selection sel, Eigen::MatrixXd* H, Eigen::VectorXd* g,
                   int* n_obs) const;
  bool Optimize(UpdateReport& report);
  bool Marginalize(std::string& error);
  /// Removes landmark variables from the prior by a Schur complement on the prior alone (their
  /// past information stays in it, they get no new measurements).
  void MarginalizeLandmarksFromPrior(const std::vector<int>& ids);
  bool InPrior(int landmark_id) const;
  void RemoveOutliers();
  void Restart(const KeyframeState& state, const std::string& why);
  ImuPreintegration NewImu() const;
  OdometryPreintegration NewOdometry() const;

  SlidingWindowDef def_;
  std::deque<KeyframeState> frames_;
  std::deque<ImuPreintegration> imu_;       ///< imu_[k]: frames_[k] → frames_[k + 1]
  std::deque<OdometryPreintegration> odo_;  ///< odo_[k]: frames_[k] → frames_[k + 1]
  ImuPreintegration imu_now_;               ///< since the newest keyframe
  OdometryPreintegration odo_now_;
  /// Time of the next sample already integrated into the previous interval (zero-order hold).
  double imu_carry_ = 0.0, odo_carry_ = 0.0;
  std::map<int, Track> tracks_;
  Prior prior_;
  long next_id_ = 0;
};

}  // namespace formsim::control::velocity
