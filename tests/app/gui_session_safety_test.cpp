// The window never loses a session (issue 21): no ImGui assertion is reachable from a tunable's
// declared extremes (and ±1e308 where a tunable is unbounded) or from texts of 100,000
// characters; a kill -9 leaves a journal that `formsim replay` reproduces byte for byte up to
// the last edit, and the next window offers it for restore (never restoring by itself);
// SIGTERM, SIGINT and SIGHUP write what `formsim run` writes, marked interrupted, plus the
// session file, with no `.tmp` left; a failed screenshot says so, with the script line, and
// `--screenshot` exits with 4. Under Xvfb, like the other GUI tests (and under ASan+UBSan in CI).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

#include "app/export/png_writer.hpp"
#include "app/export/video_writer.hpp"
#include "sim/core/number_format.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;
using testing::Binary;
using testing::CountOf;
using testing::NonBackgroundFraction;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;
using testing::Xvfb;
using testing::XvfbRun;

bool HaveXvfb() {
  return !FindOnPath("xvfb-run").empty();
}

// The values a tunable is driven to: the ends of its validity (just inside an open end), and
// ±1e308 where it has none.
std::vector<std::string> Extremes(const sim::Param& p) {
  const sim::Tune& t = p.tune;
  switch (p.kind) {
    case sim::Param::Kind::kDouble: {
      const double big = 1e308;
      const double lo = std::isfinite(t.lo) ? (t.lo_open ? std::nextafter(t.lo, big) : t.lo) : -big;
      const double hi = std::isfinite(t.hi) ? (t.hi_open ? std::nextafter(t.hi, -big) : t.hi) : big;
      return {sim::FormatDouble(lo), sim::FormatDouble(hi)};
    }
    case sim::Param::Kind::kInt: {
      const double m = 2147483647.0;
      const double lo = std::isfinite(t.lo) ? std::max(-m, t.lo + (t.lo_open ? 1 : 0)) : -m;
      const double hi = std::isfinite(t.hi) ? std::min(m, t.hi - (t.hi_open ? 1 : 0)) : m;
      return {std::to_string(static_cast<long long>(lo)),
              std::to_string(static_cast<long long>(hi))};
    }
    case sim::Param::Kind::kBool:
      return {"true", "false"};
    case sim::Param::Kind::kChoice:
      return {p.choices.front(), p.choices.back()};
  }
  return {};
}

std::string Stem(const std::string& file) {
  return fs::path(file).stem().string();
}

// A tall window, so that every row of the Parameters panel is drawn (ImGui skips the widgets of
// rows scrolled out of view, and the slider's assertion is in what it draws).
std::string TallXvfb(const std::string& cmd) {
  return XvfbRun("1280x4000") + cmd;
}

