#pragma once
/// \file The per-link UKF of paper 000 (eq. 9-21): state x = [l, φ, α], inputs
/// U = [v_i, ω_i, v_j, ω_j], process Γ(s, U) = s + Tc F(s) U (forward Euler of the output
/// kinematics of link_kinematics.hpp), measurement y = D s with a selectable subset of s.
///
/// Measurement sets: the paper measures y = [φ, α] on l-φ links and only α on l-l links.
/// With [α] alone, l and φ enter no measurement and α̇ = ω_i − ω_j does not depend on them, so
/// they are unobservable: the filter only dead-reckons l and φ from the inputs and their
/// variance grows with Q without bound. [φ, α] (the default for every link) makes l observable
/// through φ̇ whenever the leader turns or the formation moves relative to the leader; [l, φ, α]
/// measures everything.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "control/common/ukf.hpp"
#include "control/formation/link_kinematics.hpp"

namespace formsim::control::formation {

/// Which components of [l, φ, α] a link's sensor reports to its filter.
enum class MeasurementSet { kPhiAlpha, kLPhiAlpha, kAlpha };

/// Names used in scenarios: [phi, alpha], [l, phi, alpha], [alpha].
inline const char* MeasurementSetName(MeasurementSet m) {
  switch (m) {
    case MeasurementSet::kPhiAlpha:
      return "[phi, alpha]";
    case MeasurementSet::kLPhiAlpha:
      return "[l, phi, alpha]";
    case MeasurementSet::kAlpha:
      return "[alpha]";
  }
  return "?";
}

/// Definition of a link filter (Box2D-style struct with defaults; the paper's h = 0.9186e-4 rad²).
struct LinkFilterDef {
  MeasurementSet measure = MeasurementSet::kPhiAlpha;
  double Tc = 0.01;                                ///< filter period, s
  /// Euler steps of Tc / substeps per prediction (ours, beyond the paper). 1: the paper's single
  /// step, whose discretisation error on l is larger than q_l = 1e-8 admits (the filter is then
  /// overconfident on l); more steps shrink that error.
  int substeps = 1;
  double L = 0.15;                                 ///< follower's control point offset, m
  Eigen::Vector3d q{1e-8, 0.9186e-4, 0.9186e-4};   ///< process noise variance per step
  Eigen::Vector3d r{1e-4, 0.9186e-4, 0.9186e-4};   ///< measurement noise variance (l, φ, α)
  Eigen::Vector3d p0{1e-4, 0.9186e-4, 0.9186e-4};  ///< initial covariance diagonal
  UkfScaling scaling = DefaultUkfScaling(3);
};

/// What a batched time update (link_predict_lanes.hpp) reads of one link filter to run the
/// operations of its own Predict: the sigma points' basis, the weights and the settings.
struct LinkPredictBasis {
  Eigen::Vector3d x;           ///< mean [l, φ, α]
  Eigen::Matrix3d chol;        ///< lower Cholesky factor of P (upper part zero)
  double scale = 0.0;          ///< √(n+λ): sigma points x ± scale · columns of chol
  double wm0 = 0.0, wm = 0.0;  ///< mean weights of the centre point and of the six others
  double wc0 = 0.0, wc = 0.0;  ///< covariance weights of the centre point and of the others
  double Tc = 0.0, L = 0.0;
  Eigen::Vector3d q;  ///< process noise variance (Q's diagonal)
};

/// What a batched measurement update (link_update_lanes.hpp) reads of one link filter: views
/// of its storage, valid until the filter changes.
struct LinkUpdateBasis {
  const double* x = nullptr;  ///< mean [l, φ, α]
  const double* P = nullptr;  ///< covariance, column-major 3x3
  const double* r = nullptr;  ///< measurement noise variance (R's diagonal for l, φ, α)
};

/// A batched measurement update's result for one link, in a structure of arrays: element k of a
/// vector at [k * stride], element (row, col) of a matrix at [(row * 3 + col) * stride].
struct LinkUpdateResult {
  const double* x;     ///< the new mean
  const double* P;     ///< the new covariance
  const double* chol;  ///< its lower Cholesky factor
  int stride;
  double nis;
};

/// A UKF over one link; the measurement dimension depends on the measurement set.
class LinkFilter {
 public:
  virtual ~LinkFilter() = default;
  /// Builds the filter for `def.measure`.
  static std::unique_ptr<LinkFilter> Make(const LinkFilterDef& def);

  virtual void Reset(const LinkState& x0, const Eigen::Matrix3d& P0) = 0;
  /// Time update with the inputs applied during the last period.
  virtual UkfStatus Predict(const Twist& leader, const Twist& follower) = 0;
  /// Measurement update; `measured` holds all three components, only the set's are used.
  virtual UkfStatus Update(const LinkState& measured) = 0;
  /// Fills `b` for a batched time update and returns true when Predict would take the
  /// single-step sigma-point path from a Cholesky factor (made current here exactly as Predict
  /// would); false otherwise (substeps > 1, P not positive definite, ...): call Predict then.
  virtual bool PredictBasis(LinkPredictBasis& b) = 0;
  /// Ends a batched time update: the predicted mean and covariance (Q included, symmetric),
  /// computed with Predict's operations, checked and taken as Predict takes them.
  virtual UkfStatus AcceptPrediction(const Eigen::Vector3d& mean, const Eigen::Matrix3d& P) = 0;
  /// Fills `b` for a batched measurement update and returns how many components it measures
  /// (2: [φ, α], 3: [l, φ, α]) when Update would take the closed-form path with a covariance
  /// known positive definite, or could only end in a fault on a non-finite value (which the
  /// batch finds in its result and hands to Update); 0 otherwise ([α] alone, a spread that
  /// needs sigma points, ...): call Update then.
  virtual int UpdateBasis(LinkUpdateBasis& b) const = 0;
  /// Ends a batched measurement update that succeeded: the new mean, covariance (with its
  /// Cholesky factor) and NIS, computed with Update's operations.
  virtual void AcceptUpdate(const LinkUpdateResult& u) = 0;
  virtual LinkState state() const = 0;
  virtual Eigen::Matrix3d cov() const = 0;
  virtual double nis() const = 0;
  /// eᵀ P⁻¹ e for an error e of the state (the NEES when e is estimate − truth); NaN when P is
  /// not positive definite.
  virtual double Mahalanobis2(const Eigen::Vector3d& e) const = 0;
  /// Live tuning: takes Q, R, L, Tc and substeps from `d` (the measurement set, P0 and the
  /// sigma-point scaling are fixed at construction).
  void Retune(const LinkFilterDef& d) {
    def_.substeps = d.substeps;
    def_.q = d.q;
    def_.r = d.r;
    def_.L = d.L;
    def_.Tc = d.Tc;
  }
  const LinkFilterDef& def() const { return def_; }

 protected:
  explicit LinkFilter(const LinkFilterDef& def) : def_(def) {}
  LinkFilterDef def_;
};

}  // namespace formsim::control::formation
