// Guided lesson steps in the window (app/gui/lesson_guide.hpp, the Lesson panel): the script
// actions lesson-step, lesson-action and lesson-predict; a step's action through the command
// table (undoable); a prediction recorded and judged once the run has shown its check; the
// progress kept in the settings file and read back; every shipped lesson's steps clicked
// through, in-process and under Xvfb with --script.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/export/video_writer.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/ui_settings.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "tests/app/ui_window.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::CountOf;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

// The settings file of these tests: a folder of their own, never the user's.
std::string UseSettingsDir(const std::string& name) {
  const std::string dir = TempDir(name) + "/config";
  std::filesystem::remove_all(dir);
  ::setenv("XDG_CONFIG_HOME", dir.c_str(), 1);
  return dir + "/formsim/settings.yaml";
}

LessonGuide& Guide(AppUi& ui) {
  LessonPanel* p = ui.Find<LessonPanel>();
  EXPECT_NE(p, nullptr);
  return p->guide();
}

// Steps the live run to `t` seconds (or its end).
void RunTo(AppUi& ui, double t) {
  while (ui.session().exp().time() < t - 1e-9 && !ui.session().exp().finished()) ui.session().Step();
}

TEST(GuiLessonSteps, StepsActionsAndPredictionsThroughTheTable) {
  const std::string settings = UseSettingsDir("lesson_steps");
  testing::UiWindow w("formation_traj2");
  AppUi& ui = w.ui();
  // Not a lesson: each lesson action is refused with the reason.
  EXPECT_NE(ui.RunScriptAction("lesson-step 1").find("no lesson"), std::string::npos);
  EXPECT_NE(ui.RunScriptAction("lesson-action").find("no lesson"), std::string::npos);
  ASSERT_EQ(ui.RunScriptAction("lesson lphi_time_constant"), "");
  LessonGuide& g = Guide(ui);
  EXPECT_EQ(g.Steps(), 7);
  EXPECT_EQ(g.Step(), 1);
  // Out of range: the range is named.
  EXPECT_NE(ui.RunScriptAction("lesson-step 8").find("steps 1 ... 7"), std::string::npos);
  EXPECT_NE(ui.RunScriptAction("lesson-step 0").find("1 ... 1000"), std::string::npos);
  EXPECT_NE(ui.RunScriptAction("lesson-action").find("step 1 has no action"), std::string::npos);
  EXPECT_NE(ui.RunScriptAction("lesson-predict 1").find("asks for no prediction"), std::string::npos);
  // Step 4: predict, then the action (pin, halve k_l, reset).
  ASSERT_EQ(ui.RunScriptAction("lesson-step 4"), "");
  EXPECT_EQ(g.Step(), 4);
  EXPECT_NE(ui.RunScriptAction("lesson-action").find("predict first"), std::string::npos);
  EXPECT_NE(ui.RunScriptAction("lesson-predict 4").find("options 1 ... 3"), std::string::npos);
  ASSERT_EQ(ui.RunScriptAction("lesson-predict 1"), "");
  EXPECT_NE(g.Verdict().find("You predicted A. The run shows it once the run reaches t = 4 s"),
            std::string::npos)
      << g.Verdict();
  // The action's pin needs a run to keep: refused, naming the line and why.
  EXPECT_NE(ui.RunScriptAction("lesson-action").find("step 4's action 'pin': pin: the run has not started"),
            std::string::npos);
  RunTo(ui, 100);  // the lesson's own run, to the end: not the run the prediction is about
  EXPECT_NE(g.Verdict().find("Not on this run: tau_half is measured on a run started with "
                             "robots.R2.follow.k_l=0.5"),
            std::string::npos)
      << g.Verdict();
  ASSERT_EQ(ui.RunScriptAction("lesson-action"), "");
  EXPECT_EQ(ui.session().EffectiveValue("robots.R2.follow.k_l"), "0.5");
  EXPECT_EQ(ui.Find<ComparePanel>()->pins().size(), 1u);
  EXPECT_TRUE(ui.session().can_undo());  // the edit went the normal way: undoable
  // Not judged before the run has reached t = 4 s (the end of the check's window).
  RunTo(ui, 3.0);
  EXPECT_EQ(g.Verdict().find("right"), std::string::npos) << g.Verdict();
  EXPECT_NE(g.SeeLine("tau_half").find("not yet (measured once the run reaches t = 4 s)"),
            std::string::npos)
      << g.SeeLine("tau_half");
  RunTo(ui, 4.0);
  // docs/teaching.md's example, word for word (seed 1).
  EXPECT_EQ(g.Verdict(), "You predicted A — right: tau_half measured 1.995, within [1.9, 2.1]");
  EXPECT_NE(g.SeeLine("tau_half").find("√ holds"), std::string::npos) << g.SeeLine("tau_half");
  // Another answer is judged against the same run.
  ASSERT_EQ(ui.RunScriptAction("lesson-predict 2"), "");
  EXPECT_NE(g.Verdict().find("You predicted B — not quite (the answer is A)"), std::string::npos)
      << g.Verdict();
  // A check of another run names the edits it needs; the lesson's own checks hold on it only
  // once the edits are undone and the run reset.
  EXPECT_NE(g.SeeLine("tau_l").find("started with the lesson's own values"), std::string::npos)
      << g.SeeLine("tau_l");
  w.Frame();  // the Lesson tab drawn with the step, its prediction and its checks

  // Step 5 (k_l = 2 for a 3 s check): measured on the 6 s run, its window ends at 1.5 s.
  ASSERT_EQ(ui.RunScriptAction("lesson-step 5"), "");
  ASSERT_EQ(ui.RunScriptAction("lesson-action"), "");
  RunTo(ui, 1.5);
  EXPECT_NE(g.SeeLine("tau_double").find("√ holds"), std::string::npos) << g.SeeLine("tau_double");
  // Step 6 reverts k_l: the run's only edit is L.
  ASSERT_EQ(ui.RunScriptAction("lesson-step 6"), "");
  ASSERT_EQ(ui.RunScriptAction("lesson-action"), "");
  RunTo(ui, 100);
  EXPECT_NE(g.SeeLine("omega_small_l").find("√ holds"), std::string::npos)
      << g.SeeLine("omega_small_l");
  EXPECT_NE(g.SeeLine("omega_ratio").find("compares two runs"), std::string::npos);

  // The progress is in the settings file and read back.
  std::string warning;
  const UiSettings s = LoadUiSettings(&warning);
  EXPECT_EQ(warning, "");
  ASSERT_TRUE(s.lessons.count("lphi_time_constant")) << ReadText(settings);
  const LessonProgress& p = s.lessons.at("lphi_time_constant");
  EXPECT_EQ(p.step, 6);
  EXPECT_EQ(p.done, (std::set<int>{4, 5, 6}));
  EXPECT_EQ(p.predicted, (std::map<int, int>{{4, 2}}));
  EXPECT_EQ(p, ui.state().settings.lessons.at("lphi_time_constant"));
}

