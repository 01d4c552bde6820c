// Value entry like a desktop app and honest comparisons (issue 24 items 6 and 8):
// - through --script under Xvfb: Enter commits once, Esc cancels, nothing is applied while
//   typing, a value the loader refuses is refused with its reason and not applied, the wheel
//   makes a fine step, and an angle typed in degrees is stored in radians;
// - in-process with synthetic mouse input: a double-click on a slider opens the entry and does
//   not set the value under the mouse;
// - the comparison table cuts runs of different lengths to their common span (a branched pin).
#include "app/gui/parameters_panel.hpp"
#include "app/gui/value_entry.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include "app/export/png_writer.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/export/video_writer.hpp"
#include "sim/core/metrics.hpp"
#include "sim/core/number_format.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"
#include "tests/app/ui_window.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::CountOf;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;
using testing::Xvfb;

double Saved(const std::string& file, const std::string& key) {
  sim::Session s(file, {}, -1);
  return s.params().Find(key)->value;
}

TEST(ValueEntry, ScriptCommitsOnEnterCancelsOnEscAndRefusesWithTheReason) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("value_entry_script");
  const std::string kl = "robots.R2.follow.k_l", kphi = "robots.R2.follow.k_phi",
                    phi = "robots.R2.follow.phi_des";
  std::ofstream script(dir + "/script.txt");
  script << "2 angle-unit deg\n"
         << "5 field-open " << kl << "\n"
         << "8 field-type 0.37\n"
         << "10 save " << dir << "/typing.yaml\n"  // typed, not entered: nothing applied
         << "12 field-enter\n"
         << "14 save " << dir << "/entered.yaml\n"
         << "16 field-open " << kl << "\n"
         << "19 field-type 0.9\n"
         << "21 field-escape\n"
         << "23 save " << dir << "/cancelled.yaml\n"
         << "25 field-open " << kphi << "\n"
         << "28 field-type -1\n"
         << "30 field-enter\n"  // refused: the loader's reason, the field stays open and red
         << "33 screenshot " << dir << "/refused.png\n"
         << "35 save " << dir << "/refused.yaml\n"
         << "37 field-escape\n"
         << "39 field-open " << phi << "\n"
         << "42 field-type 90\n"  // degrees: stored as pi/2
         << "44 field-enter\n"
         << "46 field-wheel " << kl << " 2\n"  // two fine steps up
         << "48 save " << dir << "/end.yaml\n"
         << "50 field-type x\n";  // refused: no field is open
  script.close();
  const std::string env = "FORMSIM_STATE_DIR=" + dir + " XDG_CONFIG_HOME=" + dir + " ";
  const int rc = RunShell(env + Xvfb(Binary() +
                                     " gui formation_traj2 --paused --size 1280x800 "
                                     "--exit-after 55 --script " +
                                     dir + "/script.txt"),
                          dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  ASSERT_EQ(rc, 0) << log;
  EXPECT_EQ(Saved(dir + "/typing.yaml", kl), 0.15) << "a keystroke was applied before Enter";
  EXPECT_EQ(Saved(dir + "/entered.yaml", kl), 0.37);
  EXPECT_EQ(Saved(dir + "/cancelled.yaml", kl), 0.37) << "Esc applied the text typed";
  const double kphi_file = Saved(dir + "/typing.yaml", kphi);
  EXPECT_EQ(Saved(dir + "/refused.yaml", kphi), kphi_file) << "a refused value was applied";
  EXPECT_EQ(CountOf(log, "refused"), 2) << log;
  EXPECT_NE(log.find("'field-enter' refused: "), std::string::npos) << log;
  EXPECT_NE(log.find("k_phi=-1: must be in (0, 10000]"), std::string::npos) << log;
  EXPECT_NE(log.find("no value field is open"), std::string::npos) << log;
  EXPECT_NEAR(Saved(dir + "/end.yaml", phi), M_PI / 2, 1e-12);
  EXPECT_EQ(Saved(dir + "/end.yaml", kl), 0.372) << "two fine steps of 0.001 from 0.37";
  int w = 0, h = 0;
  ReadPng(dir + "/refused.png", &w, &h);
  EXPECT_EQ(w, 1280);
}

TEST(ValueEntry, ADoubleClickOnASliderOpensTheEntryAndSetsNothing) {
  testing::UiWindow w;
  // Double-click down the value column of the Parameters panel until a field opens (the first
  // slider there): the first click of the double-click must not set the value under the mouse.
  std::string opened;
  for (float y = 420; y < 790 && opened.empty(); y += 7) {
    const ImVec2 at(230, y);
    if (w.Hover(at) == 0) continue;
    auto press = [&](bool down) {
      w.Frame([&](ImGuiIO& io) {
        io.MousePos = at;
        io.MouseDown[0] = down;
      });
    };
    press(true);
    press(false);
    press(true);
    press(false);
    opened = w.ui().Find<ParametersPanel>()->EntryKey();
  }
  ASSERT_FALSE(opened.empty()) << "no double-click opened a field";
  EXPECT_FALSE(w.ui().session().can_undo()) << "the double-click made an edit";
  w.Frame();  // the field takes the keyboard on the frame after it is drawn
  w.Frame();
  EXPECT_TRUE(ImGui::GetIO().WantTextInput) << "the entry did not take the keyboard";
  const std::string before = w.ui().session().EffectiveValue(opened);
  // Typing applies nothing; Enter applies the value once.
  w.Frame([](ImGuiIO& io) {
    for (char c : std::string("0.5")) io.AddInputCharacter(c);
  });
  w.Frame();
  EXPECT_EQ(w.ui().session().EffectiveValue(opened), before) << "typing applied the value";
  w.Frame([](ImGuiIO& io) { io.KeysDown[13] = true; });  // Enter (the window's key map)
  w.Frame();
  EXPECT_EQ(w.ui().session().EffectiveValue(opened), "0.5");
  EXPECT_NE(w.ui().Find<ParametersPanel>()->EntryKey(), opened);
  // Esc closes it with nothing applied.
  ImGui::GetIO().KeyMap[ImGuiKey_Escape] = 27;
  ASSERT_EQ(w.ui().Find<ParametersPanel>()->CmdFieldOpen(opened), "");
  w.Frame();
  w.Frame();
  w.Frame([](ImGuiIO& io) { io.AddInputCharacter('9'); });
  w.Frame([](ImGuiIO& io) { io.KeysDown[27] = true; });
  w.Frame();
  EXPECT_NE(w.ui().Find<ParametersPanel>()->EntryKey(), opened);
  EXPECT_EQ(w.ui().session().EffectiveValue(opened), "0.5");
}

