#pragma once
/// \file What produced a run: the scenario file and the hash of its text, every `--set` and
/// `--seed`, every GUI edit with the step it took effect, the seed and the formsim version.
/// Written into summary.json, so a tuned run can be told apart from the file's own.

#include <cstdint>
#include <string>
#include <vector>

#include "sim/core/json.hpp"

namespace formsim::sim {

/// One change on top of the scenario file.
struct Override {
  std::string key;     ///< dotted path, e.g. "robots.R2.follow.k_l" or "seed"
  std::string value;   ///< YAML text
  std::string origin;  ///< "--set", "--seed", "GUI edit", "script edit", "reset with seed"
  long step = -1;      ///< world step it took effect at; -1: from the start of the run
  /// "--set robots.R2.follow.k_l=0.3" (and " at step 120" for a mid-run edit).
  std::string Describe() const;
};

struct Provenance {
  std::string file;    ///< the scenario file as given
  std::string sha256;  ///< of its text as read
  std::uint64_t seed = 0;
  std::vector<Override> overrides;  ///< in the order they were applied
  Json ToJson() const;
};

/// "0.2.0 (git 1a2b3c4)": the version formsim was built as.
std::string FormsimVersion();

}  // namespace formsim::sim
