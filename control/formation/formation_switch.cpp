#include "control/formation/formation_switch.hpp"

#include <cstdio>

#include "control/common/angle.hpp"

namespace formsim::control::formation {

SlotValues LerpSlot(const SlotValues& a, const SlotValues& b, double lambda) {
  SlotValues s;
  s.l_des = a.l_des + lambda * (b.l_des - a.l_des);
  s.phi_des = a.phi_des + lambda * WrapToPi(b.phi_des - a.phi_des);
  s.l2_des = a.l2_des + lambda * (b.l2_des - a.l2_des);
  return s;
}

SlotValues SlotTransition::At(int i, double t, SlotRates* rates) const {
  const double tau = (t - start) / duration;
  const SlotValues& a = from[static_cast<std::size_t>(i)];
  const SlotValues& b = to[static_cast<std::size_t>(i)];
  if (rates != nullptr) {
    const double r = MinimumJerkRate(tau) / duration;
    *rates = {r * (b.l_des - a.l_des), r * WrapToPi(b.phi_des - a.phi_des), r * (b.l2_des - a.l2_des)};
  }
  if (tau >= 1.0) return b;  // exactly the target once done
  return LerpSlot(a, b, MinimumJerk(tau));
}

std::string CheckTransition(const std::vector<FormationNodeDef>& nodes,
                            const std::vector<SlotValues>& from, const std::vector<SlotValues>& to,
                            double singular_threshold, int samples, int* robot) {
  std::vector<FormationNodeDef> at = nodes;
  for (int k = 0; k <= samples; ++k) {
    const double lambda = static_cast<double>(k) / samples;
    for (std::size_t i = 0; i < at.size(); ++i) {
      if (at[i].law == FormationLaw::kRoot) continue;
      const SlotValues s = LerpSlot(from[i], to[i], lambda);
      at[i].l_des = s.l_des;
      at[i].phi_des = s.phi_des;
      at[i].l2_des = s.l2_des;
    }
    try {
      BuildFormationGraph(at, singular_threshold);
    } catch (const FormationGraphError& e) {
      if (robot != nullptr) *robot = e.robot();
      char where[96];
      std::snprintf(where, sizeof where, " at %.0f%% of the transition (robot %s)", 100.0 * lambda,
                    nodes[static_cast<std::size_t>(e.robot())].name.c_str());
      return std::string(e.what()) + where;
    }
  }
  return "";
}

}  // namespace formsim::control::formation
