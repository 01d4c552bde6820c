#pragma once
/// \file A sweep on disk. `DIR/sweep.manifest` holds the definition (its scenarios, axes with their
/// values, seeds, overrides, each scenario's hash), so shards, resumed sweeps, job lines and
/// `collect` check that they belong to the same sweep and can rebuild the tables without the
/// scenario. Each finished run is one file `DIR/runs/NNNNNN.run`, written atomically (temporary
/// file, rename): a run is recorded whole or not at all, and a record is never written twice by a
/// resumed sweep. Records are synced to disk together when a sweep ends (one fsync per record
/// would cost as much as the run). Both are small line-based texts ("name value", values escaped),
/// with every number as its shortest round-trip text.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/core/metrics.hpp"
#include "sim/study/sweep_spec.hpp"

namespace formsim::sim {

/// What one run of a sweep gave.
struct SweepRecord {
  std::size_t run = 0;
  std::string status;   ///< "completed", "numerical_fault" or "error"
  std::string message;  ///< the fault or error message ("" when completed)
  /// Metrics::Scalars(MetricRole::kResult), in order: what the sweep tables rank and plot.
  std::vector<std::pair<std::string, double>> metrics;
  /// Metrics::Scalars(MetricRole::kSetting): what the run ran with (runs.csv's settings.*).
  std::vector<std::pair<std::string, double>> settings;
  /// What the kind declared about each metric (label, unit, direction, headline rank), for the
  /// metrics it declared anything about. Records written before metadata existed have none.
  std::vector<std::pair<std::string, MetricInfo>> info;
  bool failed() const { return status != "completed"; }
};

/// `record`'s metrics, settings and their descriptions from a run's `results`.
void FillRecordMetrics(const Metrics& results, SweepRecord* record);

/// `DIR/sweep.manifest`.
std::string ManifestPath(const std::string& dir);
/// `DIR/runs/NNNNNN.run`.
std::string RecordPath(const std::string& dir, std::size_t run);

/// The manifest's text.
std::string ManifestText(const SweepDefinition& def);
/// Reads a manifest's text back (points and id recomputed and checked). Throws
/// std::runtime_error naming `where` when it is malformed.
SweepDefinition ParseManifest(const std::string& text, const std::string& where);
/// Writes the manifest into `dir` (created when missing). When one is there already it must be
/// the same sweep: otherwise throws, saying how they differ.
void WriteManifest(const std::string& dir, const SweepDefinition& def);
/// Reads `dir`'s manifest. Throws std::runtime_error when there is none or it is malformed.
SweepDefinition ReadManifest(const std::string& dir);
/// True when `dir` holds a manifest.
bool HasManifest(const std::string& dir);

std::string RecordText(const SweepDefinition& def, const SweepRecord& rec);
/// Parses a record; throws std::runtime_error naming `where` when it is malformed or belongs to
/// another sweep.
SweepRecord ParseRecord(const std::string& text, const SweepDefinition& def,
                        const std::string& where);
/// Writes `rec` atomically into `dir`.
void WriteRecord(const std::string& dir, const SweepDefinition& def, const SweepRecord& rec);
/// Removes the records of `runs` that were cut short (empty or without their last line: what a
/// power cut can leave of a record not yet synced), so that they run again. Returns their paths.
std::vector<std::string> RemoveDamagedRecords(const std::string& dir,
                                              const std::vector<std::size_t>& runs);
/// Every record in `dir`, sorted by run. Leftover temporaries of interrupted writes are ignored.
std::vector<SweepRecord> ReadRecords(const std::string& dir, const SweepDefinition& def);
/// The runs among `runs` that have no record in `dir` yet, in the same order.
std::vector<std::size_t> PendingRuns(const std::string& dir, const std::vector<std::size_t>& runs);

/// The runs of shard k (1-based) of n: every n-th run starting at k - 1, so each shard gets its
/// share of every part of the grid. k = n = 1: all runs.
std::vector<std::size_t> ShardRuns(std::size_t total, int k, int n);
/// Parses "K/N" (1 <= K <= N). Throws std::runtime_error naming --shard.
void ParseShard(const std::string& text, int* k, int* n);

}  // namespace formsim::sim
