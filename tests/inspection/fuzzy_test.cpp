// The fuzzy controller with the shipped rule base (assets/fuzzy/inspection.fll): the rule table
// cell by cell, the paper's weighted-average defuzzification of partly fired rules against an
// independent computation, symmetry, and bad files.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

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

// ---- The designed rule base, written out independently of the FLL file. ----
const std::array<const char*, 9> kS = {"NB", "NBM", "NS", "NSM", "Z", "PSM", "PS", "PBM", "PB"};
const std::array<const char*, 5> kD = {"NB", "NS", "Z", "PS", "PB"};
const std::array<const char*, 5> kSpeed = {"STOP", "SLOW", "MID", "FAST", "FULL"};
// Peaks of the input terms (NB / PB are ramps, full from the outer value on).
const std::array<double, 9> kSPeak = {-0.3, -0.1, -0.04, -0.015, 0.0, 0.015, 0.04, 0.1, 0.3};
const std::array<double, 5> kDPeak = {-12.0, -4.0, 0.0, 4.0, 12.0};
// Steering table (u3 term per cell, rows s, columns dphi), as in the FLL header.
const char* const kSteer[9][5] = {{"PB", "PB", "PB", "PS", "Z"},     {"PB", "PB", "PB", "PS", "Z"},
                                  {"PB", "PB", "PBM", "PSM", "NSM"}, {"PB", "PB", "PS", "Z", "NS"},
                                  {"PB", "PS", "Z", "NS", "NB"},     {"PS", "Z", "NS", "NB", "NB"},
                                  {"PSM", "NSM", "NBM", "NB", "NB"}, {"Z", "NS", "NB", "NB", "NB"},
                                  {"Z", "NS", "NB", "NB", "NB"}};
// Speed levels u1 / u2 per cell.
const int kLeft[9][5] = {{2, 2, 2, 2, 2}, {2, 2, 2, 2, 2}, {3, 3, 3, 3, 3},
                         {3, 3, 3, 3, 3}, {3, 3, 3, 3, 2}, {3, 3, 3, 2, 2},
                         {3, 3, 2, 2, 2}, {2, 2, 1, 1, 1}, {2, 2, 1, 1, 1}};
const int kRight[9][5] = {{1, 1, 1, 2, 2}, {1, 1, 1, 2, 2}, {2, 2, 2, 3, 3},
                          {2, 2, 3, 3, 3}, {2, 3, 3, 3, 3}, {3, 3, 3, 3, 3},
                          {3, 3, 3, 3, 3}, {2, 2, 2, 2, 2}, {2, 2, 2, 2, 2}};

int U3Index(const std::string& term) {
  for (int i = 0; i < 9; ++i)
    if (term == kS[i]) return i;  // the u3 terms carry the same names as the s terms
  return -1;
}

// Membership functions of the FLL, written out (triangles a-b-c; ramps).
double Tri(double x, double a, double b, double c) {
  if (x <= a || x >= c) return x == b ? 1.0 : 0.0;
  return x < b ? (x - a) / (b - a) : (c - x) / (c - b);
}
double RampUp(double x, double a, double b) {
  return std::clamp((x - a) / (b - a), 0.0, 1.0);
}
std::array<double, 9> MuS(double s) {
  const auto& p = kSPeak;
  return {RampUp(-s, 0.1, 0.3),       Tri(s, -0.3, -0.1, -0.04),  Tri(s, -0.1, -0.04, -0.015),
          Tri(s, -0.04, -0.015, 0.0), Tri(s, -0.015, 0.0, 0.015), Tri(s, 0.0, 0.015, 0.04),
          Tri(s, 0.015, 0.04, 0.1),   Tri(s, 0.04, 0.1, 0.3),     RampUp(s, p[7], p[8])};
}
std::array<double, 5> MuD(double d) {
  return {RampUp(-d, 4.0, 12.0), Tri(d, -12.0, -4.0, 0.0), Tri(d, -4.0, 0.0, 4.0),
          Tri(d, 0.0, 4.0, 12.0), RampUp(d, 4.0, 12.0)};
}

