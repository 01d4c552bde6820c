#include "control/velocity/sliding_window_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

#include "control/common/angle.hpp"
#include "control/common/dense_ldlt.hpp"
#include "control/common/exact_products.hpp"
#include "control/velocity/factors.hpp"
#include "control/velocity/triangulation.hpp"

namespace formsim::control::velocity {

namespace {

constexpr int kD = KeyframeState::kDim;

/// Adds the normal-equation contributions JᵀJ and Jᵀr of a residual touching up to two
/// variable blocks (offset < 0: block absent or not a variable of this system).
template <class Res, class JA, class JB>
void Accumulate(Eigen::MatrixXd& H, Eigen::VectorXd& g, const Res& r, int oa, const JA& Ja, int ob,
                const JB& Jb) {
  const int na = static_cast<int>(Ja.cols()), nb = static_cast<int>(Jb.cols());
  // JᵀJ with Eigen's bits, without its kernel's packing.
  if (oa >= 0) {
    AddTransposedTimes(H.block(oa, oa, na, na), Ja, Ja);
    g.segment(oa, na).noalias() += Ja.transpose() * r;
  }
  if (ob >= 0) {
    AddTransposedTimes(H.block(ob, ob, nb, nb), Jb, Jb);
    g.segment(ob, nb).noalias() += Jb.transpose() * r;
  }
  if (oa >= 0 && ob >= 0) {
    AddTransposedTimes(H.block(oa, ob, na, nb), Ja, Jb);
    H.block(ob, oa, nb, na) = H.block(oa, ob, na, nb).transpose();
  }
}

/// A one-row residual's Jacobian block at `offset` in the normal equations (offset < 0: the
/// block is not a variable of this system).
struct RowBlock {
  int offset;
  Eigen::Ref<const Eigen::RowVectorXd> J;
};

/// The columns of one block pair: col j of H's (a, b) block gains b_j·a. `Na` > 0 fixes the
/// block's height at compile time (a keyframe's 10 states, a landmark's 2): the same operations,
/// unrolled.
template <int Na>
void AccumulateBlock(Eigen::MatrixXd& H, int oa, const double* ja, int na, int ob,
                     const Eigen::Ref<const Eigen::RowVectorXd>& jb) {
  const int n = Na > 0 ? Na : na;
  const int nb = static_cast<int>(jb.size());
  for (int j = 0; j < nb; ++j) {
    double* col = &H(oa, ob + j);
    const double bj = jb(j);
    for (int i = 0; i < n; ++i) col[i] += bj * ja[i];
  }
}

/// Adds JᵀJ and Jᵀr of a one-row residual touching the given blocks (all distinct). Plain loops
/// over the columns: each element gets one product added, the same operations as Eigen's outer
/// product (a bearing residual is most of a window's rows; this is a sixth of an update's time).
void AccumulateRow(Eigen::MatrixXd& H, Eigen::VectorXd& g, double r,
                   std::initializer_list<RowBlock> blocks) {
  for (const RowBlock& a : blocks) {
    if (a.offset < 0) continue;
    const int na = static_cast<int>(a.J.size());
    const double* ja = a.J.data();
    double* ga = g.data() + a.offset;
    for (int i = 0; i < na; ++i) ga[i] += ja[i] * r;
    for (const RowBlock& b : blocks) {
      if (b.offset < 0) continue;
      if (na == KeyframeState::kDim)
        AccumulateBlock<KeyframeState::kDim>(H, a.offset, ja, na, b.offset, b.J);
      else if (na == 2)
        AccumulateBlock<2>(H, a.offset, ja, na, b.offset, b.J);
      else
        AccumulateBlock<0>(H, a.offset, ja, na, b.offset, b.J);
    }
  }
}

KeyframeState::Vector StateDiff(const KeyframeState::Vector& a, const KeyframeState::Vector& b) {
  KeyframeState::Vector d = a - b;
  d(KeyframeState::kTheta) = WrapToPi(d(KeyframeState::kTheta));
  return d;
}

/// Pseudo-inverse of a symmetric positive semi-definite block (directions without information
/// are dropped instead of blowing up).
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()));
  const double eps = 1e-10 * std::max(es.eigenvalues().cwiseAbs().maxCoeff(), 1e-30);
  const Eigen::VectorXd inv =
      es.eigenvalues().unaryExpr([eps](double l) { return l > eps ? 1.0 / l : 0.0; });
  return es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose();
}

/// The symmetric part. A Schur complement of a positive semi-definite matrix is positive
/// semi-definite; round-off only breaks its symmetry (and may leave eigenvalues of the order of
/// 1e-16 of the largest slightly negative, far below what the window's factors add).
Eigen::MatrixXd Symmetrised(const Eigen::MatrixXd& A) {
  return 0.5 * (A + A.transpose());
}

bool AllFinite(const std::deque<KeyframeState>& frames) {
  for (const KeyframeState& f : frames)
    if (!f.x.allFinite()) return false;
  return true;
}

}  // namespace

SlidingWindowEstimator::SlidingWindowEstimator(const SlidingWindowDef& def)
    : def_(def), imu_now_(0.0, Vec2d::Zero(), def.imu), odo_now_(0.0, 0.0, def.odometry) {}

ImuPreintegration SlidingWindowEstimator::NewImu() const {
  const KeyframeState& k = frames_.back();
  return ImuPreintegration(k.bg(), k.ba(), def_.imu);
}

OdometryPreintegration SlidingWindowEstimator::NewOdometry() const {
  const KeyframeState& k = frames_.back();
  return OdometryPreintegration(k.bv(), k.bw(), def_.odometry);
}

