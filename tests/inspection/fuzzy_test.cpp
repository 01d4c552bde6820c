// The fuzzy controller with the shipped rule base (assets/fuzzy/inspection.fll).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "control/inspection/fuzzy_controller.hpp"

namespace ins = formsim::control::inspection;

namespace {

const std::string kFll = std::string(FORMSIM_SOURCE_DIR) + "/assets/fuzzy/inspection.fll";

std::string ReadFll() {
  std::ifstream in(kFll);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

}  // namespace

TEST(Fuzzy, LoadsTheShippedRuleBase) {
  ins::FuzzyController fc;
  ASSERT_NO_THROW(fc.LoadFile(kFll));
  EXPECT_EQ(fc.rules().size(), 45u);  // 9 x 5
  ASSERT_EQ(fc.variables().size(), 5u);
  EXPECT_EQ(fc.variables()[0].terms.size(), 9u);                  // s
  EXPECT_EQ(fc.variables()[1].terms.size(), 5u);                  // dphi
  EXPECT_EQ(fc.variables()[2].terms.size(), 5u);                  // u1
  EXPECT_EQ(fc.variables()[4].terms.size(), 9u);                  // u3
  EXPECT_NEAR(fc.variables()[4].terms[4].centroid, 360.0, 1e-6);  // u3 Z
  EXPECT_NEAR(fc.variables()[2].terms[0].centroid, 0.0, 1e-6);    // u1 STOP
}

TEST(Fuzzy, CentredAndAlignedDrivesStraight) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  const auto out = fc.Process(0.0, 0.0);
  ASSERT_TRUE(out.ok);
  EXPECT_DOUBLE_EQ(out.u1, out.u2);
  EXPECT_NEAR(out.u1, 3.0, 1e-9);
  EXPECT_NEAR(out.u3, 360.0, 1e-9);
  // Only "s is Z and dphi is Z" fires, fully.
  double total = 0.0;
  for (const auto& r : fc.rules()) {
    total += r.strength;
    if (r.s == "Z" && r.dphi == "Z") {
      EXPECT_NEAR(r.strength, 1.0, 1e-12);
    } else {
      EXPECT_NEAR(r.strength, 0.0, 1e-12);
    }
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
}

TEST(Fuzzy, CorrectsTowardsThePathOnEachSide) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  // Right of the path: steer left (u3 < 360), left wheel no faster than the right.
  auto right = fc.Process(0.5, 0.0);
  EXPECT_LT(right.u3, 360.0 - 35.0);
  EXPECT_LT(right.u1, right.u2);
  auto left = fc.Process(-0.5, 0.0);
  EXPECT_GT(left.u3, 360.0 + 35.0);
  EXPECT_GT(left.u1, left.u2);
  // Small offsets give small, same-signed corrections.
  EXPECT_LT(fc.Process(0.05, 0.0).u3, 360.0);
  EXPECT_GT(fc.Process(0.05, 0.0).u3, 360.0 - 35.0);
  EXPECT_GT(fc.Process(-0.05, 0.0).u3, 360.0);
  // Pointing right of the path: steer left; pointing left: steer right.
  EXPECT_LT(fc.Process(0.0, 10.0).u3, 360.0);
  EXPECT_GT(fc.Process(0.0, -10.0).u3, 360.0);
  // Far right but already approaching at 15°: hold the approach (straight).
  EXPECT_NEAR(fc.Process(1.2, -15.0).u3, 360.0, 1e-9);
  // Large errors slow the robot down.
  EXPECT_LT(fc.Process(1.2, 0.0).u2, fc.Process(0.0, 0.0).u2);
}

TEST(Fuzzy, MirrorSymmetricAndPartitionOfUnity) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  for (double s = -1.6; s <= 1.6; s += 0.13) {
    for (double d = -16.0; d <= 16.0; d += 1.7) {
      const auto a = fc.Process(s, d);
      double total = 0.0;
      for (const auto& r : fc.rules()) total += r.strength;
      EXPECT_NEAR(total, 1.0, 1e-9) << s << " " << d;
      const auto b = fc.Process(-s, -d);
      ASSERT_TRUE(a.ok && b.ok);
      EXPECT_NEAR(a.u3 - 360.0, -(b.u3 - 360.0), 1e-9);
      EXPECT_NEAR(a.u1, b.u2, 1e-9);
      EXPECT_GE(a.u1, 0.0);
      EXPECT_LE(a.u1, 4.0);
      EXPECT_GE(a.u3, 220.0);
      EXPECT_LE(a.u3, 500.0);
    }
  }
}

TEST(Fuzzy, NeverOutputsNaN) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  const auto out = fc.Process(std::nan(""), INFINITY);
  EXPECT_TRUE(std::isfinite(out.u1) && std::isfinite(out.u2) && std::isfinite(out.u3));
  // A rule base that covers only part of the input space: outside it nothing fires.
  std::string fll = ReadFll();
  std::string partial =
      fll.substr(0, fll.find("  rule:")) +
      "  rule: if s is Z and dphi is Z then u1 is FAST and u2 is FAST and u3 is Z\n";
  fc.LoadText(partial, "partial.fll");
  const auto none = fc.Process(1.2, 0.0);
  EXPECT_FALSE(none.ok);
  EXPECT_EQ(none.u1, 0.0);
  EXPECT_EQ(none.u2, 0.0);
  EXPECT_EQ(none.u3, 360.0);
}

TEST(Fuzzy, BadFilesAreClearErrorsAndKeepTheOldEngine) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  const std::string fll = ReadFll();
  auto expect_error = [&](const std::string& text, const std::string& needle) {
    try {
      fc.LoadText(text, "edited.fll");
      FAIL() << "expected an error containing " << needle;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("edited.fll"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_error(Replace(fll, "InputVariable: dphi", "InputVariable: heading"), "dphi");
  expect_error(Replace(fll, "then u1 is MID", "then u1 is MEDIUM"), "cannot load rule");
  expect_error(
      Replace(fll, "defuzzifier: WeightedAverage TakagiSugeno", "defuzzifier: Centroid 100"),
      "WeightedAverage");
  EXPECT_THROW(fc.LoadFile("/nonexistent/rules.fll"), std::runtime_error);
  // The old engine is still there.
  EXPECT_EQ(fc.rules().size(), 45u);
  EXPECT_NEAR(fc.Process(0.0, 0.0).u3, 360.0, 1e-9);
}
