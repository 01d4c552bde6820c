#pragma once
/// \file Helpers shared by the app tests: temp folders, running the formsim binary, pixels.

#include <sys/wait.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace formsim::app::testing {

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

/// Runs a shell command, returns its exit code (output goes to `log`).
inline int RunShell(const std::string& cmd, const std::string& log) {
  const int status = std::system((cmd + " >" + log + " 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

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

}  // namespace formsim::app::testing