Eigen::VectorXd SlidingWindowEstimator::LandmarkValue(const Track& t) const {
  if (inverse_depth()) return Eigen::Vector2d(t.psi, t.inv_depth);
  if (one_depth()) return Eigen::VectorXd::Constant(1, t.inv_depth);
  return t.position;
}

Vec2d SlidingWindowEstimator::Position(const std::deque<KeyframeState>& frames,
                                       const Track& t) const {
  if (!anchored()) return t.position;
  return EvaluateAnchoredPoint(FrameById(frames, t.anchor), t.psi, t.inv_depth, def_.camera_offset)
      .f;
}

SlidingWindowEstimator::Layout SlidingWindowEstimator::FullLayout() const {
  Layout layout;
  for (std::size_t s = 0; s < frames_.size(); ++s)
    layout.frame_offset.push_back(kD * static_cast<int>(s));
  layout.dim = kD * static_cast<int>(frames_.size());
  for (const auto& [id, track] : tracks_)
    if (track.initialized) {
      layout.landmark_offset[id] = layout.dim;
      layout.dim += landmark_dim();
    }
  return layout;
}

void SlidingWindowEstimator::Initialize(const KeyframeState& first,
                                        const std::vector<BearingObservation>& obs) {
  frames_.clear();
  imu_.clear();
  odo_.clear();
  tracks_.clear();
  KeyframeState k = first;
  k.id = next_id_++;
  frames_.push_back(k);

  // The start state's prior: diagonal information, gradient zero at the given mean.
  KeyframeState::Vector sigma;
  sigma << def_.prior_position_sigma, def_.prior_position_sigma, def_.prior_heading_sigma,
      def_.prior_velocity_sigma, def_.prior_velocity_sigma, def_.prior_gyro_bias_sigma,
      def_.prior_accel_bias_sigma, def_.prior_accel_bias_sigma, def_.prior_speed_bias_sigma,
      def_.prior_yaw_rate_bias_sigma;
  prior_ = Prior{};
  prior_.vars.push_back({true, k.id, kD, k.x});
  prior_.H = sigma.array().square().inverse().matrix().asDiagonal();
  prior_.g = Eigen::VectorXd::Zero(kD);

  imu_now_ = NewImu();
  odo_now_ = NewOdometry();
  imu_carry_ = odo_carry_ = 0.0;
  AddObservations(k.id, obs);
}

void SlidingWindowEstimator::AddImu(double dt, double gyro, const Vec2d& accel) {
  if (!initialized() || !std::isfinite(gyro) || !accel.allFinite()) return;
  const double used = std::min(imu_carry_, dt);
  imu_carry_ = 0.0;
  imu_now_.Integrate(dt - used, gyro, accel);
}

void SlidingWindowEstimator::AddOdometry(double dt, double speed, double yaw_rate) {
  if (!initialized() || !std::isfinite(speed) || !std::isfinite(yaw_rate)) return;
  const double used = std::min(odo_carry_, dt);
  odo_carry_ = 0.0;
  odo_now_.Integrate(dt - used, speed, yaw_rate);
}

KeyframeState SlidingWindowEstimator::Propagated() const {
  const KeyframeState& k = frames_.back();
  KeyframeState s = k;
  const Mat2d R = Rot(k.theta());
  const double dt = imu_now_.sum_dt();
  s.set_p(k.p() + k.v() * dt + R * imu_now_.CorrectedP(k.bg(), k.ba()));
  s.set_v(k.v() + R * imu_now_.CorrectedV(k.bg(), k.ba()));
  s.set_theta(WrapToPi(k.theta() + imu_now_.CorrectedTheta(k.bg())));
  s.t = k.t + dt;
  return s;
}

void SlidingWindowEstimator::AddObservations(long frame_id,
                                             const std::vector<BearingObservation>& obs) {
  for (const BearingObservation& o : obs)
    if (std::isfinite(o.bearing)) tracks_[o.id].obs.emplace_back(frame_id, o.bearing);
}

void SlidingWindowEstimator::InitialiseLandmarks() {
  const long id0 = frames_.front().id;
  std::vector<BearingRay> rays;
  for (auto& [id, track] : tracks_) {
    if (track.initialized || track.obs.size() < 2) continue;
    rays.clear();
    for (const auto& [fid, z] : track.obs) {
      const KeyframeState& f = frames_[static_cast<std::size_t>(fid - id0)];
      const Vec2d c = f.p() + Rot(f.theta()) * Vec2d(def_.camera_offset, 0.0);
      rays.push_back({c, f.theta() + z});
    }
    const TriangulationResult tri =
        Triangulate(rays, def_.min_parallax, def_.min_depth, def_.max_landmark_range);
    if (!tri.ok) continue;
    if (anchored()) {
      // Anchored at the first keyframe that saw it, at the triangulated point (one-number form:
      // on the anchor's measured ray, at the point's distance along it).
      const auto& [fid, z] = track.obs.front();
      const KeyframeState& a = frames_[static_cast<std::size_t>(fid - id0)];
      AnchorCoordinates c = EvaluateAnchorCoordinates(a, tri.point, def_.camera_offset);
      if (one_depth()) {
        const Vec2d u(std::cos(a.theta() + z), std::sin(a.theta() + z));
        const double d = (tri.point - rays.front().origin).dot(u);
        c.psi = z;
        c.rho = d > 0.0 ? 1.0 / d : 0.0;
      }
      if (!(c.rho > 0.0 && c.rho * def_.min_depth <= 1.0)) continue;
      track.anchor = fid;
      track.psi = c.psi;
      track.inv_depth = c.rho;
    }
    track.initialized = true;
    track.position = tri.point;
  }
}