// The paper's weighted average over the universe, computed here from scratch: Mamdani rules
// (strength = min of the two memberships), each consequent triangle clipped at its rule's
// strength, aggregated by max, then x0 = Σ x_i u_i / Σ u_i over `n` elements x_i evenly spread
// over [lo, hi] (cell midpoints, as fuzzylite's Centroid samples them).
struct Reference {
  double u1, u2, u3;
};
Reference Evaluate(double s, double d) {
  const auto ms = MuS(s);
  const auto md = MuD(d);
  auto defuzz = [&](double lo, double hi, int n, double spacing, auto&& term_of_cell) {
    double num = 0.0, den = 0.0;
    const double dx = (hi - lo) / n;
    for (int i = 0; i < n; ++i) {
      const double x = lo + (i + 0.5) * dx;
      double mu = 0.0;
      for (int a = 0; a < 9; ++a)
        for (int b = 0; b < 5; ++b) {
          const double w = std::min(ms[a], md[b]);
          if (w <= 0.0) continue;
          const double peak = term_of_cell(a, b);
          mu = std::max(mu, std::min(w, Tri(x, peak - spacing, peak, peak + spacing)));
        }
      num += x * mu;
      den += mu;
    }
    return num / den;
  };
  Reference r;
  r.u1 = defuzz(0.0, 4.0, 401, 1.0, [](int a, int b) { return double(kLeft[a][b]); });
  r.u2 = defuzz(0.0, 4.0, 401, 1.0, [](int a, int b) { return double(kRight[a][b]); });
  r.u3 = defuzz(220.0, 500.0, 281, 35.0,
                [](int a, int b) { return 220.0 + 35.0 * U3Index(kSteer[a][b]); });
  return r;
}

}  // namespace

TEST(Fuzzy, LoadsTheShippedRuleBaseWithThePapersStructure) {
  ins::FuzzyController fc;
  ASSERT_NO_THROW(fc.LoadFile(kFll));
  EXPECT_EQ(fc.rules().size(), 45u);  // 9 x 5
  ASSERT_EQ(fc.variables().size(), 5u);
  const auto& v = fc.variables();
  EXPECT_EQ(v[0].terms.size(), 9u);  // s
  EXPECT_EQ(v[1].terms.size(), 5u);  // dphi
  EXPECT_EQ(v[2].terms.size(), 5u);  // u1
  EXPECT_EQ(v[3].terms.size(), 5u);  // u2
  EXPECT_EQ(v[4].terms.size(), 9u);  // u3
  EXPECT_EQ(v[0].min, -1.5);
  EXPECT_EQ(v[0].max, 1.5);
  EXPECT_EQ(v[1].min, -15.0);
  EXPECT_EQ(v[1].max, 15.0);
  EXPECT_EQ(v[2].min, 0.0);
  EXPECT_EQ(v[2].max, 4.0);
  EXPECT_EQ(v[4].min, 220.0);
  EXPECT_EQ(v[4].max, 500.0);
  // The input terms are a partition of unity over the whole universe.
  for (int k = 0; k < 2; ++k)
    for (std::size_t i = 0; i < v[k].terms[0].x.size(); ++i) {
      double sum = 0.0;
      for (const auto& t : v[k].terms) sum += t.y[i];
      EXPECT_NEAR(sum, 1.0, 1e-12) << v[k].name << " at " << v[k].terms[0].x[i];
    }
}

TEST(Fuzzy, RuleTableCellByCell) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  std::map<std::pair<std::string, std::string>, const ins::FuzzyRuleInfo*> cells;
  for (const auto& r : fc.rules()) cells[{r.s, r.dphi}] = &r;
  ASSERT_EQ(cells.size(), 45u);  // every cell exactly once
  // A single-term centroid over the universe: the peak, except the half triangles at the ends.
  auto u3_of = [](int index) {
    return index == 0 ? 220.0 + 35.0 / 3.0 : index == 8 ? 500.0 - 35.0 / 3.0 : 220.0 + 35.0 * index;
  };
  auto level_of = [](int level) {
    return level == 0 ? 1.0 / 3.0 : level == 4 ? 4.0 - 1.0 / 3.0 : level;
  };
  for (int a = 0; a < 9; ++a)
    for (int b = 0; b < 5; ++b) {
      SCOPED_TRACE(std::string("s is ") + kS[a] + ", dphi is " + kD[b]);
      const auto it = cells.find({kS[a], kD[b]});
      ASSERT_NE(it, cells.end());
      EXPECT_EQ(it->second->u3, kSteer[a][b]);
      EXPECT_EQ(it->second->u1, kSpeed[kLeft[a][b]]);
      EXPECT_EQ(it->second->u2, kSpeed[kRight[a][b]]);
      // At the two terms' peaks that rule alone fires, fully; the output is its terms'
      // centroids (within the discretisation of the universe).
      const auto out = fc.Process(kSPeak[a], kDPeak[b]);
      ASSERT_TRUE(out.ok);
      for (const auto& r : fc.rules())
        EXPECT_EQ(r.strength, &r == it->second ? 1.0 : 0.0) << r.text;
      EXPECT_NEAR(out.u3, u3_of(U3Index(kSteer[a][b])), 0.05);
      EXPECT_NEAR(out.u1, level_of(kLeft[a][b]), 0.002);
      EXPECT_NEAR(out.u2, level_of(kRight[a][b]), 0.002);
    }
}

