#pragma once
/// \file File helpers the test suites share: a file's whole text, and the path of a shipped
/// scenario.

#include <fstream>
#include <sstream>
#include <string>

namespace formsim::testing {

/// The whole content of `path`, bytes as they are ("" when it cannot be read).
inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The path of the shipped scenario assets/scenarios/<name>.yaml.
inline std::string ShippedScenario(const std::string& name) {
  return std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/" + name + ".yaml";
}

}  // namespace formsim::testing
