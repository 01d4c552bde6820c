// Every slider of every shipped scenario at its extremes: the experiment must keep stepping
// without throwing, crashing or writing a non-finite number into the recorded truth. This is
// what a user dragging sliders in the GUI does (the GUI clamps values to [min, max]).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "app/scenario_files.hpp"
#include "sim/core/experiment.hpp"

using namespace formsim;

namespace {

// Values a slider can produce for a parameter.
std::vector<std::string> SliderValues(const sim::Param& p) {
  char buf[64];
  switch (p.kind) {
    case sim::Param::Kind::kDouble: {
      std::vector<std::string> out;
      for (double v : {p.min, p.max, 0.5 * (p.min + p.max)}) {
        std::snprintf(buf, sizeof buf, "%.17g", v);
        out.push_back(buf);
      }
      return out;
    }
    case sim::Param::Kind::kInt:
      return {std::to_string(static_cast<int>(p.min)), std::to_string(static_cast<int>(p.max))};
    case sim::Param::Kind::kBool:
      return {"true", "false"};
    case sim::Param::Kind::kChoice:
      return p.choices;
  }
  return {};
}

class ParamExtremes : public ::testing::TestWithParam<std::string> {};

TEST_P(ParamExtremes, EverySliderValueKeepsTheRunFinite) {
  const std::string file = GetParam();
  auto exp = sim::LoadExperiment(file);
  ASSERT_TRUE(exp);
  const std::size_t n_params = exp->params().all().size();
  ASSERT_GT(n_params, 0u) << file << " exposes no tunable parameters";
  // Copy keys first: Apply may not reorder the table, but keep the loop independent of it.
  std::vector<std::pair<std::string, std::vector<std::string>>> plan;
  for (const sim::Param& p : exp->params().all())
    if (!p.requires_reset) plan.emplace_back(p.key, SliderValues(p));
  for (const auto& [key, values] : plan) {
    for (const std::string& v : values) {
      sim::PendingChanges pc;
      pc.edits.push_back({key, v});
      std::vector<std::string> errors;
      ASSERT_NO_THROW(errors = exp->Apply(pc)) << file << ": " << key << "=" << v;
      EXPECT_TRUE(errors.empty()) << file << ": a slider value was rejected: " << errors[0];
      for (int k = 0; k < 30 && !exp->finished(); ++k)
        ASSERT_NO_THROW(exp->Step()) << file << ": after " << key << "=" << v;
    }
  }
  // The true poses must stay finite whatever the controllers were asked to do.
  const sim::Recorder& rec = exp->recorder();
  for (int c = 0; c < static_cast<int>(rec.columns()); ++c) {
    const std::string& name = rec.names()[c];
    const bool truth = name.size() > 2 && (name.substr(name.size() - 2) == ".x" ||
                                           name.substr(name.size() - 2) == ".y");
    if (!truth) continue;
    for (std::size_t r = 0; r < rec.rows(); ++r)
      ASSERT_TRUE(std::isfinite(rec.At(r, c))) << file << ": " << name << " row " << r;
  }
}

std::vector<std::string> Scenarios() { return app::ShippedScenarios(); }

std::string Name(const ::testing::TestParamInfo<std::string>& info) {
  return std::filesystem::path(info.param).stem().string();
}

INSTANTIATE_TEST_SUITE_P(Shipped, ParamExtremes, ::testing::ValuesIn(Scenarios()), Name);

}  // namespace
