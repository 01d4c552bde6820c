// The tuning session behind the GUI (sim::Session) on the minimal kind of test_kind.hpp: edits
// are checked by the loader's own rules at once, live ones apply between steps, OnReset ones
// wait, failed resets and reloads keep the run, Save keeps the file's text and loads back.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/session/session.hpp"
#include "tests/sim/test_kind.hpp"
#include "tests/support/test_files.hpp"

namespace formsim::sim {
namespace {

using testkind::NoisyCircle;

std::string SessionFile(const std::string& name, const std::string& text) {
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/test_out/session";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

using testing::ReadText;

const NoisyCircle& Circle(const Session& s) { return dynamic_cast<const NoisyCircle&>(s.exp()); }

TEST(Session, LiveEditAppliesBeforeTheNextStepOnly) {
  Session s(SessionFile("live.yaml", testkind::kScenario), {}, -1);
  EXPECT_EQ(s.Edit("v", "2"), "");
  EXPECT_EQ(Circle(s).v(), 1.2) << "an edit must not touch the experiment until applied";
  s.Step();
  EXPECT_EQ(Circle(s).v(), 2.0);
  EXPECT_EQ(s.params().Find("v")->value, 2.0);
  EXPECT_EQ(s.accepted_edits(), 1);
  // The edit is in the run's provenance with the step it took effect at.
  const std::string json = s.exp().Summary().Dump();
  EXPECT_NE(json.find("\"origin\": \"GUI edit\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"step\": 0"), std::string::npos) << json;
}

TEST(Session, EditsTheLoaderWouldRefuseAreRefusedAtOnce) {
  Session s(SessionFile("refuse.yaml", testkind::kScenario), {}, -1);
  EXPECT_NE(s.Edit("v", "abc").find("expected a finite number"), std::string::npos);
  EXPECT_NE(s.Edit("v", "nan").find("finite"), std::string::npos);
  EXPECT_NE(s.Edit("v", "-0.5").find("must be >= 0"), std::string::npos);
  EXPECT_NE(s.Edit("no.such.key", "1").find("unknown parameter"), std::string::npos);
  EXPECT_NE(s.Edit("drive.mode", "flying").find("not one of"), std::string::npos);
  // A value valid on its own that breaks a rule across keys (v + |ω| < 4) names the rule.
  const std::string cross = s.Edit("v", "3.6");
  EXPECT_NE(cross.find("v + |omega| must be < 4"), std::string::npos) << cross;
  EXPECT_NE(s.refusal("v"), "");
  for (int i = 0; i < 10; ++i) s.Step();
  EXPECT_EQ(Circle(s).v(), 1.2);
  EXPECT_EQ(s.accepted_edits(), 0);
  // Nothing refused reaches a reset either.
  EXPECT_EQ(s.Reset(), "");
  EXPECT_EQ(Circle(s).v(), 1.2);
  // An accepted edit clears the refusal shown at the widget.
  EXPECT_EQ(s.Edit("v", "2.5"), "");
  EXPECT_EQ(s.refusal("v"), "");
}

TEST(Session, OnResetEditsWaitAndResetKeepsEveryEdit) {
  Session s(SessionFile("wait.yaml", testkind::kScenario), {}, -1);
  EXPECT_EQ(s.Edit("sigma", "0.5"), "");
  EXPECT_EQ(s.Edit("v", "0.8"), "");
  s.Step();
  EXPECT_EQ(Circle(s).sigma(), 0.1);
  EXPECT_EQ(s.waiting_for_reset().at("sigma"), "0.5");
  EXPECT_EQ(s.Reset(), "");
  EXPECT_EQ(Circle(s).sigma(), 0.5);
  EXPECT_EQ(Circle(s).v(), 0.8);
  EXPECT_TRUE(s.waiting_for_reset().empty());
  EXPECT_EQ(s.exp().steps(), 0);
  // A seed change keeps the edits too, and seeds up to 2^64 - 1 are fine.
  EXPECT_EQ(s.Reset(18446744073709551615ULL), "");
  EXPECT_EQ(s.seed(), 18446744073709551615ULL);
  EXPECT_EQ(Circle(s).v(), 0.8);
}

TEST(Session, FailedReloadKeepsTheRunningExperiment) {
  const std::string file = SessionFile("reload.yaml", testkind::kScenario);
  Session s(file, {}, -1);
  EXPECT_EQ(s.Edit("v", "0.9"), "");
  for (int i = 0; i < 5; ++i) s.Step();
  std::ofstream(file) << "type: test_noisy_circle\nv: [broken\n";
  const std::string err = s.Reload();
  EXPECT_NE(err.find("reload failed"), std::string::npos) << err;
  EXPECT_NE(err.find("reload.yaml:"), std::string::npos) << err;
  EXPECT_EQ(s.exp().steps(), 5);
  EXPECT_EQ(Circle(s).v(), 0.9);
  s.Step();
  EXPECT_EQ(s.exp().steps(), 6);
}

TEST(Session, SaveKeepsCommentsAndWritesShortestNumbers) {
  Session s(SessionFile("save.yaml", testkind::kScenario), {}, -1);
  EXPECT_EQ(s.Edit("v", "0.03"), "");
  EXPECT_EQ(s.Edit("sigma", "0.2"), "");
  EXPECT_EQ(s.Edit("drive.v_max", "4.5"), "");  // not in the file: inserted into drive: {...}
  s.Step();
  const std::string out = std::string(FORMSIM_BINARY_DIR) + "/test_out/session/saved/tuned.yaml";
  std::filesystem::create_directories(std::filesystem::path(out).parent_path());
  std::string note;
  ASSERT_EQ(s.Save(out, true, &note), Session::SaveResult::kSaved);
  EXPECT_EQ(note, "");
  const std::string text = ReadText(out);
  EXPECT_NE(text.find("# A circle for the core tests"), std::string::npos) << text;
  EXPECT_NE(text.find("v: 0.03   # forward speed"), std::string::npos) << text;
  EXPECT_NE(text.find("sigma: 0.2\n"), std::string::npos) << text;
  EXPECT_NE(text.find("drive: {mode: ideal, v_max: 4.5}"), std::string::npos) << text;
  // It loads and runs with the tuned values.
  Session back(out, {}, -1);
  EXPECT_EQ(Circle(back).v(), 0.03);
  EXPECT_EQ(Circle(back).sigma(), 0.2);
  EXPECT_EQ(back.params().Find("drive.v_max")->value, 4.5);
  // Saving never overwrites without being asked.
  EXPECT_EQ(s.Save(out), Session::SaveResult::kNeedsConfirmation);
}

TEST(Session, RunWithEditsAtStepZeroEqualsTheSavedScenario) {
  Session s(SessionFile("same.yaml", testkind::kScenario), {}, -1);
  EXPECT_EQ(s.Edit("v", "0.7"), "");
  EXPECT_EQ(s.Reset(), "");
  while (!s.exp().finished()) s.Step();
  const std::string out = std::string(FORMSIM_BINARY_DIR) + "/test_out/session/same_tuned.yaml";
  s.Save(out, true);
  Session back(out, {}, -1);
  while (!back.exp().finished()) back.Step();
  ASSERT_EQ(s.exp().recorder().rows(), back.exp().recorder().rows());
  for (std::size_t r = 0; r < s.exp().recorder().rows(); ++r)
    for (std::size_t c = 0; c < s.exp().recorder().columns(); ++c)
      ASSERT_EQ(s.exp().recorder().At(r, static_cast<int>(c)),
                back.exp().recorder().At(r, static_cast<int>(c)));
}

}  // namespace
}  // namespace formsim::sim