void SlidingWindowEstimator::RepropagateIfNeeded() {
  for (std::size_t k = 0; k < imu_.size(); ++k) {
    const KeyframeState& f = frames_[k];
    if (std::abs(f.bg() - imu_[k].lin_bg()) > def_.repropagate_gyro_bias ||
        (f.ba() - imu_[k].lin_ba()).norm() > def_.repropagate_accel_bias)
      imu_[k].Repropagate(f.bg(), f.ba());
    if (std::abs(f.bv() - odo_[k].lin_bv()) > def_.repropagate_speed_bias ||
        std::abs(f.bw() - odo_[k].lin_bw()) > def_.repropagate_yaw_rate_bias)
      odo_[k].Repropagate(f.bv(), f.bw());
  }
}

void SlidingWindowEstimator::LinearizePrior(const std::deque<KeyframeState>& frames,
                                            const std::map<int, Track>& tracks,
                                            const Layout& layout, LinearTerms& out) const {
  const long id0 = frames.front().id;
  const int n = prior_.dim();
  Eigen::VectorXd dx(n);
  std::vector<int> at(prior_.vars.size()), offset(prior_.vars.size());
  int pos = 0;
  for (std::size_t a = 0; a < prior_.vars.size(); ++a) {
    const PriorVar& v = prior_.vars[a];
    at[a] = pos;
    if (v.frame) {
      const std::size_t slot = static_cast<std::size_t>(v.id - id0);
      dx.segment<kD>(pos) = StateDiff(frames[slot].x, v.x_lin);
      offset[a] = layout.frame_offset[slot];
    } else {
      dx.segment(pos, v.dim) = LandmarkValue(tracks.at(static_cast<int>(v.id))) - v.x_lin;
      if (inverse_depth()) dx(pos) = WrapToPi(dx(pos));  // ψ
      auto it = layout.landmark_offset.find(static_cast<int>(v.id));
      offset[a] = it == layout.landmark_offset.end() ? -1 : it->second;
    }
    pos += v.dim;
  }
  const Eigen::VectorXd Hdx = prior_.H * dx;
  out.cost += prior_.g.dot(dx) + 0.5 * dx.dot(Hdx);
  if (!out.H) return;
  const Eigen::VectorXd grad = prior_.g + Hdx;
  for (std::size_t a = 0; a < prior_.vars.size(); ++a) {
    const int oa = offset[a], da = prior_.vars[a].dim;
    if (oa < 0) continue;
    out.g->segment(oa, da) += grad.segment(at[a], da);
    for (std::size_t b = 0; b < prior_.vars.size(); ++b) {
      const int ob = offset[b], db = prior_.vars[b].dim;
      if (ob >= 0) out.H->block(oa, ob, da, db) += prior_.H.block(at[a], at[b], da, db);
    }
  }
}

void SlidingWindowEstimator::LinearizeMotion(const std::deque<KeyframeState>& frames,
                                             const Layout& layout, bool marg,
                                             LinearTerms& out) const {
  const bool lin = out.H != nullptr;
  // IMU and odometry between consecutive keyframes (only the oldest pair when marginalising).
  const std::size_t pairs = marg ? std::min<std::size_t>(1, imu_.size()) : imu_.size();
  for (std::size_t k = 0; k < pairs; ++k) {
    const int oi = layout.frame_offset[k], oj = layout.frame_offset[k + 1];
    const ImuFactor fi = EvaluateImuFactor(imu_[k], frames[k], frames[k + 1]);
    out.cost += 0.5 * fi.r.squaredNorm();
    if (lin) Accumulate(*out.H, *out.g, fi.r, oi, fi.Ji, oj, fi.Jj);
    const OdometryFactor fo = EvaluateOdometryFactor(odo_[k], frames[k], frames[k + 1]);
    if (def_.use_odometry) {
      out.cost += 0.5 * fo.r.squaredNorm();
      if (lin) Accumulate(*out.H, *out.g, fo.r, oi, fo.Ji, oj, fo.Jj);
    } else {
      // Without odometry the odometry biases only keep their random walk, so that the system
      // stays well posed; they do not influence the motion.
      const Eigen::Vector2d r = fo.r.tail<2>();
      out.cost += 0.5 * r.squaredNorm();
      if (lin) Accumulate(*out.H, *out.g, r, oi, fo.Ji.bottomRows<2>(), oj, fo.Jj.bottomRows<2>());
    }
  }

  if (!def_.use_nonholonomic) return;
  const Eigen::Matrix<double, 1, 1> none;  // placeholder Jacobian for one-block residuals
  const std::size_t n = marg ? 1 : frames.size();
  for (std::size_t k = 0; k < n; ++k) {
    const NonholonomicFactor f = EvaluateNonholonomicFactor(frames[k], def_.nonholonomic_sigma);
    out.cost += 0.5 * f.r * f.r;
    if (lin)
      Accumulate(*out.H, *out.g, Eigen::Matrix<double, 1, 1>(f.r), layout.frame_offset[k], f.J, -1,
                 none);
  }
}

