#pragma once
/// \file Helpers shared by the app tests: temp folders, running the formsim binary, pixels.

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include "sim/core/draw.hpp"
#include "sim/core/param_table.hpp"
#include "sim/scenario/scenario_files.hpp"

namespace formsim::app::testing {

/// The windows the tests start keep their crash-safe session journals (sim/session/session_journal)
/// under the build tree, never in the user's state folder (whose unfinished sessions would put a
/// banner into the tests' pictures), and their settings (UI scale, lesson progress) there too,
/// never in the user's. Set once, before any test runs; children inherit it.
inline const bool kStateDirSet = [] {
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/test_tmp/state";
  ::setenv("FORMSIM_STATE_DIR", dir.c_str(), 0);
  const std::string config = std::string(FORMSIM_BINARY_DIR) + "/test_tmp/config";
  ::setenv("XDG_CONFIG_HOME", config.c_str(), 1);
  return true;
}();

/// Shipped scenarios for the tests that go through every parameter (each edit re-reads the
/// whole file): all but those over 100 kB, the generated formation_swarm_1000, whose keys are
/// those of formation_swarm_100 (the same generator).
inline std::vector<std::string> PerParameterScenarios() {
  std::vector<std::string> out;
  for (const std::string& f : sim::ShippedScenarios())
    if (std::filesystem::file_size(f) <= 100000) out.push_back(f);
  return out;
}

/// The parameters such a test goes through: every one, except in a large formation (over 300
/// tunables, its robots repeating the same keys), where they are the scenario-wide ones and those
/// of its first three robots (a root, an l-l and an l-φ follower in the generated swarms).
inline std::vector<sim::Param> ParamsToExercise(const sim::ParamTable& table) {
  if (table.size() <= 300) return table.all();
  std::vector<sim::Param> out;
  std::set<std::string> robots;
  for (const sim::Param& p : table.all()) {
    if (p.key.rfind("robots.", 0) != 0) {
      out.push_back(p);
      continue;
    }
    const std::string robot = p.key.substr(7, p.key.find('.', 7) - 7);
    if (robots.count(robot) == 0 && robots.size() >= 3) continue;
    robots.insert(robot);
    out.push_back(p);
  }
  return out;
}

inline std::string Scenario(const std::string& stem) {
  return std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/" + stem + ".yaml";
}

/// A fresh folder under the build tree, removed first if it exists.
inline std::string TempDir(const std::string& name) {
  const std::filesystem::path p = std::filesystem::path(FORMSIM_BINARY_DIR) / "test_tmp" / name;
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p.string();
}

inline std::string Binary() {
  return std::string(FORMSIM_BINARY_DIR) + "/formsim";
}

/// How many times `what` occurs in `text` (refusals in a GUI log).
inline int CountOf(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

/// Runs a shell command, returns its exit code (output goes to `log`).
inline int RunShell(const std::string& cmd, const std::string& log) {
  const int status = std::system((cmd + " >" + log + " 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// A shell command that starts `cmd` (a sweep writing into `dir`) and sends it `signal` (e.g.
/// "-9", "-INT") once `dir`/runs holds `records` finished run records; its exit code is the
/// sweep's. Signalled by what is on disk, not after a sleep: a fixed sleep raced the sweep on
/// loaded machines (it outlasted the whole sweep).
inline std::string SignalOnceRecorded(const std::string& cmd, const std::string& dir, int records,
                                      const std::string& signal) {
  return "(" + cmd + " & pid=$!; for i in $(seq 1 6000); do [ $(ls " + dir +
         "/runs 2>/dev/null | grep -c '[.]run$') -ge " + std::to_string(records) +
         " ] && break; sleep 0.005; done; kill " + signal + " $pid; wait $pid)";
}

/// The start of a command line that runs what follows under a virtual X server of `screen`
/// ("1280x800") pixels. ctest runs GUI tests side by side and `xvfb-run -a` alone searches for a
/// free display from the same number (99) in each: two that start together can take the same
/// one, and one then fails with "Xvfb failed to start". Each call here starts its search from
/// its own number (the process id and a count), so they do not meet.
inline std::string XvfbRun(const std::string& screen) {
  static int calls = 0;
  const int from = 100 + static_cast<int>((static_cast<long>(getpid()) * 37 + 211 * calls++) % 3000);
  return "xvfb-run -n " + std::to_string(from) + " -a -s '-screen 0 " + screen + "x24' ";
}

/// `cmd` run under a virtual X server (1280x800), for the GUI tests.
inline std::string Xvfb(const std::string& cmd) { return XvfbRun("1280x800") + cmd; }

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Fraction of pixels that differ from the most common colour (the background).
inline double NonBackgroundFraction(const std::vector<std::uint8_t>& rgba) {
  std::vector<std::uint32_t> px(rgba.size() / 4);
  for (std::size_t i = 0; i < px.size(); ++i)
    px[i] = rgba[4 * i] | rgba[4 * i + 1] << 8 | rgba[4 * i + 2] << 16;
  // Background: the most frequent colour among a sample.
  std::vector<std::uint32_t> sample;
  for (std::size_t i = 0; i < px.size(); i += 97) sample.push_back(px[i]);
  std::sort(sample.begin(), sample.end());
  std::uint32_t bg = sample[0];
  std::size_t best = 0;
  for (std::size_t i = 0; i < sample.size();) {
    std::size_t j = i;
    while (j < sample.size() && sample[j] == sample[i]) ++j;
    if (j - i > best) best = j - i, bg = sample[i];
    i = j;
  }
  std::size_t other = 0;
  for (std::uint32_t p : px) other += p != bg;
  return static_cast<double>(other) / px.size();
}

/// One pixel's colour, 0-255 per channel.
struct Rgb {
  int r, g, b;
};
/// The pixel at logical (x, y) of an RGBA image `w` pixels wide.
inline Rgb At(const std::vector<std::uint8_t>& px, int w, float x, float y) {
  const std::size_t i = (static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)) * 4;
  return {px[i], px[i + 1], px[i + 2]};
}
/// Euclidean distance in 0-255 units between a pixel and a colour.
inline double Distance(Rgb a, sim::Color c) {
  const double dr = a.r - 255.0 * c.r, dg = a.g - 255.0 * c.g, db = a.b - 255.0 * c.b;
  return std::sqrt(dr * dr + dg * dg + db * db);
}

/// Runs the built formsim with `args` (a shell command line), output to `log`; its exit code.
inline int Formsim(const std::string& args, const std::string& log) {
  return RunShell(Binary() + " " + args, log);
}

/// Whether any file under `dir` ends in .tmp (a write that was not finished or cleaned up).
inline bool AnyTmp(const std::string& dir) {
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.path().extension() == ".tmp") return true;
  return false;
}

}  // namespace formsim::app::testing
