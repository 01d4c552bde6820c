#pragma once
/// \file Measurement updates of several link UKFs at once, one link per SIMD lane, on the same
/// paths as the time updates (link_predict_lanes.hpp: AVX2, four links an instruction; the
/// portable path, two in SSE2 registers; LanePath::kScalar: every link by its own Update).
///
/// A lane runs exactly the operations of the closed-form update (Ukf::UpdateSelection, Correct
/// and Accept) for [φ, α] or [l, φ, α], in the order Eigen gives its small products and sums, so
/// a link's result is the same bits as its own Update (link_update_lanes.cpp is compiled with
/// -ffp-contract=off). A link whose update leaves that path (a covariance not known positive
/// definite, a spread that needs the sigma-point update, a non-finite value, an innovation more
/// than a turn out, a factorisation that fails, a measured set of [α] alone) runs Update itself.

#include <cstddef>

#include "control/formation/link_filter.hpp"
#include "control/formation/link_predict_lanes.hpp"

namespace formsim::control::formation {

/// Collects links to update and runs them in lanes as they fill up (one batch per measured set).
class LinkUpdateBatch {
 public:
  static constexpr int kLanes = 4;

  LinkUpdateBatch() : path_(ResolveLanePath(CurrentLanePath())) {}
  LinkUpdateBatch(const LinkUpdateBatch&) = delete;
  LinkUpdateBatch& operator=(const LinkUpdateBatch&) = delete;
  /// Flushes.
  ~LinkUpdateBatch() { Flush(); }

  /// Updates `f` with `measured`; its status is in `*status` after Flush at the latest (a link
  /// that cannot take a lane is updated at once). `f` and `status` must stay valid until then.
  void Add(LinkFilter& f, const LinkState& measured, UkfStatus* status);
  /// Runs the links collected so far.
  void Flush();
  /// Links updated in a lane so far, and links that Update ran instead.
  std::size_t laned() const { return laned_; }
  std::size_t fell_back() const { return fell_back_; }

  /// What a lane reads and writes, one array element per lane (structure of arrays).
  struct Lanes {
    alignas(32) double x[3][kLanes];
    alignas(32) double P[3][3][kLanes];
    alignas(32) double z[3][kLanes];  ///< the measured [l, φ, α]
    alignas(32) double r[3][kLanes];  ///< R's diagonal for [l, φ, α]
    // Out: the new mean, covariance, its Cholesky factor, the NIS and whether the lane stayed
    // on the common path (else its link runs Update).
    alignas(32) double x_out[3][kLanes];
    alignas(32) double P_out[3][3][kLanes];
    alignas(32) double L_out[3][3][kLanes];
    alignas(32) double nis[kLanes];
    alignas(32) long long ok[kLanes];
  };

 private:
  struct Set {
    int n = 0;
    LinkFilter* filter[kLanes] = {};
    UkfStatus* status[kLanes] = {};
    LinkState measured[kLanes];
    Lanes lanes;
  };
  void Run(int measured, Set& s);

  LanePath path_;
  Set sets_[2];  ///< [φ, α] and [l, φ, α]
  std::size_t laned_ = 0, fell_back_ = 0;
};

/// Runs the lanes [0, kLanes) of `l` for `measured` components (2: [φ, α], 3: [l, φ, α]) with
/// the given path's code (kPortable or kAvx2; the latter only where CpuHasAvx2()).
void RunUpdateLanes(LanePath path, int measured, LinkUpdateBatch::Lanes& l);

}  // namespace formsim::control::formation
