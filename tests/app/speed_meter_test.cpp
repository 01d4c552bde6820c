// The run indicator's achieved speed: simulated seconds per wall second over the last second,
// and "behind" once the run has fallen under the chosen speed for more than a second.
#include "app/gui/speed_meter.hpp"

#include <gtest/gtest.h>

namespace formsim::app {
namespace {

TEST(SpeedMeter, MarksBehindWhenTheRunCannotKeepUp) {
  SpeedMeter m;
  for (int i = 0; i < 120; ++i) m.Add(1.0 / 60, 0.65 / 60, 1.0, true);  // two seconds at 0.65x
  EXPECT_NEAR(m.achieved(), 0.65, 1e-6);
  EXPECT_TRUE(m.behind());
  EXPECT_EQ(m.Label(), "achieved 0.65x, behind");
  for (int i = 0; i < 300; ++i) m.Add(1.0 / 60, 1.0 / 60, 1.0, true);  // catches up
  EXPECT_NEAR(m.achieved(), 1.0, 0.01);
  EXPECT_FALSE(m.behind());
  EXPECT_EQ(m.Label(), "achieved 1.00x");
}

TEST(SpeedMeter, AShortHitchIsNotBehindAndPausingStartsAfresh) {
  SpeedMeter m;
  for (int i = 0; i < 60; ++i) m.Add(1.0 / 60, 2.0 / 60, 2.0, true);
  for (int i = 0; i < 30; ++i) m.Add(1.0 / 60, 0.0, 2.0, true);  // half a second stalled
  EXPECT_FALSE(m.behind());
  m.Add(1.0 / 60, 0.0, 2.0, false);
  EXPECT_EQ(m.Label(), "");
  EXPECT_EQ(m.achieved(), 0.0);
  for (int i = 0; i < 200; ++i) m.Add(1.0 / 60, 1.0 / 60, 0.0, true);  // "max": never behind
  EXPECT_FALSE(m.behind());
}

}  // namespace
}  // namespace formsim::app