TEST(Fuzzy, PartlyFiredRulesDefuzzifyByTheWeightedAverageOverTheUniverse) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  // s = 1 cm: Z 1/3, PSM 2/3; dphi = 1 deg: Z 3/4, PS 1/4. Four rules fire with min strengths
  // Z/Z 1/3 -> Z, Z/PS 1/4 -> NS, PSM/Z 2/3 -> NS, PSM/PS 1/4 -> NB; NS is clipped at 2/3, Z at
  // 1/3, NB at 1/4. Their union's centre of area lies between NS (290) and Z (360), nearer NS.
  const auto out = fc.Process(0.01, 1.0);
  ASSERT_TRUE(out.ok);
  std::map<std::string, double> fired;
  for (const auto& r : fc.rules())
    if (r.strength > 0.0) fired[r.s + "/" + r.dphi] = r.strength;
  ASSERT_EQ(fired.size(), 4u);
  EXPECT_NEAR(fired["Z/Z"], 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(fired["Z/PS"], 0.25, 1e-12);
  EXPECT_NEAR(fired["PSM/Z"], 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(fired["PSM/PS"], 0.25, 1e-12);
  const Reference ref = Evaluate(0.01, 1.0);
  EXPECT_NEAR(out.u3, ref.u3, 1e-9);
  EXPECT_NEAR(out.u1, ref.u1, 1e-9);
  EXPECT_NEAR(out.u2, ref.u2, 1e-9);
  EXPECT_GT(out.u3, 290.0);
  EXPECT_LT(out.u3, 325.0);
  // Not the weighted average of the term peaks (Takagi-Sugeno): that would be
  // (360/3 + 290·2/3 + 232·1/4) / (1/3 + 2/3 + 1/4) = 297.
  EXPECT_GT(std::abs(out.u3 - 297.0), 5.0);
  // The aggregated output set the controller shows is the same union.
  const auto& u3 = fc.variables()[4];
  double peak = 0.0;
  for (double y : u3.output_set.y) peak = std::max(peak, y);
  EXPECT_NEAR(peak, 2.0 / 3.0, 1e-12);

  // More points across the table, against the same independent computation.
  for (double s : {-0.7, -0.2, -0.05, -0.022, 0.003, 0.027, 0.07, 0.2})
    for (double d : {-13.0, -6.5, -1.2, 2.5, 7.0}) {
      const auto o = fc.Process(s, d);
      const Reference r = Evaluate(s, d);
      EXPECT_NEAR(o.u3, r.u3, 1e-9) << s << " " << d;
      EXPECT_NEAR(o.u1, r.u1, 1e-9) << s << " " << d;
      EXPECT_NEAR(o.u2, r.u2, 1e-9) << s << " " << d;
    }
}

TEST(Fuzzy, CorrectsTowardsThePathOnEachSide) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  const auto centre = fc.Process(0.0, 0.0);
  EXPECT_DOUBLE_EQ(centre.u1, centre.u2);
  EXPECT_NEAR(centre.u3, 360.0, 1e-9);
  // Right of the path: steer left (u3 < 360), left wheel no faster than the right.
  auto right = fc.Process(0.5, 0.0);
  EXPECT_LT(right.u3, 360.0 - 3 * 35.0);
  EXPECT_LT(right.u1, right.u2);
  auto left = fc.Process(-0.5, 0.0);
  EXPECT_GT(left.u3, 360.0 + 3 * 35.0);
  EXPECT_GT(left.u1, left.u2);
  // Small offsets give small, same-signed corrections.
  EXPECT_LT(fc.Process(0.005, 0.0).u3, 360.0);
  EXPECT_GT(fc.Process(0.005, 0.0).u3, 360.0 - 35.0);
  EXPECT_GT(fc.Process(-0.005, 0.0).u3, 360.0);
  // Pointing right of the path: steer left; pointing left: steer right.
  EXPECT_LT(fc.Process(0.0, 10.0).u3, 360.0);
  EXPECT_GT(fc.Process(0.0, -10.0).u3, 360.0);
  // Far right but already approaching at 15°: hold the approach (straight).
  EXPECT_NEAR(fc.Process(1.2, -15.0).u3, 360.0, 1e-9);
  // Large errors slow the robot down.
  EXPECT_LT(fc.Process(1.2, 0.0).u2, fc.Process(0.0, 0.0).u2);
  // The steering needed on the 2.5 m turn (13.5°, 63 servo units) comes with an offset under
  // 2 cm: the controller knows nothing of the curvature.
  EXPECT_GT(fc.Process(-0.02, 0.0).u3, 360.0 + 63.0);
}

