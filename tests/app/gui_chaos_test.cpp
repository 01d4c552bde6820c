// The GUI chaos test: a seeded generator draws N random actions from the window's command table
// (app/gui/command_table.hpp), with random and extreme arguments (out of range, non-finite, huge,
// wrong words, /dev/zero, missing folders), and runs them in the real window under Xvfb (and
// under ASan+UBSan in the sanitizer suite). The window must stay up to its last frame and exit
// 0 with no sanitizer report, and the session it records must replay to the same CSV, byte for
// byte. N = FORMSIM_CHAOS_ACTIONS (default 2000; scripts/fuzz.sh runs more), seed
// FORMSIM_CHAOS_SEED (default 1).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "app/gui/command_table.hpp"
#include "app/export/video_writer.hpp"
#include "sim/core/number_format.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;
using testing::Xvfb;

long EnvOr(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != 0 ? std::atol(v) : fallback;
}

class Chaos {
 public:
  Chaos(unsigned seed, std::string dir, std::vector<std::string> keys)
      : rng_(seed), dir_(std::move(dir)), keys_(std::move(keys)) {}

  template <typename T>
  const T& Pick(const std::vector<T>& v) {
    return v[std::uniform_int_distribution<std::size_t>(0, v.size() - 1)(rng_)];
  }
  bool Coin(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }

  std::string Number(double lo, double hi, bool whole) {
    const std::vector<std::string> extreme = {
        "nan", "inf",      "-inf", "1e308", "-1e308",
        "-0",  "4.9e-324", "abc",  "",      "9223372036854775808"};
    if (Coin(0.3)) return Pick(extreme);
    if (Coin(0.3)) return sim::FormatDouble(Coin(0.5) ? lo : hi);
    const double v = std::uniform_real_distribution<double>(lo, std::min(hi, lo + 50))(rng_);
    return whole ? std::to_string(static_cast<long long>(v)) : sim::FormatDouble(v);
  }

  std::string Path(const std::string& ext) {
    const std::vector<std::string> odd = {"/dev/zero",      "/dev/full", "/nonexistent/dir/x" + ext,
                                          "/proc/self/mem", dir_,        ""};
    if (Coin(0.25)) return Pick(odd);
    return dir_ + "/f" + std::to_string(std::uniform_int_distribution<int>(0, 5)(rng_)) + ext;
  }

  std::string Free(const Command& c, const CommandArg& a) {
    const std::string huge(Coin(0.5) ? 300 : 30000, 'x');
    if (Coin(0.05)) return huge;
    if (c.name == "edit" && !keys_.empty()) return Pick(keys_) + "=" + Number(-10, 10, false);
    if (c.name == "revert" && !keys_.empty()) return Pick(keys_);
    if (c.name == "load" || c.name == "lesson")
      return Pick(std::vector<std::string>{"formation_traj2", "formation_switching", "agv_fused",
                                           "ll_singularity", "no_such", huge});
    if (c.name == "open") return Coin(0.5) ? testing::Scenario("formation_traj2") : Path(".yaml");
    if (c.name == "formation")
      return Pick(std::vector<std::string>{"shape wedge 0.6", "shape grid 1e308", "remove R5",
                                           "add l_phi R1 0.5 0.5", "attach R4 l_l R1 R2", "shape",
                                           "explode"});
    if (c.name == "overlay")
      return Pick(std::vector<std::string>{"all", "none", "default", "-links", "nonsense"});
    if (c.name == "reset-seed")
      return Pick(
          std::vector<std::string>{"0", "18446744073709551615", "18446744073709551616", "-1", "7"});
    if (a.name == "PATH" || a.name == "DIR")
      return Path(c.name == "screenshot" ? ".png" : c.name == "export-figures" ? "" : ".yaml");
    return Pick(std::vector<std::string>{"R2", "R3", "nobody", "switch-formation", "x"});
  }

  std::string Line(const Command& c) {
    std::string line = c.name;
    for (const CommandArg& a : c.args) {
      if (a.optional && Coin(0.5)) break;
      std::string v;
      switch (a.type) {
        case ArgType::kWhole:
          v = Number(a.lo, std::min(a.hi, 30.0), true);  // seeds: at most a few dozen
          break;
        case ArgType::kReal:
          v = Number(a.lo, a.hi, false);
          break;
        case ArgType::kOnOff:
          v = Pick(std::vector<std::string>{"on", "off", "toggle", "maybe"});
          break;
        case ArgType::kChoice:
          v = !a.choices.empty() && Coin(0.9) ? Pick(a.choices) : Free(c, a);
          break;
        case ArgType::kWord:
        case ArgType::kRest:
          v = Free(c, a);
          break;
      }
      line += " " + v;
    }
    return line;
  }

 private:
  std::mt19937_64 rng_;
  std::string dir_;
  std::vector<std::string> keys_;
};

TEST(GuiChaos, RandomCommandsNeverEndTheWindowAndTheSessionReplays) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const long n = EnvOr("FORMSIM_CHAOS_ACTIONS", 2000);
  const unsigned seed = static_cast<unsigned>(EnvOr("FORMSIM_CHAOS_SEED", 1));
  const std::string dir = TempDir("gui_chaos");
  std::vector<std::string> keys;
  const sim::Session start(testing::Scenario("formation_switching"), std::vector<sim::Override>{});
  for (const sim::Param& p : start.params().all()) keys.push_back(p.key);
  Chaos chaos(seed, dir + "/files", keys);
  std::filesystem::create_directories(dir + "/files");
  std::vector<const Command*> pool;
  for (const Command& c : Commands())
    if (!c.ends_program && c.name != "wait") pool.push_back(&c);
  {
    std::ofstream script(dir + "/chaos.txt");
    script << "# " << n << " random actions, seed " << seed << "\n0 speed max\n";
    for (long i = 0; i < n; ++i) script << i + 1 << " " << chaos.Line(*chaos.Pick(pool)) << "\n";
    // Then a run of some length, so that the replay is compared over many rows, not one.
    script << n + 1 << " live\n"
           << n + 2 << " reset\n"
           << n + 3 << " speed max\n"
           << n + 4 << " play\n";
  }
  // In its own folder (a save or screenshot without a path writes into the working folder),
  // with a state folder of its own: restore-session finds no other window's journal.
  const int rc =
      RunShell("cd " + dir + "/files && FORMSIM_STATE_DIR=" + dir + "/state " +
                   Xvfb(Binary() +
                        " gui formation_switching --size 640x400 --paused "
                        "--exit-after " +
                        std::to_string(n + 40) + " --script " + dir + "/chaos.txt --out " + dir +
                        "/live --session " + dir + "/session.yaml"),
               dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  ASSERT_EQ(rc, 0) << log.substr(log.size() > 4000 ? log.size() - 4000 : 0);
  EXPECT_EQ(log.find("AddressSanitizer"), std::string::npos);
  EXPECT_EQ(log.find("runtime error"), std::string::npos);
  EXPECT_GT(testing::CountOf(log, "refused"), n / 20) << "the chaos should hit refusals";
  const int rrc = RunShell(Binary() + " replay " + dir + "/session.yaml --out " + dir + "/replay",
                           dir + "/replay_log.txt");
  ASSERT_EQ(rrc, 0) << ReadText(dir + "/replay_log.txt");
  const std::string live = ReadText(dir + "/live/timeseries.csv");
  EXPECT_GT(testing::CountOf(live, "\n"), 20) << "the last run should have many rows";
  EXPECT_TRUE(live == ReadText(dir + "/replay/timeseries.csv"))
      << "the replayed session's CSV differs from the window's";
}

}  // namespace
}  // namespace formsim::app
