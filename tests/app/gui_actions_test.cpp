// The GUI under Xvfb driven by --script through the same commands as the mouse and keyboard:
// every button of the Scenario and Run panels, and every slider of every shipped scenario at
// both ends followed by a reset. The GUI must stay alive (exit 0 when asked), refuse what the
// loader would refuse with a reason, and keep its edits (the file it saves holds exactly the
// values an in-process session accepts for the same actions).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/export/png_writer.hpp"
#include "app/export/video_writer.hpp"
#include "sim/core/experiment.hpp"
#include "sim/core/number_format.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::CountOf;
using testing::NonBackgroundFraction;
using testing::ReadText;
using testing::RunShell;
using testing::Xvfb;
using testing::Scenario;
using testing::TempDir;

TEST(GuiActions, EveryButtonOfTheScenarioAndRunPanels) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_buttons");
  std::ofstream script(dir + "/script.txt");
  script << "# every button of the Scenario and Run panels\n"
         << "3 step\n4 step\n5 play\n8 pause\n9 play\n"
         << "20 reset\n"
         << "25 reset-seed 9223372036854775807\n"    // int64 max: fine, seeds are 64-bit
         << "26 reset-seed 18446744073709551615\n"   // 2^64 - 1: fine
         << "27 reset-seed 18446744073709551616\n"   // refused: does not fit
         << "28 reset-seed -3\n"                      // refused
         << "30 edit robots.R2.follow.k_l=0.4\n"
         << "31 edit formation.L=0.5\n"               // refused: breaks the l-l triangle
         << "32 edit robots.R2.follow.k_l=-0.5\n"     // refused: the loader's rule
         << "40 reset\n"
         << "45 save " << dir << "/tuned.yaml\n"
         << "50 reload\n"
         << "55 open " << dir << "/tuned.yaml\n"
         << "60 open " << dir << "/no_such_file.yaml\n"  // refused, the scenario stays
         << "65 reload\n";
  int frame = 70;
  for (const std::string& f : sim::ShippedScenarios()) {
    script << frame << " load " << std::filesystem::path(f).stem().string() << "\n"
           << frame + 1 << " step\n" << frame + 2 << " reset\n";
    frame += 4;
  }
  script << frame << " load formation_cascade7\n"
         << frame + 2 << " screenshot " << dir << "/end.png\n"
         << frame + 3 << " nonsense 1\n";  // refused: unknown action
  script.close();
  const int rc = RunShell(Xvfb(Binary() + " gui formation_cascade7 --paused --size 800x500 --speed max "
                                          "--exit-after " + std::to_string(frame + 10) +
                                          " --script " + dir + "/script.txt"),
                          dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  ASSERT_EQ(rc, 0) << log;
  EXPECT_EQ(CountOf(log, "refused"), 6) << log;
  EXPECT_NE(log.find("triangle"), std::string::npos) << log;
  EXPECT_NE(log.find("must be > 0"), std::string::npos) << log;
  EXPECT_NE(log.find("seed must be"), std::string::npos) << log;
  EXPECT_NE(log.find("unknown action 'nonsense'"), std::string::npos) << log;
  // The saved file keeps the accepted edit and only that.
  sim::Session saved(dir + "/tuned.yaml", {}, -1);
  EXPECT_EQ(saved.params().Find("robots.R2.follow.k_l")->value, 0.4);
  EXPECT_EQ(saved.params().Find("formation.L")->value, 0.15);
  EXPECT_EQ(saved.seed(), 18446744073709551615ULL);
  int w = 0, h = 0;
  const auto px = ReadPng(dir + "/end.png", &w, &h);
  EXPECT_EQ(w, 800);
  EXPECT_GT(NonBackgroundFraction(px), 0.2);
}

// Widget values of a parameter: both slider ends (or every choice, both booleans).
std::vector<std::string> Ends(const sim::Param& p) {
  switch (p.kind) {
    case sim::Param::Kind::kDouble:
      return {sim::FormatDouble(p.slider_min()), sim::FormatDouble(p.slider_max())};
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

class GuiSliders : public ::testing::TestWithParam<std::string> {};

TEST_P(GuiSliders, EverySliderAtBothEndsThenResetKeepsTheGuiAliveAndItsEdits) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string prefix = GetParam();
  const std::string dir = TempDir("gui_sliders_" + prefix);
  std::ofstream script(dir + "/script.txt");
  int frame = 2;
  std::vector<std::pair<std::string, std::unique_ptr<sim::Session>>> expected;
  for (const std::string& f : testing::PerParameterScenarios()) {
    const std::string stem = std::filesystem::path(f).stem().string();
    if (stem.rfind(prefix, 0) != 0) continue;
    // The same actions on an in-process session give what the GUI must have kept.
    auto model = std::make_unique<sim::Session>(f, std::vector<sim::Override>{});
    script << frame++ << " load " << stem << "\n";
    std::vector<std::pair<std::string, std::vector<std::string>>> plan;
    for (const sim::Param& p : testing::ParamsToExercise(model->params())) plan.emplace_back(p.key, Ends(p));
    for (const auto& [key, values] : plan) {
      for (const std::string& v : values) {
        script << frame++ << " edit " << key << "=" << v << "\n";
        model->Edit(key, v);
      }
      script << frame++ << " reset\n";
      EXPECT_EQ(model->Reset(), "");
    }
    script << frame++ << " save " << dir << "/" << stem << ".yaml\n";
    expected.emplace_back(stem, std::move(model));
  }
  script.close();
  ASSERT_FALSE(expected.empty());
  const int rc = RunShell(Xvfb(Binary() + " gui --size 640x400 --speed max --exit-after " +
                               std::to_string(frame + 3) + " --script " + dir + "/script.txt"),
                          dir + "/log.txt");
  ASSERT_EQ(rc, 0) << ReadText(dir + "/log.txt");
  for (const auto& [stem, model] : expected) {
    sim::Session saved(dir + "/" + stem + ".yaml", {}, -1);
    for (const sim::Param& p : model->params().all()) {
      const sim::Param* q = saved.params().Find(p.key);
      ASSERT_NE(q, nullptr) << stem << " " << p.key;
      EXPECT_EQ(q->Text(), p.Text()) << stem << " " << p.key;
    }
  }
}

// Every registered kind, as the prefix of its shipped scenarios' names (`<kind>_*.yaml`). gtest
// evaluates this when the tests are listed, after every kind has registered itself.
std::vector<std::string> KindPrefixes() {
  std::vector<std::string> out;
  for (const std::string& type : sim::ExperimentRegistry::Types()) out.push_back(type + "_");
  return out;
}

INSTANTIATE_TEST_SUITE_P(Kinds, GuiSliders, ::testing::ValuesIn(KindPrefixes()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           return i.param.substr(0, i.param.size() - 1);
                         });

}  // namespace
}  // namespace formsim::app
