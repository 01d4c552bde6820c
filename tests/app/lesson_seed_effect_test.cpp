// A seed effect the runs do not show: `formsim lessons check` warns (and exits 1) when a check
// the lesson's text says depends on the seed ("varies from seed to seed", "on 24 of the first
// 30 seeds", a share < 1) has the same value on every seed checked. A fixture lesson that claims
// one is flagged; no shipped lesson is.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "sim/scenario/scenario.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/study/lesson_checks.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

// lphi_time_constant with one more sentence: its τ_l "varies from seed to seed". The lesson has
// no noise, so τ_l is the same on every seed.
TEST(LessonSeedEffect, AClaimTheRunsDoNotShowIsFlagged) {
  const std::string dir = TempDir("lesson_seed_effect");
  std::string text = ReadText(sim::ResolveLesson("lphi_time_constant"));
  const std::string goal = "  goal: >-\n";
  const auto at = text.find(goal);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + goal.size(), "    Its time constant varies from seed to seed {tau_l}.\n");
  const std::string file = dir + "/lphi_seed_claim.yaml";
  std::ofstream(file) << text;
  const std::string log = dir + "/log.txt";
  EXPECT_EQ(RunShell(Binary() + " lessons check " + file + " --seeds 1,2 --jobs 2", log), 1);
  const std::string out = ReadText(log);
  EXPECT_NE(out.find("warning: lphi_seed_claim: check tau_l is "), std::string::npos) << out;
  EXPECT_NE(out.find("on every one of the 2 seeds checked, yet the lesson's text says it depends "
                     "on the seed: \"Its time constant varies from seed to seed {tau_l}.\""),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("1 claim a seed effect their values do not show"), std::string::npos) << out;
  EXPECT_EQ(out.find(" FAILS"), std::string::npos) << out;  // every check holds; the claim does not
  // The lesson as shipped: no warning, exit 0.
  EXPECT_EQ(RunShell(Binary() + " lessons check lphi_time_constant --seeds 1,2 --jobs 2", log), 0)
      << ReadText(log);
  EXPECT_EQ(ReadText(log).find("warning:"), std::string::npos) << ReadText(log);
}

// Every check a shipped lesson's text says depends on the seed takes more than one value on
// seeds 1..3 (only those checks run, with the checks they compare with).
TEST(LessonSeedEffect, ShippedLessonsShowTheSeedEffectsTheyClaim) {
  int claimed = 0;
  for (const std::string& file : sim::ShippedLessons()) {
    const sim::ParsedScenario p = sim::ParseScenario(sim::ScenarioSource::FromFile(file), {});
    sim::LessonCheckOptions opt;
    opt.jobs = 2;
    opt.seeds = {1, 2, 3};
    for (const auto& [id, claim] : sim::ChecksClaimingASeedEffect(p.lesson)) opt.only.push_back(id);
    if (opt.only.empty()) continue;
    claimed += static_cast<int>(opt.only.size());
    for (const sim::SeedEffectWarning& w : sim::SeedEffectWarnings(p.lesson, sim::CheckLesson(file, opt)))
      ADD_FAILURE() << sim::FormatSeedEffectWarning(w);
  }
  EXPECT_GE(claimed, 4);
}

}  // namespace
}  // namespace formsim::app