int SlidingWindowEstimator::LinearizeAnchoredBearings(const std::deque<KeyframeState>& frames,
                                                      const Layout& layout, const Track& track,
                                                      int ol, bool marg, LinearTerms& out) const {
  const long id0 = frames.front().id;
  const std::size_t a = static_cast<std::size_t>(track.anchor - id0);
  int count = 0;
  for (const auto& [fid, z] : track.obs) {
    if (marg && fid != id0 && track.anchor != id0) continue;
    if (one_depth() && fid == track.anchor) continue;
    ++count;
    if (fid == track.anchor) {
      // From its anchor the landmark's bearing is ψ itself.
      const double w = 1.0 / std::max(def_.bearing_sigma, 1e-12);
      const double r = w * WrapToPi(track.psi - z);
      out.cost += 0.5 * r * r;
      if (out.H) AccumulateRow(*out.H, *out.g, r, {{ol, Eigen::RowVector2d(w, 0.0)}});
      continue;
    }
    const std::size_t s = static_cast<std::size_t>(fid - id0);
    const InverseDepthBearingFactor f =
        EvaluateInverseDepthBearingFactor(frames[s], frames[a], track.psi, track.inv_depth, z,
                                          def_.bearing_sigma, def_.camera_offset);
    out.cost += 0.5 * f.r * f.r;
    if (out.H)
      AccumulateRow(*out.H, *out.g, f.r,
                    {{layout.frame_offset[s], f.Jk},
                     {layout.frame_offset[a], f.Ja},
                     {ol, f.Jl.rightCols(landmark_dim())}});  // ρ alone: its column
  }
  return count;
}

int SlidingWindowEstimator::LinearizeBearings(const std::deque<KeyframeState>& frames,
                                              const std::map<int, Track>& tracks,
                                              const Layout& layout, bool marg,
                                              LinearTerms& out) const {
  const long id0 = frames.front().id;
  int count = 0;
  for (const auto& [id, track] : tracks) {
    if (!track.initialized) continue;
    auto it = layout.landmark_offset.find(id);
    const int ol = it == layout.landmark_offset.end() ? -1 : it->second;
    if (anchored()) {
      count += LinearizeAnchoredBearings(frames, layout, track, ol, marg, out);
      continue;
    }
    for (const auto& [fid, z] : track.obs) {
      if (marg && fid != id0) continue;
      const std::size_t s = static_cast<std::size_t>(fid - id0);
      const BearingFactor f = EvaluateBearingFactor(frames[s], track.position, z,
                                                    def_.bearing_sigma, def_.camera_offset);
      out.cost += 0.5 * f.r * f.r;
      ++count;
      if (out.H) AccumulateRow(*out.H, *out.g, f.r, {{layout.frame_offset[s], f.Jk}, {ol, f.Jf}});
    }
  }
  return count;
}

double SlidingWindowEstimator::Linearize(const std::deque<KeyframeState>& frames,
                                         const std::map<int, Track>& tracks, const Layout& layout,
                                         Selection sel, Eigen::MatrixXd* H, Eigen::VectorXd* g,
                                         int* n_obs) const {
  if (H != nullptr) {
    H->setZero(layout.dim, layout.dim);
    g->setZero(layout.dim);
  }
  const bool marg = sel == Selection::kMarginalisation;
  // The terms in a fixed order (the cost is their sum in this order): prior, motion, bearings.
  LinearTerms out{H, g, 0.0};
  if (!prior_.vars.empty()) LinearizePrior(frames, tracks, layout, out);
  LinearizeMotion(frames, layout, marg, out);
  const int count = LinearizeBearings(frames, tracks, layout, marg, out);
  if (n_obs) *n_obs = count;
  return out.cost;
}

