#include "control/formation/formation_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "control/common/angle.hpp"

namespace formsim::control::formation {
namespace {

// Lattice rows: `counts[r]` slots in row r, rows `row_gap` apart, neighbours `d` apart, each
// row centred on the root's line; within a row the slots nearest the centre come first.
std::vector<Vec2> Rows(const std::vector<int>& counts, int n, double d, double row_gap) {
  std::vector<Vec2> out;
  for (std::size_t r = 0; r < counts.size() && static_cast<int>(out.size()) < n; ++r) {
    std::vector<double> ys;
    for (int c = 0; c < counts[r]; ++c) ys.push_back((0.5 * (counts[r] - 1) - c) * d);
    std::stable_sort(ys.begin(), ys.end(), [](double a, double b) {
      return std::abs(a) < std::abs(b) - 1e-12 || (std::abs(std::abs(a) - std::abs(b)) <= 1e-12 && a > b);
    });
    for (double y : ys) {
      if (static_cast<int>(out.size()) == n) break;
      out.push_back({-static_cast<double>(r) * row_gap, y});
    }
  }
  return out;
}

}  // namespace

// The slots before the root is moved to the origin.
static std::vector<Vec2> Unshifted(ShapeKind kind, int n, double d);

const std::vector<std::string>& ShapeNames() {
  static const std::vector<std::string> k = {"column", "line_abreast", "wedge",
                                             "diamond", "v",           "grid"};
  return k;
}

bool ShapeFromName(const std::string& name, ShapeKind* kind) {
  const auto& names = ShapeNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return false;
  *kind = static_cast<ShapeKind>(it - names.begin());
  return true;
}

std::vector<Vec2> ShapeSlots(ShapeKind kind, int n, double d) {
  std::vector<Vec2> out = Unshifted(kind, n, d);
  // The root's slot is the origin.
  if (!out.empty()) {
    const Vec2 o = out[0];
    for (Vec2& p : out) p = p - o;
  }
  return out;
}

static std::vector<Vec2> Unshifted(ShapeKind kind, int n, double d) {
  std::vector<Vec2> out;
  if (n < 1) return out;
  const double h = d * std::sqrt(3.0) / 2.0;  // row gap of a triangular lattice
  switch (kind) {
    case ShapeKind::kColumn:
      for (int i = 0; i < n; ++i) out.push_back({-i * d, 0.0});
      return out;
    case ShapeKind::kLineAbreast:
      // The root in the middle, then left and right alternately.
      out.push_back({0.0, 0.0});
      for (int k = 1; static_cast<int>(out.size()) < n; ++k) {
        out.push_back({0.0, ((k + 1) / 2) * d * (k % 2 == 1 ? 1.0 : -1.0)});
      }
      return out;
    case ShapeKind::kWedge: {
      std::vector<int> counts;
      for (int r = 0, total = 0; total < n; ++r) counts.push_back(r + 1), total += r + 1;
      return Rows(counts, n, d, h);
    }
    case ShapeKind::kDiamond: {
      // Rows 1, 2, ..., w, ..., 2, 1 for the smallest w holding n (w² slots).
      int w = 1;
      while (w * w < n) ++w;
      std::vector<int> counts;
      for (int r = 1; r <= w; ++r) counts.push_back(r);
      for (int r = w - 1; r >= 1; --r) counts.push_back(r);
      return Rows(counts, n, d, h);
    }
    case ShapeKind::kV:
      // Two arms back from the root at ±30° off the line behind it (a lattice's edges).
      out.push_back({0.0, 0.0});
      for (int k = 1; static_cast<int>(out.size()) < n; ++k) {
        const int a = (k + 1) / 2;
        out.push_back({-a * h, a * 0.5 * d * (k % 2 == 1 ? 1.0 : -1.0)});
      }
      return out;
    case ShapeKind::kGrid: {
      int cols = 1;
      while (cols * cols < n) ++cols;
      std::vector<int> counts((n + cols - 1) / cols, cols);
      // Square rows: the lattice rows `d` apart; the root in the middle of the front row.
      return Rows(counts, n, d, d);
    }
  }
  return out;
}

FormationShape GraphForSlots(const std::vector<Vec2>& slots, const std::vector<std::string>& names,
                             double L) {
  if (slots.empty() || slots.size() != names.size())
    throw std::invalid_argument("GraphForSlots: one slot per robot, at least one");
  FormationShape s;
  s.slots = slots;
  const int n = static_cast<int>(slots.size());
  for (int i = 0; i < n; ++i) {
    FormationNodeDef node;
    node.name = names[i];
    node.L = L;
    node.initial_pose = {slots[i].x, slots[i].y, 0.0};
    if (i == 0) {
      node.law = FormationLaw::kRoot;
      s.nodes.push_back(node);
      continue;
    }
    const Vec2 m = slots[i] + Vec2{L, 0.0};
    // The nearest robot ahead (placed before) and its distance.
    int nearest = 0;
    for (int k = 1; k < i; ++k)
      if ((m - slots[k]).Norm() < (m - slots[nearest]).Norm() - 1e-12) nearest = k;
    const double reach = 2.1 * (m - slots[nearest]).Norm();
    // Candidate leaders within reach only: the pairs stay few however large the shape.
    std::vector<int> near;
    for (int k = 0; k < i; ++k)
      if ((m - slots[k]).Norm() <= reach) near.push_back(k);
    int best_a = -1, best_b = -1;
    double best_score = -1.0;
    for (std::size_t ia = 0; ia < near.size(); ++ia)
      for (std::size_t ib = ia + 1; ib < near.size(); ++ib) {
        const int a = near[ia], b = near[ib];
        const double l1 = (m - slots[a]).Norm(), l2 = (m - slots[b]).Norm();
        const double sep = (slots[b] - slots[a]).Norm();
        if (l1 > reach || l2 > reach || !(sep > 0.0)) continue;
        const double sin_apex = std::abs((slots[a] - m).Cross(slots[b] - m)) / (l1 * l2);
        const double slack = std::min(l1 + l2 - sep, sep - std::abs(l1 - l2));
        if (sin_apex < kMinApexSin || slack < kMinTriangleSlack * sep) continue;
        // Well-shaped first, then short links.
        const double score = sin_apex - 0.1 * (l1 + l2) / reach;
        if (score > best_score + 1e-12) best_score = score, best_a = a, best_b = b;
      }
    if (best_a >= 0) {
      node.law = FormationLaw::kLL;
      node.leaders = {names[best_a], names[best_b]};
      node.l_des = (m - slots[best_a]).Norm();
      node.l2_des = (m - slots[best_b]).Norm();
    } else {
      const Vec2 r = m - slots[nearest];
      node.law = FormationLaw::kLPhi;
      node.leaders = {names[nearest]};
      node.l_des = r.Norm();
      node.phi_des = WrapTo2Pi(std::atan2(r.y, r.x));
    }
    s.nodes.push_back(node);
  }
  return s;
}

FormationShape MakeFormationShape(ShapeKind kind, const std::vector<std::string>& names,
                                  double spacing, double L) {
  if (names.empty()) throw std::invalid_argument("a formation shape needs at least one robot");
  if (!(spacing > 2.0 * L))
    throw std::invalid_argument("a formation shape needs a spacing above 2 L");
  return GraphForSlots(ShapeSlots(kind, static_cast<int>(names.size()), spacing), names, L);
}

}  // namespace formsim::control::formation
