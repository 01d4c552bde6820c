#pragma once
/// \file Shared check of the invalid scenario fixtures: every
/// tests/fixtures/invalid/<prefix>*.yaml starts with "# expect: <text>"; loading it must throw a
/// ScenarioError that contains the text, starts with "<file>:" and points at a line holding the
/// offending key.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "sim/scenario/scenario.hpp"

namespace formsim::testing {

/// Checks every fixture whose file name starts with `prefix`; returns how many were checked.
inline int CheckInvalidFixtures(const std::string& prefix) {
  const std::filesystem::path dir = std::string(FORMSIM_SOURCE_DIR) + "/tests/fixtures/invalid";
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string file = entry.path().string(), stem = entry.path().filename().string();
    if (stem.rfind(prefix, 0) != 0 || entry.path().extension() != ".yaml") continue;
    std::ifstream in(file);
    std::string first;
    std::getline(in, first);
    EXPECT_EQ(first.rfind("# expect: ", 0), 0u) << file << " has no '# expect:' first line";
    const std::string expect = first.substr(std::min<std::size_t>(10, first.size()));
    try {
      sim::LoadExperiment(file);
      ADD_FAILURE() << file << " was accepted";
    } catch (const sim::ScenarioError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(expect), std::string::npos) << file << "\n  got: " << what;
      EXPECT_EQ(what.rfind(file + ":", 0), 0u) << what;
      EXPECT_GT(e.line(), 0) << what;
      std::ifstream again(file);
      std::string line;
      for (int k = 0; k < e.line(); ++k) std::getline(again, line);
      // The last component of the key path, without a list index.
      std::string key = e.key().substr(e.key().rfind('.') + 1);
      key = key.substr(0, key.find('['));
      EXPECT_NE(line.find(key), std::string::npos) << what << "\n  line " << e.line() << ": " << line;
    }
    ++checked;
  }
  return checked;
}

}  // namespace formsim::testing
