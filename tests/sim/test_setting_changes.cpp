// Short descriptions of changed settings (sim/core/setting_changes.hpp): changes shared by
// several keys are told once, with what tells the keys apart.
#include <gtest/gtest.h>

#include "sim/core/setting_changes.hpp"

namespace formsim::sim {
namespace {

TEST(SettingChanges, SharedChangesAreFactoredOut) {
  EXPECT_EQ(FactorChanges({{"robots.R2.follow.k_l", "R2.follow.k_l", "0.15", "0.5"},
                           {"robots.R3.follow.k_l", "R3.follow.k_l", "0.15", "0.5"}}),
            "k_l 0.15 → 0.5 (R2, R3)");
  // Different values are not merged; a lone change keeps its short name; order is kept.
  EXPECT_EQ(FactorChanges({{"robots.R2.follow.k_l", "R2.follow.k_l", "0.15", "0.5"},
                           {"seed", "seed", "1", "7"},
                           {"robots.R3.follow.k_l", "R3.follow.k_l", "0.15", "0.9"},
                           {"robots.R4.follow.k_l", "R4.follow.k_l", "0.15", "0.5"}}),
            "k_l 0.15 → 0.5 (R2, R4), seed 1 → 7, R3.follow.k_l 0.15 → 0.9");
  // The keys may differ in more than one place.
  EXPECT_EQ(
      FactorChanges({{"a.x.b.gain", "x.b.gain", "1", "2"}, {"a.y.c.gain", "y.c.gain", "1", "2"}}),
      "gain 1 → 2 (x.b, y.c)");
  EXPECT_EQ(FactorChanges({}), "");
}

}  // namespace
}  // namespace formsim::sim
