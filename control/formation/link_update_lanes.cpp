#include "control/formation/link_update_lanes.hpp"

namespace formsim::control::formation {

void LinkUpdateBatch::Add(LinkFilter& f, const LinkState& measured, UkfStatus* status) {
  LinkUpdateBasis b;
  const int m = path_ == LanePath::kScalar ? 0 : f.UpdateBasis(b);
  if (m != 2 && m != 3) {
    *status = f.Update(measured);
    ++fell_back_;
    return;
  }
  Set& s = sets_[m - 2];
  const int i = s.n++;
  s.filter[i] = &f;
  s.status[i] = status;
  s.measured[i] = measured;
  Lanes& l = s.lanes;
  l.z[0][i] = measured.l, l.z[1][i] = measured.phi, l.z[2][i] = measured.alpha;
  for (int k = 0; k < 3; ++k) {
    l.x[k][i] = b.x[k];
    l.r[k][i] = b.r[k];
    for (int c = 0; c < 3; ++c) l.P[k][c][i] = b.P[c * 3 + k];  // column-major in
  }
  if (s.n == kLanes) Run(m, s);
}

void LinkUpdateBatch::Flush() {
  for (int m : {2, 3})
    if (sets_[m - 2].n > 0) Run(m, sets_[m - 2]);
}

void LinkUpdateBatch::Run(int measured, Set& s) {
  Lanes& l = s.lanes;
  // Unused lanes repeat lane 0 (their results are dropped).
  for (int i = s.n; i < kLanes; ++i)
    for (int k = 0; k < 3; ++k) {
      l.x[k][i] = l.x[k][0], l.z[k][i] = l.z[k][0], l.r[k][i] = l.r[k][0];
      for (int c = 0; c < 3; ++c) l.P[k][c][i] = l.P[k][c][0];
    }
  RunUpdateLanes(path_, measured, l);
  for (int i = 0; i < s.n; ++i) {
    if (!l.ok[i]) {
      // Off the common path somewhere: Update itself (nothing of the filter changed yet).
      *s.status[i] = s.filter[i]->Update(s.measured[i]);
      ++fell_back_;
      continue;
    }
    s.filter[i]->AcceptUpdate(
        {&l.x_out[0][i], &l.P_out[0][0][i], &l.L_out[0][0][i], kLanes, l.nis[i]});
    *s.status[i] = UkfStatus::kOk;
    ++laned_;
  }
  s.n = 0;
}

}  // namespace formsim::control::formation
