#pragma once
/// \file Time updates of several link UKFs at once, one link per SIMD lane (AVX2: four links
/// per instruction; the portable path: two, in SSE2 registers, which every x86-64 has).
///
/// Each lane runs exactly the operations of LinkFilter::Predict for its link, in the same order
/// (the same sigma points, the same sine/cosine polynomials and reductions, the same sums), so
/// a link's result is the same bits as its own Predict: IEEE addition, multiplication and
/// division are correctly rounded lane by lane, and nothing here is contracted to FMA or
/// reassociated (link_predict_lanes.cpp is compiled with -ffp-contract=off, no -ffast-math).
/// Where Predict would branch off its common path (an angle more than one turn out, a sigma
/// point's spread beyond the small-angle polynomials, an arctangent off the axis, a non-finite
/// value, substeps > 1), that link alone is predicted by Predict itself.

#include <cstddef>

#include "control/common/cpu_features.hpp"
#include "control/common/ukf.hpp"
#include "control/formation/link_filter.hpp"

namespace formsim::control::formation {

/// Which code runs a batch's lanes.
enum class LanePath {
  kAuto,      ///< AVX2 when the CPU has it, else portable (the default)
  kScalar,    ///< every link by its own Predict (the reference)
  kPortable,  ///< SSE2 pairs
  kAvx2,      ///< four lanes; falls back to kPortable on a CPU without AVX2
};

/// "auto", "scalar", "portable", "avx2".
const char* LanePathName(LanePath p);
/// The path that `p` resolves to on this CPU (kAuto and kAvx2 without AVX2 become kPortable).
LanePath ResolveLanePath(LanePath p);
/// Process-wide choice of path for every LinkPredictBatch (tests compare the paths; results are
/// the same bits with each).
void SetLanePath(LanePath p);
LanePath CurrentLanePath();

/// Collects links to predict and runs them in lanes as they fill up.
class LinkPredictBatch {
 public:
  static constexpr int kLanes = 4;

  LinkPredictBatch() : path_(ResolveLanePath(CurrentLanePath())) {}
  LinkPredictBatch(const LinkPredictBatch&) = delete;
  LinkPredictBatch& operator=(const LinkPredictBatch&) = delete;
  /// Flushes.
  ~LinkPredictBatch() { Flush(); }

  /// Predicts `f` with this period's inputs; its status is in `*status` after Flush at the
  /// latest (a link that cannot take a lane is predicted at once). `f` and `status` must stay
  /// valid until then.
  void Add(LinkFilter& f, const Twist& leader, const Twist& follower, UkfStatus* status);
  /// Runs the links collected so far.
  void Flush();
  /// Links whose prediction came from a lane so far, and links that Predict ran instead (off
  /// the lanes' common path, or the scalar path).
  std::size_t laned() const { return laned_; }
  std::size_t fell_back() const { return fell_back_; }

  /// What a lane reads and writes, one array element per lane (structure of arrays).
  struct Lanes {
    alignas(32) double x[3][kLanes];
    alignas(32) double chol[3][3][kLanes];
    alignas(32) double scale[kLanes], wm0[kLanes], wm[kLanes], wc0[kLanes], wc[kLanes];
    alignas(32) double Tc[kLanes], L[kLanes], q[3][kLanes];
    alignas(32) double lv[kLanes], lw[kLanes], fv[kLanes], fw[kLanes];
    // Out: the predicted mean, the covariance's lower triangle (00, 10, 20, 11, 21, 22) and
    // whether the lane stayed on Predict's common path (else its link runs Predict).
    alignas(32) double mean[3][kLanes];
    alignas(32) double P[6][kLanes];
    alignas(32) long long ok[kLanes];
  };

 private:
  LanePath path_;
  int n_ = 0;
  LinkFilter* filter_[kLanes] = {};
  UkfStatus* status_[kLanes] = {};
  Twist leader_[kLanes], follower_[kLanes];
  std::size_t laned_ = 0, fell_back_ = 0;
  Lanes lanes_;
};

/// Runs the lanes [0, kLanes) of `l` with the given path's code (kPortable or kAvx2; the
/// latter only where CpuHasAvx2()).
void RunPredictLanes(LanePath path, LinkPredictBatch::Lanes& l);

}  // namespace formsim::control::formation
