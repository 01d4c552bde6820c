#include "control/formation/formation_graph.hpp"
#include "control/common/number_format.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

namespace formsim::control::formation {

const char* LawName(FormationLaw law) {
  switch (law) {
    case FormationLaw::kLPhi:
      return "l_phi";
    case FormationLaw::kLL:
      return "l_l";
    case FormationLaw::kRoot:
      break;
  }
  return "root";
}

const std::vector<std::string>& FollowerLawNames() {
  static const std::vector<std::string> names = {LawName(FormationLaw::kLPhi),
                                                 LawName(FormationLaw::kLL)};
  return names;
}

bool ParseLaw(const std::string& name, FormationLaw* law) {
  for (FormationLaw l : {FormationLaw::kLPhi, FormationLaw::kLL})
    if (name == LawName(l)) {
      *law = l;
      return true;
    }
  return false;
}

std::size_t LeadersOfLaw(FormationLaw law) {
  return law == FormationLaw::kRoot ? 0 : law == FormationLaw::kLPhi ? 1 : 2;
}

namespace {

// Checks one node's own numbers and leader list; fills leader indices.
void CheckNode(const std::vector<FormationNodeDef>& nodes, int i,
               const std::map<std::string, int>& index, std::vector<int>& leaders) {
  const FormationNodeDef& n = nodes[i];
  if (n.law == FormationLaw::kRoot) {
    if (!n.leaders.empty()) throw FormationGraphError(i, "leaders", "a root leader has no leaders");
    return;
  }
  if (!(n.L > 0.0)) throw FormationGraphError(i, "L", "control point offset L must be > 0");
  if (!(n.l_des > 0.0)) throw FormationGraphError(i, "l_des", "desired distance must be > 0");
  if (n.law == FormationLaw::kLL && !(n.l2_des > 0.0))
    throw FormationGraphError(i, "l2_des", "desired distance must be > 0");
  const std::size_t want = LeadersOfLaw(n.law);
  if (n.leaders.size() != want)
    throw FormationGraphError(i, "leaders",
                              std::string("law ") + LawName(n.law) + " needs exactly " +
                                  std::to_string(want) + " leader" + (want == 1 ? "" : "s") +
                                  ", got " + std::to_string(n.leaders.size()));
  for (std::size_t a = 0; a < n.leaders.size(); ++a) {
    const std::string& ln = n.leaders[a];
    if (ln == n.name)
      throw FormationGraphError(i, "leaders", "robot '" + n.name + "' cannot follow itself");
    for (std::size_t b = 0; b < a; ++b)
      if (n.leaders[b] == ln)
        throw FormationGraphError(i, "leaders", "leader '" + ln + "' is listed twice");
    auto it = index.find(ln);
    if (it == index.end())
      throw FormationGraphError(i, "leaders",
                                "leader '" + ln + "' is not a robot of this scenario");
    leaders.push_back(it->second);
  }
}

// Finds a cycle among the nodes not yet ordered and describes it ("R2 -> R3 -> R2").
std::pair<int, std::string> DescribeCycle(const std::vector<FormationNodeDef>& nodes,
                                          const std::vector<std::vector<int>>& leaders,
                                          const std::vector<int>& remaining) {
  // Walk leader edges from a remaining node; every remaining node has a remaining leader, so
  // the walk must revisit a node.
  std::vector<int> pos(nodes.size(), -1), path;
  int cur = remaining.front();
  while (pos[cur] < 0) {
    pos[cur] = static_cast<int>(path.size());
    path.push_back(cur);
    int next = -1;
    for (int l : leaders[cur])
      if (std::find(remaining.begin(), remaining.end(), l) != remaining.end()) {
        next = l;
        break;
      }
    cur = next;
  }
  std::string text;
  for (std::size_t k = pos[cur]; k < path.size(); ++k) text += nodes[path[k]].name + " -> ";
  text += nodes[cur].name;
  return {cur, text};
}

}  // namespace

bool TriangleApex(const Vec2& p1, const Vec2& p2, double l1, double l2, int side, Vec2& apex) {
  const Vec2 d = p2 - p1;
  const double dist = d.Norm();
  if (!(dist > 0.0) || dist >= l1 + l2 || dist <= std::abs(l1 - l2)) return false;
  // Distance from p1 along d to the chord, and half chord length.
  const double a = (l1 * l1 - l2 * l2 + dist * dist) / (2.0 * dist);
  const double h = std::sqrt(std::max(0.0, l1 * l1 - a * a));
  const Vec2 u = d * (1.0 / dist), n{-u.y, u.x};
  apex = p1 + u * a + n * (h * (side >= 0 ? 1.0 : -1.0));
  return true;
}

FormationGraph BuildFormationGraph(const std::vector<FormationNodeDef>& nodes,
                                   double singular_threshold) {
  const int n = static_cast<int>(nodes.size());
  std::map<std::string, int> index;
  for (int i = 0; i < n; ++i) index[nodes[i].name] = i;

  FormationGraph g;
  g.leaders.assign(n, {});
  for (int i = 0; i < n; ++i) CheckNode(nodes, i, index, g.leaders[i]);

  // Kahn's algorithm, stable by declaration order.
  std::vector<int> indeg(n, 0);
  std::vector<std::vector<int>> followers(n);
  for (int i = 0; i < n; ++i) {
    indeg[i] = static_cast<int>(g.leaders[i].size());
    for (int l : g.leaders[i]) followers[l].push_back(i);
  }
  std::vector<bool> done(n, false);
  while (static_cast<int>(g.order.size()) < n) {
    int pick = -1;
    for (int i = 0; i < n && pick < 0; ++i)
      if (!done[i] && indeg[i] == 0) pick = i;
    if (pick < 0) {
      std::vector<int> remaining;
      for (int i = 0; i < n; ++i)
        if (!done[i]) remaining.push_back(i);
      const auto [at, text] = DescribeCycle(nodes, g.leaders, remaining);
      throw FormationGraphError(at, "leaders", "the formation graph has a cycle: " + text);
    }
    done[pick] = true;
    g.order.push_back(pick);
    for (int f : followers[pick]) --indeg[f];
  }

  // Depth, root tree, side and desired shape, in topological order.
  g.depth.assign(n, 0);
  g.root.assign(n, -1);
  g.shape.assign(n, Vec2{});
  g.side.assign(n, 0);
  for (int i : g.order) {
    const FormationNodeDef& nd = nodes[i];
    const auto& ls = g.leaders[i];
    for (int l : ls) g.depth[i] = std::max(g.depth[i], g.depth[l] + 1);
    if (nd.law == FormationLaw::kRoot) {
      g.root[i] = i;
      continue;
    }
    const int r0 = g.root[ls[0]];
    const bool same_root =
        std::all_of(ls.begin(), ls.end(), [&](int l) { return g.root[l] == r0; });
    g.root[i] = same_root ? r0 : -1;
    if (nd.law == FormationLaw::kLPhi) {
      if (r0 >= 0) {
        const Vec2 m = g.shape[ls[0]] + Vec2{std::cos(nd.phi_des), std::sin(nd.phi_des)} * nd.l_des;
        g.shape[i] = m - Vec2{nd.L, 0.0};
      }
      continue;
    }
    // l-l: the side comes from the initial poses; the triangle check from the desired shape.
    const Vec2 p1 = nodes[ls[0]].initial_pose.p(), p2 = nodes[ls[1]].initial_pose.p();
    const Vec2 m0 = ControlPoint(nd.initial_pose, nd.L);
    g.side[i] = (p2 - p1).Cross(m0 - p1) >= 0.0 ? 1 : -1;
    if (g.root[i] < 0) continue;
    const Vec2 q1 = g.shape[ls[0]], q2 = g.shape[ls[1]];
    const double sep = (q2 - q1).Norm();
    Vec2 apex;
    if (!TriangleApex(q1, q2, nd.l_des, nd.l2_des, g.side[i], apex))
      throw FormationGraphError(
          i, "l_des",
          "desired distances " + FormatSignificant(nd.l_des, 4) + " and " + FormatSignificant(nd.l2_des, 4) +
              " cannot form a triangle with the leaders' desired separation " + FormatSignificant(sep, 4) + " (" +
              nodes[ls[0]].name + "-" + nodes[ls[1]].name + "): need |l1 - l2| < " + FormatSignificant(sep, 4) +
              " < l1 + l2");
    // sin of the angle at the apex between the two leader directions = det of the l-l law.
    const Vec2 a = q1 - apex, b = q2 - apex;
    const double s = std::abs(a.Cross(b)) / (a.Norm() * b.Norm());
    if (s < singular_threshold)
      throw FormationGraphError(i, "l_des",
                                "desired triangle with " + nodes[ls[0]].name + " and " +
                                    nodes[ls[1]].name + " is nearly flat (|sin| = " + FormatSignificant(s, 4) +
                                    " < singular_threshold " + FormatSignificant(singular_threshold, 4) + ")");
    g.shape[i] = apex - Vec2{nd.L, 0.0};
  }
  return g;
}

}  // namespace formsim::control::formation