bool SlidingWindowEstimator::Optimize(UpdateReport& report) {
  const Layout layout = FullLayout();
  report.landmarks = static_cast<int>(layout.landmark_offset.size());

  Eigen::MatrixXd H, Hc;
  Eigen::VectorXd g, gc;
  double cost = Linearize(frames_, tracks_, layout, Selection::kAll, &H, &g, &report.observations);
  report.initial_cost = report.final_cost = cost;
  if (!std::isfinite(cost) || !H.allFinite() || !g.allFinite()) {
    report.message = "non-finite residuals or Jacobians before the solve";
    return false;
  }

  // Levenberg-Marquardt that starts as pure Gauss-Newton: the window's information spans ten
  // decades, so any fixed Marquardt damping would stall the weakly observed directions. Damping
  // is only switched on (and grown) when a step fails to lower the cost.
  double lambda = def_.initial_lambda, nu = 2.0;
  // The trial state, assigned (not built) each iteration so that its nodes and buffers are
  // reused; an accepted step swaps it in.
  std::deque<KeyframeState> frames;
  std::map<int, Track> tracks;
  Eigen::MatrixXd scaled;
  Eigen::VectorXd damped;
  DenseLdlt ldlt;  // Eigen's LDLT, its bits in less time; its buffers serve every iteration
  for (int it = 0; it < def_.max_iterations; ++it) {
    // A = H with the damped diagonal; only its diagonal is formed apart.
    damped = H.diagonal();
    for (int i = 0; i < layout.dim; ++i) damped(i) += lambda * std::max(H(i, i), 1e-9) + 1e-15;
    // Jacobi scaling: the unknowns span many orders of magnitude of information (bias random
    // walks vs. weakly observed directions), the scaled system is far better conditioned.
    // D⁻½ A D⁻½ entry by entry as (dᵢ Aᵢⱼ) dⱼ.
    const Eigen::VectorXd dinv = damped.cwiseSqrt().cwiseInverse();
    scaled.noalias() = dinv.asDiagonal() * H * dinv.asDiagonal();
    for (int i = 0; i < layout.dim; ++i) scaled(i, i) = (dinv(i) * damped(i)) * dinv(i);
    ldlt.Compute(std::move(scaled));
    if (!ldlt.ok() || !ldlt.positive()) {
      report.message = "normal equations not positive definite";
      return false;
    }
    const Eigen::VectorXd delta = dinv.asDiagonal() * ldlt.Solve(-(dinv.asDiagonal() * g));
    if (!delta.allFinite()) {
      report.message = "non-finite Gauss-Newton step";
      return false;
    }
    frames = frames_;
    tracks = tracks_;
    for (std::size_t s = 0; s < frames.size(); ++s) {
      frames[s].x += delta.segment<kD>(kD * s);
      frames[s].set_theta(WrapToPi(frames[s].theta()));
    }
    for (const auto& [id, off] : layout.landmark_offset) {
      if (inverse_depth()) {
        tracks[id].psi = WrapToPi(tracks[id].psi + delta(off));
        tracks[id].inv_depth += delta(off + 1);
      } else if (one_depth()) {
        tracks[id].inv_depth += delta(off);
      } else {
        tracks[id].position += delta.segment<2>(off);
      }
    }

    const double new_cost = Linearize(frames, tracks, layout, Selection::kAll, &Hc, &gc, nullptr);
    if (std::isfinite(new_cost) && new_cost < cost && Hc.allFinite() && gc.allFinite()) {
      const double rel = (cost - new_cost) / std::max(std::abs(cost), 1e-12);
      // Gain ratio of actual to predicted reduction (Nielsen's damping update).
      const double predicted = -(g.dot(delta) + 0.5 * delta.dot(H * delta));
      const double rho = predicted > 0.0 ? (cost - new_cost) / predicted : 1.0;
      frames_.swap(frames);
      tracks_.swap(tracks);
      H.swap(Hc);
      g.swap(gc);
      cost = new_cost;
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      if (lambda < 1e-12) lambda = 0.0;
      nu = 2.0;
      ++report.iterations;
      if (rel < 1e-10 || delta.lpNorm<Eigen::Infinity>() < 1e-10) break;
    } else {
      lambda = lambda == 0.0 ? 1e-6 : lambda * nu;
      nu *= 2.0;
      if (lambda > 1e6) break;
    }
  }
  report.final_cost = cost;
  if (!AllFinite(frames_)) {
    report.message = "non-finite state after the solve";
    return false;
  }
  return true;
}

void SlidingWindowEstimator::RemoveOutliers() {
  std::vector<int> bad_ids;
  for (const auto& [id, t] : tracks_) {
    if (!t.initialized) continue;
    const Vec2d position = Position(frames_, t);
    bool bad = !position.allFinite() ||
               (position - frames_.back().p()).norm() > 2.0 * def_.max_landmark_range ||
               (anchored() && !(t.inv_depth > 0.0 && t.inv_depth * def_.min_depth <= 1.0));
    for (std::size_t o = 0; o < t.obs.size() && !bad; ++o) {
      const BearingFactor b =
          EvaluateBearingFactor(FrameById(frames_, t.obs[o].first), position, t.obs[o].second,
                                def_.bearing_sigma, def_.camera_offset);
      // Behind the camera, or a residual beyond 6 σ (a chi-square gate for one degree).
      bad = b.depth < def_.min_depth || std::abs(b.r) > 6.0;
    }
    if (bad) bad_ids.push_back(id);
  }
  // An outlier that is part of the prior keeps its past information there and gets no more.
  std::vector<int> in_prior;
  for (int id : bad_ids)
    if (InPrior(id)) in_prior.push_back(id);
  MarginalizeLandmarksFromPrior(in_prior);
  for (int id : bad_ids) tracks_.erase(id);
}

bool SlidingWindowEstimator::InPrior(int landmark_id) const {
  for (const PriorVar& v : prior_.vars)
    if (!v.frame && v.id == landmark_id) return true;
  return false;
}

void SlidingWindowEstimator::MarginalizeLandmarksFromPrior(const std::vector<int>& ids) {
  if (ids.empty() || prior_.vars.empty()) return;
  // Partition the prior's coordinates into removed (m) and kept (k).
  std::vector<int> mi, ki;
  std::vector<PriorVar> kept;
  int pos = 0;
  for (const PriorVar& v : prior_.vars) {
    const bool drop =
        !v.frame && std::find(ids.begin(), ids.end(), static_cast<int>(v.id)) != ids.end();
    for (int d = 0; d < v.dim; ++d) (drop ? mi : ki).push_back(pos + d);
    if (!drop) kept.push_back(v);
    pos += v.dim;
  }
  if (mi.empty()) return;
  const int m = static_cast<int>(mi.size()), k = static_cast<int>(ki.size());
  Eigen::MatrixXd Hmm(m, m), Hkm(k, m), Hkk(k, k);
  Eigen::VectorXd gm(m), gk(k);
  for (int a = 0; a < m; ++a) {
    gm(a) = prior_.g(mi[a]);
    for (int b = 0; b < m; ++b) Hmm(a, b) = prior_.H(mi[a], mi[b]);
  }
  for (int a = 0; a < k; ++a) {
    gk(a) = prior_.g(ki[a]);
    for (int b = 0; b < m; ++b) Hkm(a, b) = prior_.H(ki[a], mi[b]);
    for (int b = 0; b < k; ++b) Hkk(a, b) = prior_.H(ki[a], ki[b]);
  }
  const Eigen::MatrixXd Hmm_inv = PseudoInverse(Hmm);
  prior_.H = Symmetrised(Hkk - Hkm * Hmm_inv * Hkm.transpose());
  prior_.g = gk - Hkm * Hmm_inv * gm;
  prior_.vars = std::move(kept);
}