TEST(GuiSafety, EveryTunableAtItsDeclaredExtremesDrawsWithoutAnAssertion) {
  if (!HaveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_extremes");
  std::ofstream script(dir + "/script.txt");
  long frame = 2;
  int edits = 0, unbounded = 0;
  std::vector<std::string> shots;
  bool degrees = false;
  for (const std::string& f : testing::PerParameterScenarios()) {
    sim::Session s(f, {}, -1);
    // Angles in degrees for every other scenario (the panel converts them for its sliders).
    degrees = !degrees;
    script << frame << " angle-unit " << (degrees ? "deg" : "rad") << "\n";
    script << frame << " load " << Stem(f) << "\n";
    for (const sim::Param& p : testing::ParamsToExercise(s.params())) {
      unbounded += p.kind == sim::Param::Kind::kDouble &&
                   !(std::isfinite(p.tune.lo) && std::isfinite(p.tune.hi));
      // One end per frame, each drawn before the next: the low ends, then the high ends.
      const auto v = Extremes(p);
      script << frame + 1 << " edit " << p.key << "=" << v.front() << "\n";
      script << frame + 3 << " edit " << p.key << "=" << v.back() << "\n";
      edits += 2;
    }
    const std::string shot = dir + "/" + Stem(f) + ".png";
    // frame + 2 draws the low ends (no picture: a 1280x4000 PNG costs more than the frame)
    script << frame + 4 << " screenshot " << shot << "\n";
    shots.push_back(shot);
    frame += 6;
  }
  script.close();
  const std::string log = dir + "/log.txt";
  const int rc = RunShell(TallXvfb("env FORMSIM_STATE_DIR=" + dir + "/state " + Binary() +
                                   " gui formation_traj2 --paused --size 1280x4000 --exit-after " +
                                   std::to_string(frame + 2) + " --script " + dir + "/script.txt"),
                          log);
  const std::string text = ReadText(log);
  ASSERT_EQ(rc, 0) << text.substr(0, 4000);
  EXPECT_EQ(text.find("Assertion"), std::string::npos);
  EXPECT_GT(edits, 200);
  std::printf(
      "%d edits to declared extremes over %zu scenarios (%d unbounded doubles got ±1e308)\n", edits,
      shots.size(), unbounded);
  for (const std::string& shot : shots) {
    int w = 0, h = 0;
    const auto px = ReadPng(shot, &w, &h);
    EXPECT_EQ(h, 4000) << shot;
    EXPECT_GT(NonBackgroundFraction(px), 0.05) << shot;
  }
}

TEST(ParamSlider, EndsStayFiniteAndWithinTheSliderLimitWhateverTheValue) {
  // An unbounded tunable at ±1e308: the derived slider is finite, inside ±kSliderLimit (ImGui
  // asserts beyond DBL_MAX / 2), and the panel shows such a value in a text field.
  sim::Param p;
  p.kind = sim::Param::Kind::kDouble;
  for (double v : {1e308, -1e308, 0.0, 1e15, -3.5, std::numeric_limits<double>::max()}) {
    p.value = v;
    EXPECT_TRUE(std::isfinite(p.slider_min()) && std::isfinite(p.slider_max())) << v;
    EXPECT_LE(std::abs(p.slider_min()), sim::kSliderLimit) << v;
    EXPECT_LE(std::abs(p.slider_max()), sim::kSliderLimit) << v;
  }
  p.tune.Above(0);
  p.value = 1e308;
  EXPECT_EQ(p.slider_min(), 0);
  EXPECT_EQ(p.slider_max(), sim::kSliderLimit);
}

TEST(GuiSafety, ValuesBeyondAnySliderAreATextField) {
  // Every shipped tunable whose validity reaches beyond a slider (a double beyond ±1e15, an
  // integer beyond ±1e9), at that value, from --set and from script edits: the window starts,
  // draws the row as a text field and goes on.
  if (!HaveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_beyond_sliders");
  std::ofstream script(dir + "/script.txt");
  int found = 0;
  long frame = 2;
  std::string first_set;
  for (const std::string& f : testing::PerParameterScenarios()) {
    sim::Session s(f, {}, -1);
    std::vector<std::string> edits;
    for (const sim::Param& p : testing::ParamsToExercise(s.params())) {
      const double limit = p.kind == sim::Param::Kind::kInt ? 1e9 : sim::kSliderLimit;
      if (p.kind != sim::Param::Kind::kDouble && p.kind != sim::Param::Kind::kInt) continue;
      for (const std::string& v : Extremes(p)) {
        double x = 0;
        if (sim::ParseFiniteDouble(v, &x) && std::abs(x) > limit) edits.push_back(p.key + "=" + v);
      }
    }
    if (edits.empty()) continue;
    script << frame << " load " << Stem(f) << "\n";
    for (const std::string& e : edits) script << frame + 1 << " edit " << e << "\n";
    script << frame + 3 << " screenshot " << dir << "/" << Stem(f) << ".png\n";
    found += static_cast<int>(edits.size());
    frame += 5;
  }
  script.close();
  std::printf("%d values beyond any slider\n", found);
  if (found == 0) GTEST_SKIP() << "no shipped tunable reaches beyond a slider";
  // The issue's reproducer: `formsim gui formation_traj2 --set robots.R2.follow.k_l=1e308`
  // aborted at start (when k_l is left unbounded).
  {
    sim::Session traj2(testing::Scenario("formation_traj2"), {}, -1);
    const sim::Param* k_l = traj2.params().Find("robots.R2.follow.k_l");
    first_set = k_l && !std::isfinite(k_l->tune.hi)
                    ? "formation_traj2 --set robots.R2.follow.k_l=1e308"
                    : "formation_traj2";
  }
  const std::string log = dir + "/log.txt";
  const int rc = RunShell(TallXvfb("env FORMSIM_STATE_DIR=" + dir + "/state " + Binary() + " gui " +
                                   first_set + " --paused --size 1280x4000 --exit-after " +
                                   std::to_string(frame + 2) + " --script " + dir + "/script.txt"),
                          log);
  ASSERT_EQ(rc, 0) << ReadText(log).substr(0, 3000);
}

// A lesson whose every text (name, description, title, goal, an equation) and one robot's name
// hold 100,000 characters or more.
std::string LongLesson(const std::string& dir) {
  std::string text =
      ReadText(std::string(FORMSIM_SOURCE_DIR) + "/assets/lessons/deep_cascade.yaml");
  auto words = [](const std::string& w) {
    std::string s;
    while (s.size() < 100000) s += w + " ";
    return s;
  };
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto p = text.find(from);
    EXPECT_NE(p, std::string::npos) << from;
    if (p != std::string::npos) text.replace(p, from.size(), to);
  };
  const std::string robot = "R" + std::string(100000, 'x');
  replace("name: deep_cascade", "name: \"" + std::string(100000, 'N') + "\"");
  replace("description: \"", "description: \"" + words("description"));
  replace("title: \"", "title: \"" + words("title"));
  replace("  goal: >-\n", "  goal: >-\n    " + words("goal") + "\n");
  replace("  equations:\n", "  equations:\n    - \"" + words("equation") + "\"\n");
  for (std::string from : {"name: R1\n", "leaders: [R1]", "leaders: [R1,"}) {
    std::string to = from;
    to.replace(to.find("R1"), 2, robot);
    for (auto p = text.find(from); p != std::string::npos; p = text.find(from, p + to.size()))
      text.replace(p, from.size(), to);
  }
  const std::string path = dir + "/long_texts.yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(GuiSafety, TextsOfAHundredThousandCharactersDrawWithoutAnAssertion) {
  if (!HaveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_long_texts");
  const std::string lesson = LongLesson(dir);
  std::ofstream script(dir + "/script.txt");
  // A refused edit whose value (and so its message in the status line and the Messages list)
  // is 60,000 characters; every tab; a pin (legends); the window title follows the name.
  script << "2 edit robots.R2.follow.k_l=" << std::string(60000, '9') << "\n"
         << "3 edit robots.R2.follow.k_l" << std::string(60000, 'y') << "=1\n"
         << "4 screenshot " << dir << "/lesson.png\n"
         << "5 tab plots\n6 screenshot " << dir << "/plots.png\n"
         << "7 tab tables\n8 screenshot " << dir << "/tables.png\n"
         << "9 tab summary\n10 screenshot " << dir << "/summary.png\n"
         << "11 pin\n12 wait\n13 tab history\n14 screenshot " << dir << "/history.png\n"
         << "15 open " << lesson << "\n16 screenshot " << dir << "/reopened.png\n";
  script.close();
  const std::string log = dir + "/log.txt";
  const int rc =
      RunShell(Xvfb("env FORMSIM_STATE_DIR=" + dir + "/state " + Binary() + " gui " + lesson +
                    " --size 1280x800 --exit-after 20 --script " + dir + "/script.txt"),
               log);
  const std::string text = ReadText(log);
  ASSERT_EQ(rc, 0) << text.substr(0, 3000);
  EXPECT_EQ(CountOf(text, "refused"), 2) << text.substr(0, 3000);
  for (const char* shot : {"lesson", "plots", "tables", "summary", "history", "reopened"}) {
    int w = 0, h = 0;
    const auto px = ReadPng(dir + "/" + shot + ".png", &w, &h);
    EXPECT_EQ(w, 1280) << shot;
    EXPECT_GT(NonBackgroundFraction(px), 0.1) << shot;
  }
}

// ---- signals and crashes: the window in the background, a signal once a file shows up ----

// A window started in the background; one a failed test left running is killed when the test
// ends (it has no --exit-after).
struct Background {
  std::string dir;
  long pid = 0;
  ~Background() {
    std::error_code ec;
    if (pid > 0 && !fs::exists(dir + "/rc", ec)) ::kill(static_cast<pid_t>(pid), SIGKILL);
  }
};

bool WaitFor(const std::string& path, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    std::error_code ec;
    if (fs::exists(path, ec) && fs::file_size(path, ec) > 0) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// Starts `formsim gui ARGS` under Xvfb in the background with its own state folder; returns
// formsim's pid (the shell writes it, then formsim's exit status to dir/rc).
void Start(Background& b, const std::string& dir, const std::string& args) {
  b.dir = dir;
  const std::string inner = "FORMSIM_STATE_DIR=" + dir + "/state " + Binary() + " gui " + args +
                            " & echo \\$! > " + dir + "/pid; wait \\$!; echo \\$? > " + dir + "/rc";
  const std::string cmd =
      XvfbRun("1280x800") + "sh -c \"" + inner + "\" >" + dir + "/log.txt 2>&1 &";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_TRUE(WaitFor(dir + "/pid", 30));
  b.pid = std::atol(ReadText(dir + "/pid").c_str());
  ASSERT_GT(b.pid, 0) << ReadText(dir + "/log.txt");
}

int ExitStatus(const Background& b) {
  EXPECT_TRUE(WaitFor(b.dir + "/rc", 60)) << ReadText(b.dir + "/log.txt");
  return std::stoi(ReadText(b.dir + "/rc"));
}

// A deterministic session: paused, stepped by the script, with edits at known steps; then a
// screenshot to say "ready".
void WriteSteppedScript(const std::string& path, const std::string& ready) {
  std::ofstream s(path);
  int frame = 2;
  auto steps = [&](int n) {
    for (int i = 0; i < n; ++i) s << frame++ << " step\n";
  };
  steps(12);
  s << frame++ << " edit robots.R2.follow.k_l=0.4\n";
  steps(15);
  s << frame++ << " edit robots.R3.follow.k_l2=0.2\n";
  steps(9);
  s << frame++ << " screenshot " << ready << "\n";
}
constexpr int kScriptFrames = 2 + 12 + 1 + 15 + 1 + 9 + 1;

std::vector<std::string> Journals(const std::string& state) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(state, ec))
    if (e.path().extension() == ".journal") out.push_back(e.path().string());
  return out;
}

using testing::AnyTmp;

// The reference: the same stepped script in a window that ends by itself.
std::string ReferenceCsv(const std::string& dir) {
  WriteSteppedScript(dir + "/script.txt", dir + "/ready.png");
  const int rc = RunShell(
      Xvfb("env FORMSIM_STATE_DIR=" + dir + "/state " + Binary() +
           " gui formation_cascade7 --paused --size 800x500 --out " + dir + "/out --exit-after " +
           std::to_string(kScriptFrames + 3) + " --script " + dir + "/script.txt"),
      dir + "/log.txt");
  EXPECT_EQ(rc, 0) << ReadText(dir + "/log.txt");
  EXPECT_TRUE(Journals(dir + "/state").empty()) << "a clean exit removes its journal";
  return ReadText(dir + "/out/timeseries.csv");
}

TEST(GuiSession, KillNineLeavesAJournalThatReplaysToTheLastEditAndIsOfferedForRestore) {
  if (!HaveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string ref = ReferenceCsv(TempDir("gui_kill9_ref"));
  ASSERT_FALSE(ref.empty());
  const std::string dir = TempDir("gui_kill9");
  WriteSteppedScript(dir + "/script.txt", dir + "/ready.png");
  Background b;
  Start(b, dir,
        "formation_cascade7 --paused --size 800x500 --out " + dir + "/out --script " + dir +
            "/script.txt");
  ASSERT_GT(b.pid, 0);
  ASSERT_TRUE(WaitFor(dir + "/ready.png", 60)) << ReadText(dir + "/log.txt");
  std::this_thread::sleep_for(
      std::chrono::milliseconds(1500));  // the step is journaled each second
  ASSERT_EQ(::kill(static_cast<pid_t>(b.pid), SIGKILL), 0);
  EXPECT_EQ(ExitStatus(b), 128 + SIGKILL);
  // What a crash leaves: the journal (and the CSV's temporary, as any killed process would).
  const auto journals = Journals(dir + "/state");
  ASSERT_EQ(journals.size(), 1u);
  const int rc = RunShell(Binary() + " replay " + journals[0] + " --out " + dir + "/replayed",
                          dir + "/replay_log.txt");
  ASSERT_EQ(rc, 0) << ReadText(dir + "/replay_log.txt");
  const std::string replayed = ReadText(dir + "/replayed/timeseries.csv");
  EXPECT_EQ(replayed, ref) << "the journal replays byte for byte to the last step written";
  EXPECT_EQ(CountOf(replayed, "\n"), 1 + 1 + 12 + 15 + 9);  // header, row 0, 36 steps

  // The next window offers it and does nothing by itself; a script restores it and goes on.
  const std::string next = TempDir("gui_kill9_next");
  fs::copy(dir + "/state", next + "/state");
  std::ofstream(next + "/script.txt") << "2 screenshot " << next << "/offered.png\n"
                                      << "3 restore-session\n"
                                      << "4 screenshot " << next << "/restored.png\n"
                                      << "5 step\n6 step\n"
                                      << "7 save-session " << next << "/s.yaml\n"
                                      << "8 restore-session\n";  // refused: nothing left
  int rcn =
      RunShell(Xvfb("env FORMSIM_STATE_DIR=" + next + "/state " + Binary() +
                    " gui formation_traj2 --paused --size 1280x800 --exit-after 10 --script " +
                    next + "/script.txt"),
               next + "/log.txt");
  const std::string log = ReadText(next + "/log.txt");
  ASSERT_EQ(rcn, 0) << log;
  EXPECT_EQ(CountOf(log, "refused"), 1) << log;
  EXPECT_NE(log.find("no unfinished session"), std::string::npos) << log;
  EXPECT_TRUE(Journals(next + "/state").empty()) << "restored, then a clean exit: no journal left";
  // The saved session holds the killed window's edits and the two steps after the restore.
  const std::string saved = ReadText(next + "/s.yaml");
  EXPECT_NE(saved.find("robots.R3.follow.k_l2"), std::string::npos) << saved.substr(0, 2000);
  ASSERT_EQ(
      RunShell(Binary() + " replay " + next + "/s.yaml --out " + next + "/r", next + "/rl.txt"), 0)
      << ReadText(next + "/rl.txt");
  const std::string after = ReadText(next + "/r/timeseries.csv");
  EXPECT_EQ(after.substr(0, ref.size()), ref);
  EXPECT_EQ(CountOf(after, "\n"), CountOf(ref, "\n") + 2);

  // Discard: the journal goes; without an action it stays (never automatic).
  const std::string third = TempDir("gui_kill9_discard");
  fs::copy(dir + "/state", third + "/state");
  ASSERT_EQ(RunShell(Xvfb("env FORMSIM_STATE_DIR=" + third + "/state " + Binary() +
                          " gui formation_traj2 --paused --size 800x500 --exit-after 5"),
                     third + "/log.txt"),
            0);
  EXPECT_EQ(Journals(third + "/state").size(), 1u) << "a window never restores nor drops by itself";
  std::ofstream(third + "/script.txt") << "2 discard-session\n";
  ASSERT_EQ(RunShell(Xvfb("env FORMSIM_STATE_DIR=" + third + "/state " + Binary() +
                          " gui formation_traj2 --paused --size 800x500 --exit-after 5 --script " +
                          third + "/script.txt"),
                     third + "/log.txt"),
            0);
  EXPECT_TRUE(Journals(third + "/state").empty());
}

TEST(GuiSession, StopSignalsWriteTheResultsMarkedInterruptedAndTheSession) {
  if (!HaveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string ref = ReferenceCsv(TempDir("gui_signal_ref"));
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
    const std::string dir = TempDir("gui_signal_" + std::to_string(sig));
    WriteSteppedScript(dir + "/script.txt", dir + "/ready.png");
    Background b;
    Start(b, dir,
          "formation_cascade7 --paused --size 800x500 --out " + dir + "/out --session " + dir +
              "/s.yaml --script " + dir + "/script.txt");
    ASSERT_TRUE(WaitFor(dir + "/ready.png", 60)) << ReadText(dir + "/log.txt");
    ASSERT_EQ(::kill(static_cast<pid_t>(b.pid), sig), 0);
    EXPECT_EQ(ExitStatus(b), 128 + sig) << ReadText(dir + "/log.txt");
    EXPECT_NE(ReadText(dir + "/log.txt").find("interrupted"), std::string::npos);
    const std::string csv = ReadText(dir + "/out/timeseries.csv");
    EXPECT_EQ(csv, ref) << "signal " << sig;
    EXPECT_NE(ReadText(dir + "/out/summary.json").find("\"interrupted\""), std::string::npos);
    EXPECT_FALSE(AnyTmp(dir)) << "no .tmp file after signal " << sig;
    EXPECT_TRUE(Journals(dir + "/state").empty()) << "the session was saved: no journal";
    // The session file replays to the same CSV.
    ASSERT_EQ(
        RunShell(Binary() + " replay " + dir + "/s.yaml --out " + dir + "/r", dir + "/rl.txt"), 0)
        << ReadText(dir + "/rl.txt");
    EXPECT_EQ(ReadText(dir + "/r/timeseries.csv"), ref);
  }
  // Without --session the journal stays for restore.
  const std::string dir = TempDir("gui_signal_nosession");
  WriteSteppedScript(dir + "/script.txt", dir + "/ready.png");
  Background b;
  Start(b, dir, "formation_cascade7 --paused --size 800x500 --script " + dir + "/script.txt");
  ASSERT_TRUE(WaitFor(dir + "/ready.png", 60));
  ASSERT_EQ(::kill(static_cast<pid_t>(b.pid), SIGTERM), 0);
  EXPECT_EQ(ExitStatus(b), 143);
  EXPECT_EQ(Journals(dir + "/state").size(), 1u);
}

TEST(GuiWrites, AFailedScreenshotSaysSoWithTheScriptLineAndScreenshotExitsWith4) {
  if (!HaveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_failed_writes");
  std::ofstream(dir + "/script.txt") << "2 screenshot " << dir << "/no/such/folder/a.png\n"
                                     << "3 screenshot /dev/full\n"
                                     << "4 save-session /dev/full\n"
                                     << "5 save " << dir << "/no/such/folder/t.yaml\n"
                                     << "6 screenshot " << dir << "/fine.png\n";
  int rc = RunShell(Xvfb("env FORMSIM_STATE_DIR=" + dir + "/state " + Binary() +
                         " gui formation_traj2 --paused --size 800x500 --exit-after 8 --script " +
                         dir + "/script.txt"),
                    dir + "/log.txt");
  std::string log = ReadText(dir + "/log.txt");
  EXPECT_EQ(rc, 0) << log;
  EXPECT_NE(
      log.find("script.txt:1 (frame 2): 'screenshot " + dir + "/no/such/folder/a.png' failed"),
      std::string::npos)
      << log;
  EXPECT_NE(log.find("script.txt:2 (frame 3): 'screenshot /dev/full' failed"), std::string::npos)
      << log;
  EXPECT_NE(log.find("script.txt:3 (frame 4): 'save-session /dev/full' refused"), std::string::npos)
      << log;
  EXPECT_NE(log.find("script.txt:4 (frame 5)"), std::string::npos) << log;
  EXPECT_EQ(CountOf(log, "' failed: "), 2) << log;
  EXPECT_TRUE(fs::exists(dir + "/fine.png"));
  if (::geteuid() != 0) {  // root writes into a read-only folder
    fs::create_directories(dir + "/ro");
    fs::permissions(dir + "/ro", fs::perms::owner_read | fs::perms::owner_exec);
    std::ofstream(dir + "/script2.txt") << "2 screenshot " << dir << "/ro/a.png\n";
    RunShell(
        Xvfb(Binary() + " gui formation_traj2 --paused --size 800x500 --exit-after 5 --script " +
             dir + "/script2.txt"),
        dir + "/log2.txt");
    EXPECT_NE(ReadText(dir + "/log2.txt").find("failed"), std::string::npos);
    fs::permissions(dir + "/ro", fs::perms::owner_all);
  }
  // --screenshot that cannot be written: a message and the export-failure status.
  for (const std::string& path : {std::string("/dev/full"), dir + "/no/such/folder/s.png"}) {
    rc = RunShell(
        Xvfb("env FORMSIM_STATE_DIR=" + dir + "/state " + Binary() +
             " gui formation_traj2 --paused --size 800x500 --exit-after 3 --screenshot " + path),
        dir + "/log3.txt");
    log = ReadText(dir + "/log3.txt");
    EXPECT_EQ(rc, 4) << path << ": " << log;
    EXPECT_NE(log.find("--screenshot " + path + " failed"), std::string::npos) << log;
  }
}

}  // namespace
}  // namespace formsim::app
