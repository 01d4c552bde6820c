// Every slider of every shipped scenario at both ends and in the middle, through the tuning
// session exactly as the GUI's widgets drive it, followed by a reset: a value is either
// accepted or refused with a reason (rules across keys, such as the l-l triangle, can refuse
// an in-range value), the run keeps stepping, a reset always succeeds, and every recorded
// number of every column stays finite.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "sim/core/number_format.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

using namespace formsim;

namespace {

// Values a widget can produce for a parameter.
std::vector<std::string> WidgetValues(const sim::Param& p) {
  switch (p.kind) {
    case sim::Param::Kind::kDouble: {
      const double lo = p.slider_min(), hi = p.slider_max();
      return {sim::FormatDouble(lo), sim::FormatDouble(hi), sim::FormatDouble(0.5 * (lo + hi))};
    }
    case sim::Param::Kind::kInt:
      return {std::to_string(static_cast<long long>(p.slider_min())),
              std::to_string(static_cast<long long>(p.slider_max()))};
    case sim::Param::Kind::kBool:
      return {"true", "false"};
    case sim::Param::Kind::kChoice:
      return p.choices;
  }
  return {};
}

// Every recorded cell is a finite number or "not sampled".
void ExpectFinite(const sim::Experiment& exp, const std::string& what) {
  const sim::Recorder& rec = exp.recorder();
  for (std::size_t r = 0; r < rec.rows(); ++r)
    for (std::size_t c = 0; c < rec.columns(); ++c) {
      const double v = rec.At(r, static_cast<int>(c));
      ASSERT_TRUE(std::isfinite(v) || sim::IsNotSampled(v))
          << what << ": " << rec.names()[c] << " row " << r << " = " << v;
    }
}

class ParamExtremes : public ::testing::TestWithParam<std::string> {};

TEST_P(ParamExtremes, EveryWidgetValueIsAcceptedOrRefusedAndTheRunStaysFinite) {
  const std::string file = GetParam();
  sim::Session s(file, {}, -1);
  ASSERT_FALSE(s.params().empty()) << file << " exposes no tunable parameters";
  std::vector<std::pair<std::string, std::vector<std::string>>> plan;
  for (const sim::Param& p : app::testing::ParamsToExercise(s.params()))
    plan.emplace_back(p.key, WidgetValues(p));
  int accepted = 0, refused = 0;
  for (const auto& [key, values] : plan) {
    for (const std::string& v : values) {
      std::string err;
      ASSERT_NO_THROW(err = s.Edit(key, v)) << file << ": " << key << "=" << v;
      if (err.empty()) ++accepted;
      else ++refused;
      for (int k = 0; k < 20 && !s.exp().finished(); ++k)
        ASSERT_NO_THROW(s.Step()) << file << ": after " << key << "=" << v;
      ExpectFinite(s.exp(), file + " after " + key + "=" + v);
    }
    // A reset after each parameter's extremes rebuilds from everything accepted so far.
    ASSERT_EQ(s.Reset(), "") << file << " after " << key;
    for (int k = 0; k < 20 && !s.exp().finished(); ++k) ASSERT_NO_THROW(s.Step());
    ExpectFinite(s.exp(), file + " after reset following " + key);
  }
  EXPECT_GT(accepted, 0) << file;
  RecordProperty("refused", refused);
}

std::vector<std::string> Scenarios() { return app::testing::PerParameterScenarios(); }

std::string Name(const ::testing::TestParamInfo<std::string>& info) {
  return std::filesystem::path(info.param).stem().string();
}

INSTANTIATE_TEST_SUITE_P(Shipped, ParamExtremes, ::testing::ValuesIn(Scenarios()), Name);

}  // namespace
