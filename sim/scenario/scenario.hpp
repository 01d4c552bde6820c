#pragma once
/// \file The one load path. Every way of running a scenario (`formsim run` with or without
/// export flags, `formsim gui`, a GUI reset, reload or edit, a sweep) goes through
/// ParseScenario: the file's text, parsed afresh (so every node keeps its line), plus the
/// overrides (--set, --seed, GUI edits) in order, read strictly by the kind's reader. An error
/// names file:line:key, or the override that put the bad value there.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "sim/core/experiment.hpp"
#include "sim/scenario/lesson.hpp"
#include "sim/core/param_table.hpp"
#include "sim/core/provenance.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

/// The text of a scenario and where it came from.
class ScenarioSource {
 public:
  /// Reads `file`. Throws ScenarioError when it cannot be read.
  static ScenarioSource FromFile(const std::string& file);
  /// A scenario held in memory; relative paths in it resolve against `dir`.
  static ScenarioSource FromText(std::string text, std::string name, std::string dir);

  const std::string& file() const { return file_; }
  const std::string& dir() const { return dir_; }
  const std::string& text() const { return text_; }
  const std::string& sha256() const { return sha256_; }

 private:
  std::string file_, dir_, text_, sha256_;
};

/// A scenario read and checked: what is needed to build an experiment or to retune one.
struct ParsedScenario {
  ExperimentSetup setup;
  std::shared_ptr<const ExperimentConfig> config;
  ParamTable params;              ///< every tunable with its current value
  std::vector<PathField> paths;   ///< file-path keys (rewritten by Save into another folder)
  const ExperimentKind* kind = nullptr;
  LessonDef lesson;               ///< the `lesson:` block of a lesson file (present = false else)
};

/// The longest value one override (`--set`, a GUI or script edit) may carry: 64 KiB.
constexpr std::size_t kMaxOverrideBytes = std::size_t{64} << 10;

/// Reads `source` with `overrides` applied in order (each value at most kMaxOverrideBytes).
/// Throws ScenarioError.
ParsedScenario ParseScenario(const ScenarioSource& source, const std::vector<Override>& overrides);
/// Builds the experiment. Throws on failures of the kind's constructor.
std::unique_ptr<Experiment> BuildExperiment(const ParsedScenario& parsed);

/// `--set key=value` strings and `--seed` as overrides (seed < 0: none). Throws ScenarioError
/// naming the malformed assignment.
std::vector<Override> CliOverrides(const std::vector<std::string>& sets, long long seed);

/// Convenience for tests, benchmarks and `formsim run`: file + --set + --seed -> experiment.
std::unique_ptr<Experiment> LoadExperiment(const std::string& file,
                                           const std::vector<std::string>& sets = {},
                                           long long seed = -1);

/// Same from YAML text held in memory (tests, generated scenarios); `name` is used in messages.
std::unique_ptr<Experiment> LoadExperimentFromText(const std::string& text,
                                                   const std::string& name = "scenario",
                                                   const std::vector<std::string>& sets = {},
                                                   long long seed = -1);

}  // namespace formsim::sim