void SlidingWindowEstimator::ReanchorLandmarks(long keep_from) {
  std::vector<Reanchoring> moves;
  std::vector<int> dropped;
  for (auto& [id, track] : tracks_) {
    if (!track.initialized || track.anchor >= keep_from) continue;
    const auto next = std::find_if(track.obs.begin(), track.obs.end(),
                                   [keep_from](const auto& o) { return o.first >= keep_from; });
    if (next == track.obs.end()) continue;  // leaves the window with its anchor
    const KeyframeState& a = FrameById(frames_, track.anchor);
    const KeyframeState& b = FrameById(frames_, next->first);
    // The same point in the new anchor's coordinates: an exact change of variables.
    const Vec2d f = Position(frames_, track);
    const AnchorCoordinates nb = EvaluateAnchorCoordinates(b, f, def_.camera_offset);
    if (!(nb.rho > 0.0 && nb.rho * def_.min_depth <= 1.0) || !std::isfinite(nb.psi)) {
      dropped.push_back(id);
      continue;
    }
    if (InPrior(id)) {
      // The prior's old (ψ, ρ) as a function of (old anchor, new anchor, new (ψ, ρ)).
      const AnchoredPoint p = EvaluateAnchoredPoint(b, nb.psi, nb.rho, def_.camera_offset);
      const AnchorCoordinates old = EvaluateAnchorCoordinates(a, p.f, def_.camera_offset);
      Reanchoring m;
      m.id = id;
      m.old_anchor = track.anchor;
      m.new_anchor = next->first;
      m.old_value = Eigen::Vector2d(old.psi, old.rho);
      m.new_value = Eigen::Vector2d(nb.psi, nb.rho);
      m.Ja = old.Ja;
      m.Jb = old.Jf * p.Ja;
      m.Jl.col(0) = old.Jf * p.Jpsi;
      m.Jl.col(1) = old.Jf * p.Jrho;
      moves.push_back(m);
    }
    track.anchor = next->first;
    track.psi = nb.psi;
    track.inv_depth = nb.rho;
  }
  ReanchorPrior(moves);
  // Landmarks behind their new anchor leave the window (their past information stays in the
  // prior) and are tracked again from scratch.
  std::vector<int> in_prior;
  for (int id : dropped)
    if (InPrior(id)) in_prior.push_back(id);
  MarginalizeLandmarksFromPrior(in_prior);
  for (int id : dropped) {
    Track& t = tracks_[id];
    t.initialized = false;
    t.anchor = -1;
  }
}

std::vector<int> SlidingWindowEstimator::AnchoredAtOldest() const {
  std::vector<int> ids;
  for (const auto& [id, track] : tracks_)
    if (track.initialized && track.anchor == frames_.front().id) ids.push_back(id);
  return ids;
}

void SlidingWindowEstimator::ShiftAnchorsOfOldest(const std::vector<int>& ids) {
  // VINS-Mono's removeBackShiftDepth: the point at its last estimate, seen from the next
  // keyframe that saw it, keeps its depth along that camera's optical axis and moves onto that
  // keyframe's measured ray; ρ becomes a new variable without prior. Too few bearings left, or
  // behind the camera: the landmark is triangulated again when it can be.
  for (int id : ids) {
    Track& t = tracks_[id];
    t.initialized = false;
    if (t.obs.size() < 3) continue;  // fewer than two bearings once the anchor's goes
    const auto& [fid, z] = t.obs[1];
    const KeyframeState& b = FrameById(frames_, fid);
    const Vec2d q = Rot(b.theta()).transpose() * (Position(frames_, t) - b.p()) -
                    Vec2d(def_.camera_offset, 0.0);
    const double d = q.x() / std::cos(z);
    if (!(std::cos(z) > 0.0 && d >= def_.min_depth && std::isfinite(d))) continue;
    t.initialized = true;
    t.anchor = fid;
    t.psi = z;
    t.inv_depth = 1.0 / d;
  }
}