// A window started later with the settings file shows the step where the student left.
TEST(GuiLessonSteps, ProgressIsReadBackAndABrokenFileIsNeverFatal) {
  const std::string settings = UseSettingsDir("lesson_progress");
  {
    UiSettings s;
    s.ui_scale = 1.5f;
    s.lessons["printed_vs_per_sample"] = {3, {1, 2}, {{3, 3}}};
    ASSERT_EQ(SaveUiSettings(s), "");
  }
  {
    testing::UiWindow w("formation_traj2");
    w.ui().state().settings = LoadUiSettings();
    ASSERT_EQ(w.ui().RunScriptAction("lesson printed_vs_per_sample"), "");
    LessonGuide& g = Guide(w.ui());
    EXPECT_EQ(g.Step(), 3);
    EXPECT_EQ(g.Progress().done, (std::set<int>{1, 2}));
    EXPECT_NE(g.Verdict().find("You predicted C"), std::string::npos) << g.Verdict();
    w.Frame();
  }
  // A wrong lesson entry is dropped alone, with a warning naming file:line and the key.
  {
    std::ofstream(settings) << "ui_scale: 2\nlessons:\n  good: {step: 2, done: [1]}\n"
                               "  bad: {step: -1}\n  worse: [1, 2]\n  odd: {step: 1, colour: red}\n";
    std::string warning;
    const UiSettings s = LoadUiSettings(&warning);
    EXPECT_FLOAT_EQ(s.ui_scale, 2.0f);
    ASSERT_EQ(s.lessons.size(), 1u);
    EXPECT_EQ(s.lessons.at("good").step, 2);
    EXPECT_NE(warning.find(settings + ":"), std::string::npos) << warning;
    EXPECT_NE(warning.find("lessons."), std::string::npos) << warning;
  }
  // Not YAML at all: the defaults and a warning.
  {
    std::ofstream(settings) << "lessons: {a: [\n";
    std::string warning;
    const UiSettings s = LoadUiSettings(&warning);
    EXPECT_TRUE(s.lessons.empty());
    EXPECT_NE(warning.find("defaults used"), std::string::npos) << warning;
  }
  // A window over a lesson whose kept step is past its end shows its last step.
  {
    testing::UiWindow w("formation_traj2");
    w.ui().state().settings.lessons["agv_outliers_gate"].step = 40;
    ASSERT_EQ(w.ui().RunScriptAction("lesson agv_outliers_gate"), "");
    EXPECT_EQ(Guide(w.ui()).Step(), Guide(w.ui()).Steps());
    w.Frame();
  }
}

