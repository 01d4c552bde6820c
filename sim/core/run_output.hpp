#pragma once
/// \file Writing a run's outputs: timeseries.csv and summary.json in an output folder.

#include <string>

#include "sim/core/experiment.hpp"

namespace formsim::sim {

/// Creates `dir` (and parents) and checks that a file can be written in it, before any work is
/// done, so a bad folder fails fast. Throws std::runtime_error naming the folder and the reason.
void PrepareOutputDir(const std::string& dir);

/// Writes `dir/timeseries.csv` and `dir/summary.json` (the summary gets the scenario name, seed,
/// steps and events added). Files are written to a temporary name and renamed, so a failure
/// never leaves a half-written file. Throws std::runtime_error on failure.
void WriteRunOutputs(const Experiment& experiment, const std::string& dir);

/// Writes `text` to `path` atomically (temp file + rename). Throws std::runtime_error.
void WriteFileAtomic(const std::string& path, const std::string& text);

}  // namespace formsim::sim
