#pragma once
/// \file Writing a run's outputs: timeseries.csv and summary.json in an output folder.

#include <string>

#include "sim/core/experiment.hpp"

namespace formsim::sim {

/// Rows a headless run (`formsim run`, each run of a sweep) keeps in memory for its figures;
/// the CSV is streamed to disk. The same bound everywhere, so a sweep's run is `formsim run`.
constexpr std::size_t kRunHistoryRows = 20000;

/// Creates `dir` (and parents) and checks that a file can be written in it, before any work is
/// done, so a bad folder fails fast. Throws std::runtime_error naming the folder and the reason.
void PrepareOutputDir(const std::string& dir);

/// `dir/timeseries.csv`.
std::string CsvPath(const std::string& dir);

/// Writes `dir/summary.json` and completes `dir/timeseries.csv` (finishing the stream when the
/// recorder streams there, else writing the rows in memory). Files are written to a temporary
/// name, synced and renamed, so a failure never leaves a half-written file; when one file
/// fails the other is still written. Throws std::runtime_error naming what failed.
void WriteRunOutputs(Experiment& experiment, const std::string& dir);

/// Writes `text` to `path` atomically (temp file, every write checked, fsync, rename). Throws
/// std::runtime_error and removes the temporary on failure. `sync` false skips the fsync: the
/// file still appears whole or not at all if the process dies, but a power cut may leave it
/// empty (for many small files synced together later, e.g. a sweep's run records).
void WriteFileAtomic(const std::string& path, const std::string& text, bool sync = true);

/// Flushes every written file of the file system holding `dir` to the disk (syncfs). Throws
/// std::runtime_error on failure.
void SyncFileSystem(const std::string& dir);

}  // namespace formsim::sim