void SlidingWindowEstimator::ReanchorPrior(const std::vector<Reanchoring>& moves) {
  if (moves.empty()) return;
  // Keyframes a move needs that the prior lacks are appended (no information yet, linearised
  // at the current estimate). The new anchor may be newer than the last marginalisation; the
  // old one is in the prior whenever the landmark is (both were in the window then).
  const int n_old = prior_.dim();
  auto has_frame = [this](long id) {
    for (const PriorVar& v : prior_.vars)
      if (v.frame && v.id == id) return true;
    return false;
  };
  for (const Reanchoring& m : moves)
    for (long id : {m.old_anchor, m.new_anchor})
      if (!has_frame(id)) prior_.vars.push_back({true, id, kD, FrameById(frames_, id).x});
  std::map<std::pair<bool, long>, int> at;  // offset of each variable
  int n = 0;
  for (const PriorVar& v : prior_.vars) {
    at[{v.frame, v.id}] = n;
    n += v.dim;
  }
  auto lin_of = [this](bool frame, long id) -> const Eigen::VectorXd& {
    for (const PriorVar& v : prior_.vars)
      if (v.frame == frame && v.id == id) return v.x_lin;
    return prior_.vars.front().x_lin;  // unreachable: both anchors and the landmark are in it
  };
  // The prior's old coordinates in the new ones: dx_old = a + T dx_new, T the (padded) identity
  // except on the two rows of each moved landmark:
  //   d(ψ, ρ)_old = a + Ja dx_a + Jb dx_b + Jl d(ψ, ρ)_new,
  // dx_a, dx_b being the prior's own coordinates of the anchors (deviations from its
  // linearisation point). With T = E + U Dᵀ (U picks those rows): H' = TᵀHT, g' = Tᵀ(g + H a).
  const int k = 2 * static_cast<int>(moves.size());
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, k);
  Eigen::VectorXd a_full = Eigen::VectorXd::Zero(n_old);
  std::vector<int> rows(static_cast<std::size_t>(k));
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const Reanchoring& m = moves[i];
    const int r = at.at({false, m.id}), oa = at.at({true, m.old_anchor}),
              ob = at.at({true, m.new_anchor});
    const KeyframeState::Vector da =
        StateDiff(FrameById(frames_, m.old_anchor).x, lin_of(true, m.old_anchor));
    const KeyframeState::Vector db =
        StateDiff(FrameById(frames_, m.new_anchor).x, lin_of(true, m.new_anchor));
    Eigen::Vector2d dv = m.old_value - lin_of(false, m.id);
    dv(0) = WrapToPi(dv(0));
    a_full.segment<2>(r) = dv - m.Ja * da - m.Jb * db;
    for (int j = 0; j < 2; ++j) {
      const int c = 2 * static_cast<int>(i) + j;
      rows[static_cast<std::size_t>(c)] = r + j;
      D.block(oa, c, kD, 1) += m.Ja.row(j).transpose();
      D.block(ob, c, kD, 1) += m.Jb.row(j).transpose();
      D.block(r, c, 2, 1) += m.Jl.row(j).transpose();
      D(r + j, c) -= 1.0;
    }
  }
  Eigen::MatrixXd Hp = Eigen::MatrixXd::Zero(n, n);
  Hp.topLeftCorner(n_old, n_old) = prior_.H;
  Eigen::VectorXd ga = Eigen::VectorXd::Zero(n);
  ga.head(n_old) = prior_.g + prior_.H * a_full;
  Eigen::MatrixXd HU(n, k), UHU(k, k);
  Eigen::VectorXd gU(k);
  for (int i = 0; i < k; ++i) {
    const int ri = rows[static_cast<std::size_t>(i)];
    HU.col(i) = Hp.col(ri);
    gU(i) = ga(ri);
    for (int j = 0; j < k; ++j) UHU(i, j) = Hp(ri, rows[static_cast<std::size_t>(j)]);
  }
  // D's rows are zero but for the moved landmarks and their anchors: the products are formed
  // over its non-zero rows, with the bits of the dense ones.
  const Eigen::MatrixXd HUDt = TimesTransposed(HU, D);
  const Eigen::MatrixXd DUHUDt = TimesTransposed(D * UHU, D);
  prior_.H = Symmetrised(Hp + HUDt + HUDt.transpose() + DUHUDt);
  prior_.g = ga + D * gU;
  for (const Reanchoring& m : moves)
    for (PriorVar& v : prior_.vars)
      if (!v.frame && v.id == m.id) v.x_lin = m.new_value;
}

bool SlidingWindowEstimator::Marginalize(std::string& error) {
  const long id0 = frames_.front().id;
  // Normally done before the solve (AddKeyframe); here it only catches what is left.
  if (inverse_depth()) ReanchorLandmarks(frames_[1].id);
  // Removed: the oldest keyframe (one-number form: with the ρ of the landmarks it anchors).
  // Kept: every other keyframe, the initialised landmarks it saw and the landmarks already in
  // the prior.
  Layout layout;
  layout.frame_offset.assign(frames_.size(), -1);
  layout.frame_offset[0] = 0;
  layout.dim = kD;
  const std::vector<int> shifted = one_depth() ? AnchoredAtOldest() : std::vector<int>{};
  for (int id : shifted) layout.landmark_offset[id] = layout.dim++;
  const int m = layout.dim;
  std::vector<PriorVar> kept;
  for (std::size_t s = 1; s < frames_.size(); ++s) {
    layout.frame_offset[s] = layout.dim;
    layout.dim += kD;
    kept.push_back({true, frames_[s].id, kD, frames_[s].x});
  }
  for (const auto& [id, track] : tracks_) {
    if (!track.initialized || layout.landmark_offset.count(id)) continue;
    const bool seen = !track.obs.empty() && track.obs.front().first == id0;
    if (!seen && !InPrior(id)) continue;
    layout.landmark_offset[id] = layout.dim;
    layout.dim += landmark_dim();
    kept.push_back({false, id, landmark_dim(), LandmarkValue(track)});
  }
  const int k = layout.dim - m;

  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  Linearize(frames_, tracks_, layout, Selection::kMarginalisation, &H, &g, nullptr);
  if (!H.allFinite() || !g.allFinite()) {
    error = "non-finite marginalisation system";
    return false;
  }
  const Eigen::MatrixXd Hmm_inv = PseudoInverse(H.topLeftCorner(m, m));
  const Eigen::MatrixXd Hkm = H.bottomLeftCorner(k, m);
  Prior p;
  p.H = Symmetrised(H.bottomRightCorner(k, k) - Hkm * Hmm_inv * Hkm.transpose());
  p.g = g.tail(k) - Hkm * Hmm_inv * g.head(m);
  if (!p.H.allFinite() || !p.g.allFinite()) {
    error = "marginalisation prior is not finite";
    return false;
  }
  p.vars = std::move(kept);
  prior_ = std::move(p);
  ShiftAnchorsOfOldest(shifted);

  frames_.pop_front();
  imu_.pop_front();
  odo_.pop_front();
  // Drop the removed keyframe's bearings; landmarks nobody in the window sees any more leave
  // (out of the prior if they were in it).
  std::vector<int> gone;
  for (auto& [id, track] : tracks_) {
    if (!track.obs.empty() && track.obs.front().first == id0) track.obs.erase(track.obs.begin());
    if (track.obs.empty()) gone.push_back(id);
  }
  std::vector<int> gone_in_prior;
  for (int id : gone)
    if (InPrior(id)) gone_in_prior.push_back(id);
  MarginalizeLandmarksFromPrior(gone_in_prior);
  for (int id : gone) tracks_.erase(id);
  return true;
}