TEST(ValueEntry, TheWheelMakesAFineStepInTheUnitShown) {
  sim::Param p;
  p.kind = sim::Param::Kind::kDouble;
  p.tune.slider_lo = 0.0;
  p.tune.slider_hi = 2.0;
  EXPECT_EQ(FineStep(p, 0.15, 1, 1.0), "0.16");  // a hundredth of the range, rounded down: 0.01
  EXPECT_EQ(FineStep(p, 0.15, -3, 1.0), "0.12");
  EXPECT_EQ(FineStep(p, 1.995, 5, 1.0), "2");  // kept within the slider
  // An angle in degrees: one degree per notch on a 0 ... 2 rad slider (114.6°).
  const double k = 180 / M_PI;
  double v = 0;
  ASSERT_TRUE(sim::ParseFiniteDouble(FineStep(p, 30 / k, 1, k), &v));
  EXPECT_NEAR(v * k, 31.0, 1e-9);
}

// Steps the live run to `t` seconds.
void StepTo(testing::UiWindow& w, double t) {
  while (w.ui().session().exp().time() < t - 1e-9) ASSERT_EQ(w.ui().RunScriptAction("step"), "");
}

// The window's background work (pins, replays to the common span) done.
void Settle(testing::UiWindow& w) {
  for (int i = 0; i < 2000 && w.ui().Busy(); ++i) {
    w.Frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  w.Frame();
}

// The comparison's runs once every replay to the common span is done; `now` holds the live
// run's metrics the first column points to.
std::vector<ComparePanel::CompareRun> Compared(testing::UiWindow& w, sim::Metrics* now,
                                        std::string* title) {
  std::vector<ComparePanel::CompareRun> runs;
  *now = w.ui().session().exp().Results();
  for (int i = 0; i < 2000; ++i) {
    runs = w.ui().Find<ComparePanel>()->CompareRuns(*now, title);
    bool all = true;
    for (const auto& r : runs) all = all && r.metrics != nullptr;
    if (all) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return runs;
}

TEST(CompareSpan, ABranchedPinIsComparedOverTheCommonSpan) {
  testing::UiWindow w;
  StepTo(w, 2.0);
  // Back to 1 s and branch: the original (2 s) is pinned, the live run restarts from 1 s.
  ASSERT_EQ(w.ui().RunScriptAction("scrub 1"), "");
  ASSERT_EQ(w.ui().RunScriptAction("branch"), "");
  Settle(w);
  ASSERT_EQ(w.ui().Find<ComparePanel>()->pins().size(), 1u);
  ASSERT_NEAR(w.ui().Find<ComparePanel>()->pins()[0]->exp->time(), 2.0, 1e-9);
  ASSERT_NEAR(w.ui().session().exp().time(), 1.0, 1e-9);
  std::string title;
  sim::Metrics live;
  auto runs = Compared(w, &live, &title);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_NE(title.find("common span 0 ... 1.0 s"), std::string::npos) << title;
  EXPECT_EQ(runs[0].header, "now (1.0 s)");
  EXPECT_EQ(runs[1].header, "pin 1 (1.0 of 2.0 s)");
  ASSERT_NE(runs[1].metrics, nullptr) << runs[1].why;
  // The branch is an exact replay: over the common span the two runs are the same run.
  const auto now = runs[0].metrics->Scalars(), pin = runs[1].metrics->Scalars();
  const auto whole = w.ui().Find<ComparePanel>()->pins()[0]->results->Scalars();
  ASSERT_EQ(now.size(), pin.size());
  int differs_whole = 0;
  for (std::size_t i = 0; i < now.size(); ++i) {
    EXPECT_EQ(now[i].first, pin[i].first);
    if (std::isfinite(now[i].second) || std::isfinite(pin[i].second)) {
      EXPECT_EQ(now[i].second, pin[i].second) << now[i].first;
    }
    differs_whole += whole[i].second != now[i].second && std::isfinite(now[i].second);
  }
  EXPECT_GT(differs_whole, 0) << "the pin's whole run would compare equal too: no test";
  // The other way round: the live run goes past the pin and is cut to the pin's 2 s.
  StepTo(w, 2.5);
  runs = Compared(w, &live, &title);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_NE(title.find("common span 0 ... 2.0 s"), std::string::npos) << title;
  EXPECT_EQ(runs[0].header, "now (2.0 of 2.5 s)");
  ASSERT_NE(runs[0].metrics, nullptr) << runs[0].why;
  const auto cut = runs[0].metrics->Scalars();
  ASSERT_EQ(cut.size(), whole.size());
  for (std::size_t i = 0; i < cut.size(); ++i)
    if (std::isfinite(cut[i].second) || std::isfinite(whole[i].second)) {
      EXPECT_EQ(cut[i].second, whole[i].second) << cut[i].first;
    }
}

}  // namespace
}  // namespace formsim::app
