#include "control/formation/link_predict_lanes.hpp"

#include <atomic>
#include <cmath>
#include <cstring>

#include "control/formation/link_update_lanes.hpp"

namespace formsim::control::formation {
namespace {

std::atomic<LanePath> g_path{LanePath::kAuto};

using Lanes = LinkPredictBatch::Lanes;
using UpdateLanes_ = LinkUpdateBatch::Lanes;

// The kernel twice, each copy with internal linkage and its own vector width: the portable one
// in SSE2 pairs (x86-64's baseline), the AVX2 one compiled for AVX2 alone (no FMA: a product
// and a sum stay two roundings) and reached only after the CPU check.
namespace portable {
typedef double V __attribute__((vector_size(16)));
using M = decltype(V{} < V{});
constexpr int W = 2;
#define FORMSIM_LANE_FN inline __attribute__((always_inline))
#include "control/formation/link_predict_lanes.inc"
#include "control/formation/link_update_lanes.inc"
#undef FORMSIM_LANE_FN
}  // namespace portable

// x86 only: other targets (the WebAssembly build) have the portable lanes alone.
#if defined(__x86_64__) || defined(__i386__)
#define FORMSIM_HAVE_AVX2_LANES 1
namespace avx2 {
typedef double V __attribute__((vector_size(32)));
using M = decltype(V{} < V{});
constexpr int W = 4;
#define FORMSIM_LANE_FN inline __attribute__((always_inline, target("avx2")))
#include "control/formation/link_predict_lanes.inc"
#include "control/formation/link_update_lanes.inc"
#undef FORMSIM_LANE_FN
__attribute__((target("avx2"))) void Run(Lanes& l) {
  RunLanes(l, 0);
}
__attribute__((target("avx2"))) void RunUpdate(int measured, UpdateLanes_& l) {
  if (measured == 3)
    UpdateLanes<3>(l, 0);
  else
    UpdateLanes<2>(l, 0);
}
}  // namespace avx2
static_assert(LinkPredictBatch::kLanes == avx2::W);
#endif

static_assert(LinkPredictBatch::kLanes % portable::W == 0);

}  // namespace

const char* LanePathName(LanePath p) {
  switch (p) {
    case LanePath::kAuto:
      return "auto";
    case LanePath::kScalar:
      return "scalar";
    case LanePath::kPortable:
      return "portable";
    case LanePath::kAvx2:
      return "avx2";
  }
  return "?";
}

LanePath ResolveLanePath(LanePath p) {
  if (p == LanePath::kScalar) return p;
  if (p == LanePath::kPortable) return p;
  return CpuHasAvx2() ? LanePath::kAvx2 : LanePath::kPortable;
}

void SetLanePath(LanePath p) {
  g_path.store(p, std::memory_order_relaxed);
}
LanePath CurrentLanePath() {
  return g_path.load(std::memory_order_relaxed);
}

void RunPredictLanes(LanePath path, Lanes& l) {
#ifdef FORMSIM_HAVE_AVX2_LANES
  if (path == LanePath::kAvx2 && CpuHasAvx2()) {
    avx2::Run(l);
    return;
  }
#else
  (void)path;
#endif
  for (int base = 0; base < LinkPredictBatch::kLanes; base += portable::W)
    portable::RunLanes(l, base);
}

void RunUpdateLanes(LanePath path, int measured, UpdateLanes_& l) {
#ifdef FORMSIM_HAVE_AVX2_LANES
  if (path == LanePath::kAvx2 && CpuHasAvx2()) {
    avx2::RunUpdate(measured, l);
    return;
  }
#else
  (void)path;
#endif
  for (int base = 0; base < LinkUpdateBatch::kLanes; base += portable::W) {
    if (measured == 3)
      portable::UpdateLanes<3>(l, base);
    else
      portable::UpdateLanes<2>(l, base);
  }
}

void LinkPredictBatch::Add(LinkFilter& f, const Twist& leader, const Twist& follower,
                           UkfStatus* status) {
  LinkPredictBasis b;
  if (path_ == LanePath::kScalar || !f.PredictBasis(b)) {
    *status = f.Predict(leader, follower);
    ++fell_back_;
    return;
  }
  const int i = n_++;
  filter_[i] = &f;
  status_[i] = status;
  leader_[i] = leader;
  follower_[i] = follower;
  Lanes& l = lanes_;
  for (int k = 0; k < 3; ++k) l.x[k][i] = b.x(k);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) l.chol[r][c][i] = b.chol(r, c);
  l.scale[i] = b.scale;
  l.wm0[i] = b.wm0, l.wm[i] = b.wm, l.wc0[i] = b.wc0, l.wc[i] = b.wc;
  l.Tc[i] = b.Tc, l.L[i] = b.L;
  for (int k = 0; k < 3; ++k) l.q[k][i] = b.q(k);
  l.lv[i] = leader.v, l.lw[i] = leader.w, l.fv[i] = follower.v, l.fw[i] = follower.w;
  if (n_ == kLanes) Flush();
}

void LinkPredictBatch::Flush() {
  if (n_ == 0) return;
  Lanes& l = lanes_;
  // Unused lanes repeat lane 0 (their results are dropped).
  for (int i = n_; i < kLanes; ++i) {
    for (int k = 0; k < 3; ++k) l.x[k][i] = l.x[k][0];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) l.chol[r][c][i] = l.chol[r][c][0];
    l.scale[i] = l.scale[0];
    l.wm0[i] = l.wm0[0], l.wm[i] = l.wm[0], l.wc0[i] = l.wc0[0], l.wc[i] = l.wc[0];
    l.Tc[i] = l.Tc[0], l.L[i] = l.L[0];
    for (int k = 0; k < 3; ++k) l.q[k][i] = l.q[k][0];
    l.lv[i] = l.lv[0], l.lw[i] = l.lw[0], l.fv[i] = l.fv[0], l.fw[i] = l.fw[0];
  }
  RunPredictLanes(path_, l);
  for (int i = 0; i < n_; ++i) {
    if (!l.ok[i]) {
      // Off the common path somewhere: Predict itself (nothing of the filter changed yet).
      *status_[i] = filter_[i]->Predict(leader_[i], follower_[i]);
      ++fell_back_;
      continue;
    }
    // PredictSigma's Symmetrize: the upper triangle mirrors the lower.
    Eigen::Matrix3d P;
    P << l.P[0][i], l.P[1][i], l.P[2][i],  //
        l.P[1][i], l.P[3][i], l.P[4][i],   //
        l.P[2][i], l.P[4][i], l.P[5][i];
    ++laned_;
    *status_[i] =
        filter_[i]->AcceptPrediction(Eigen::Vector3d(l.mean[0][i], l.mean[1][i], l.mean[2][i]), P);
  }
  n_ = 0;
}

}  // namespace formsim::control::formation