// An input scale stretches the terms: the controller scaled by k at k·s decides exactly as the
// unscaled one at s, the curves and ranges it reports are stretched, and reloading keeps it.
TEST(Fuzzy, InputScalesStretchTheTerms) {
  ins::FuzzyController plain, scaled;
  plain.LoadFile(kFll);
  scaled.LoadFile(kFll);
  scaled.SetInputScales(4.0, 0.5);
  for (double s : {-0.3, -0.02, 0.0, 0.013, 0.07, 0.25})
    for (double d : {-12.0, -3.0, 0.0, 5.0}) {
      const auto a = plain.Process(s, d), b = scaled.Process(4.0 * s, 0.5 * d);
      EXPECT_EQ(a.u1, b.u1);
      EXPECT_EQ(a.u2, b.u2);
      EXPECT_EQ(a.u3, b.u3);
    }
  // The turn's 63 servo units now need four times the offset.
  EXPECT_LT(scaled.Process(-0.02, 0.0).u3, 360.0 + 63.0);
  EXPECT_GT(scaled.Process(-0.08, 0.0).u3, 360.0 + 63.0);
  const auto& sv = scaled.variables()[0];
  const auto& pv = plain.variables()[0];
  ASSERT_EQ(sv.name, "s");
  EXPECT_DOUBLE_EQ(sv.max, 4.0 * pv.max);
  EXPECT_DOUBLE_EQ(sv.terms[0].x.back(), 4.0 * pv.terms[0].x.back());
  scaled.Process(0.1, 1.0);
  EXPECT_DOUBLE_EQ(sv.value, 0.1);
  EXPECT_DOUBLE_EQ(scaled.variables()[1].value, 1.0);
  scaled.LoadFile(kFll);
  EXPECT_EQ(scaled.s_scale(), 4.0);
  EXPECT_DOUBLE_EQ(scaled.variables()[0].max, 4.0 * pv.max);
  EXPECT_THROW(scaled.SetInputScales(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(scaled.SetInputScales(1.0, NAN), std::invalid_argument);
}

TEST(Fuzzy, MirrorSymmetricAndWithinTheOutputRanges) {
  ins::FuzzyController fc;
  fc.LoadFile(kFll);
  for (double s = -1.6; s <= 1.6; s += 0.026) {
    for (double d = -16.0; d <= 16.0; d += 1.7) {
      const auto a = fc.Process(s, d);
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
  expect_error(Replace(fll, "defuzzifier: Centroid 281", "defuzzifier: WeightedAverage Automatic"),
               "Centroid");
  EXPECT_THROW(fc.LoadFile("/nonexistent/rules.fll"), std::runtime_error);
  // The old engine is still there.
  EXPECT_EQ(fc.rules().size(), 45u);
  EXPECT_NEAR(fc.Process(0.0, 0.0).u3, 360.0, 1e-9);
}