// Every shipped lesson, in-process: every step shown and drawn, every prediction made, every
// action run through the table without a refusal, a few steps of the run after each.
TEST(GuiLessonSteps, EveryShippedLessonsStepsClickThrough) {
  UseSettingsDir("lesson_every");
  testing::UiWindow w("formation_traj2");
  AppUi& ui = w.ui();
  for (const std::string& file : sim::ShippedLessons()) {
    const std::string name = std::filesystem::path(file).stem().string();
    ASSERT_EQ(ui.RunScriptAction("lesson " + name), "") << name;
    LessonGuide& g = Guide(ui);
    ASSERT_GE(g.Steps(), 3) << name;
    for (int s = 1; s <= g.Steps(); ++s) {
      ASSERT_EQ(ui.RunScriptAction("lesson-step " + std::to_string(s)), "") << name;
      const sim::LessonStep step = *g.Current();
      if (!step.predict.question.empty()) {
        EXPECT_EQ(ui.RunScriptAction("lesson-predict 1"), "") << name << " step " << s;
      }
      if (!step.action.label.empty()) {
        EXPECT_EQ(ui.RunScriptAction("lesson-action"), "") << name << " step " << s;
      }
      for (int k = 0; k < 5; ++k) ui.session().Step();
      w.Frame();
      for (const std::string& id : step.Checks()) EXPECT_FALSE(g.SeeLine(id).empty());
    }
    EXPECT_EQ(ui.state().settings.lessons.at(name).step, g.Steps()) << name;
  }
}

// Under Xvfb, one window and one script: every shipped lesson opened, each step shown, each
// prediction made and each action pressed, with no refusal.
TEST(GuiLessonSteps, EveryLessonByScriptUnderXvfb) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_lesson_script");
  long frame = 2, actions = 0;
  {
    std::ofstream script(dir + "/script.txt");
    for (const std::string& file : sim::ShippedLessons()) {
      const sim::ParsedScenario p = sim::ParseScenario(sim::ScenarioSource::FromFile(file), {});
      script << frame++ << " lesson " << std::filesystem::path(file).stem().string() << "\n";
      script << frame++ << " play\n";  // a student runs the lesson's run (an action may pin it)
      frame += 3;
      for (std::size_t s = 0; s < p.lesson.steps.size(); ++s) {
        script << frame++ << " lesson-step " << s + 1 << "\n";
        ++actions;
        if (!p.lesson.steps[s].predict.question.empty()) {
          script << frame++ << " lesson-predict 2\n";
          ++actions;
        }
        if (!p.lesson.steps[s].action.label.empty()) {
          script << frame++ << " lesson-action\n";
          script << frame++ << " play\n";
          ++actions;
        }
        frame += 2;
      }
    }
    script << frame + 2 << " screenshot " << dir << "/last.png\n";
  }
  ASSERT_GT(actions, 50);
  const std::string cmd = "XDG_CONFIG_HOME=" + dir + "/config " +
                          testing::Xvfb(Binary() + " gui --lesson lphi_time_constant --speed max "
                                                   "--exit-after " + std::to_string(frame + 6) +
                                        " --script " + dir + "/script.txt");
  const int rc = RunShell(cmd, dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  ASSERT_EQ(rc, 0) << log;
  EXPECT_EQ(CountOf(log, "refused"), 0) << log;
  EXPECT_TRUE(std::filesystem::exists(dir + "/last.png"));
  // The progress of every lesson was kept.
  const std::string settings = ReadText(dir + "/config/formsim/settings.yaml");
  for (const std::string& file : sim::ShippedLessons())
    EXPECT_NE(settings.find(std::filesystem::path(file).stem().string() + ": {step:"),
              std::string::npos)
        << settings;
}

}  // namespace
}  // namespace formsim::app