void SlidingWindowEstimator::Restart(const KeyframeState& state, const std::string& why) {
  (void)why;
  KeyframeState s = state;
  // After a fault the velocity is not known as well as at a start from rest.
  const double v_sigma = def_.prior_velocity_sigma;
  def_.prior_velocity_sigma = std::max(v_sigma, 0.2);
  Initialize(s, {});
  def_.prior_velocity_sigma = v_sigma;
  frames_.back().t = state.t;
}

UpdateReport SlidingWindowEstimator::AddKeyframe(double t,
                                                 const std::vector<BearingObservation>& obs) {
  UpdateReport report;
  if (!initialized()) {
    report.ok = false;
    report.message = "estimator not initialised";
    return report;
  }
  if (!(imu_now_.sum_dt() > 0.0)) {
    report.message = "no IMU samples since the last keyframe; keyframe skipped";
    return report;
  }
  const KeyframeState last_good = frames_.back();
  // Hold the newest samples up to the keyframe time; the next samples skip that part.
  const double imu_gap = t - (last_good.t + imu_now_.sum_dt());
  if (imu_gap > 1e-9 && !imu_now_.samples().empty()) {
    const ImuPreintegration::Sample s = imu_now_.samples().back();
    imu_now_.Integrate(imu_gap, s.gyro, s.accel);
    imu_carry_ = imu_gap;
  }
  const double odo_gap = t - (last_good.t + odo_now_.sum_dt());
  if (odo_gap > 1e-9 && !odo_now_.samples().empty()) {
    const OdometryPreintegration::Sample s = odo_now_.samples().back();
    odo_now_.Integrate(odo_gap, s.speed, s.yaw_rate);
    odo_carry_ = odo_gap;
  }
  // Initial guess: IMU propagation; with odometry, the position from corrected odometry.
  KeyframeState k = Propagated();
  if (def_.use_odometry && odo_now_.sum_dt() > 0.0) {
    const KeyframeState& prev = frames_.back();
    k.set_p(prev.p() + Rot(prev.theta()) * odo_now_.CorrectedP(prev.bv(), prev.bw()));
  }
  k.t = t;
  k.id = next_id_++;
  // Where to restart after a fault: the last good keyframe moved by the corrected odometry
  // (robust to a corrupted IMU), or simply the last good keyframe.
  KeyframeState fallback = last_good;
  if (def_.use_odometry && !odo_now_.samples().empty()) {
    const Mat2d R = Rot(last_good.theta());
    fallback.set_p(last_good.p() + R * odo_now_.CorrectedP(last_good.bv(), last_good.bw()));
    fallback.set_theta(WrapToPi(last_good.theta() + odo_now_.CorrectedTheta(last_good.bw())));
    const double speed = odo_now_.samples().back().speed - last_good.bv();
    fallback.set_v(Rot(fallback.theta()) * Vec2d(speed, 0.0));
  }
  if (!fallback.x.allFinite()) fallback = last_good;
  fallback.t = t;
  frames_.push_back(k);
  imu_.push_back(imu_now_);
  odo_.push_back(odo_now_);
  AddObservations(k.id, obs);
  RepropagateIfNeeded();
  InitialiseLandmarks();
  // Landmarks anchored at keyframes that this update will marginalise move to a keyframe that
  // stays, before the solve, so that marginalising them afterwards keeps the optimum.
  const int window = std::max(def_.window_size, 2);
  if (inverse_depth() && static_cast<int>(frames_.size()) > window)
    ReanchorLandmarks(frames_[frames_.size() - static_cast<std::size_t>(window)].id);

  if (!Optimize(report)) {
    report.ok = false;
    Restart(fallback, report.message);
    return report;
  }
  RemoveOutliers();
  while (static_cast<int>(frames_.size()) > std::max(def_.window_size, 2)) {
    std::string error;
    if (!Marginalize(error)) {
      report.ok = false;
      report.message = error;
      Restart(frames_.back(), error);
      return report;
    }
    report.marginalised = true;
  }
  imu_now_ = NewImu();
  odo_now_ = NewOdometry();
  return report;
}

UpdateReport SlidingWindowEstimator::Reoptimize() {
  UpdateReport report;
  if (!initialized()) {
    report.ok = false;
    report.message = "estimator not initialised";
    return report;
  }
  report.ok = Optimize(report);
  return report;
}

std::vector<SlidingWindowEstimator::LandmarkView> SlidingWindowEstimator::Landmarks() const {
  std::vector<LandmarkView> out;
  const long newest = frames_.empty() ? -1 : frames_.back().id;
  for (const auto& [id, track] : tracks_) {
    LandmarkView v;
    v.id = id;
    v.initialized = track.initialized;
    v.position = track.initialized ? Position(frames_, track) : track.position;
    v.observations = static_cast<int>(track.obs.size());
    v.seen_in_latest = !track.obs.empty() && track.obs.back().first == newest;
    out.push_back(v);
  }
  return out;
}

}  // namespace formsim::control::velocity
