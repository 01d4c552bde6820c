#pragma once
/// \file The tables of a sweep, built from its definition and its run records alone (never from
/// the order or place the runs ran in), so a sweep on one core, on all cores, resumed, or
/// collected from shards writes the same bytes:
///   runs.csv       one row per run: run, the varied keys, seed, every metric, the settings the
///                  run used (columns settings.<name>: control_period, settle_time ...), status,
///                  message
///   aggregate.csv  one row per point: the varied keys, runs, failed, and for every metric
///                  n, mean, std, min, max, median, q05, q95, sem, ci95_lo and ci95_hi over the
///                  completed runs (metric_stats.hpp says how each is computed), then each
///                  setting (settings.<name>) when the point's completed runs agree on it
/// A sweep over several scenarios has a `scenario` column (the file's stem) after `run` in
/// runs.csv and after `point` in aggregate.csv, whose rows are then one per scenario and point
/// (point numbers are shared by the scenarios), and writes a third table:
///   aggregate_over_scenarios.csv  one row per point: the varied keys, scenarios, runs, failed
///                  and the same statistics over every completed run of every scenario (the
///                  scenarios in order, each in seed order): .mean, .max and .q95 are what
///                  `formsim tune --over mean`, `max` and `quantile:0.95` fold the runs into
/// Metric columns are the dotted paths of summary.json's `results` (Metrics::Scalars), in the
/// order they first appear in run order. Numbers are shortest round-trip text.

#include <cstddef>
#include <string>
#include <vector>

#include "sim/study/metric_stats.hpp"
#include "sim/study/sweep_store.hpp"

namespace formsim::sim {

/// The statistics after each metric's name in aggregate.csv's header, in order (".n", ...).
const std::vector<std::string>& AggregateSuffixes();

/// aggregate_over_scenarios.csv's name.
constexpr const char* kPooledCsv = "aggregate_over_scenarios.csv";

/// The rows of aggregate_over_scenarios.csv (a sweep over several scenarios).
struct SweepPooled {
  std::vector<std::size_t> points;              ///< the points with at least one record, in order
  std::vector<std::size_t> scenarios;           ///< per entry: how many scenarios have a record
  std::vector<std::size_t> runs, failed;        ///< per entry, over every scenario
  std::vector<std::vector<MetricStats>> stats;  ///< [entry][metric]
  std::string csv;                              ///< "" for a sweep of one scenario
};

struct SweepTables {
  std::vector<std::string> metrics;             ///< the metric columns, in order
  std::vector<MetricInfo> info;                 ///< per metric: what its kind declared
  std::vector<std::string> settings;            ///< the settings columns (without "settings.")
  /// The rows of aggregate.csv: the points that have at least one record (several scenarios:
  /// each scenario's points, scenario by scenario).
  std::vector<std::size_t> points;
  std::vector<std::size_t> scenarios;           ///< per entry: its scenario (index)
  std::vector<std::size_t> runs, failed;        ///< per entry of `points`
  std::vector<std::vector<MetricStats>> stats;  ///< [entry of points][metric]
  std::string runs_csv, aggregate_csv;
  SweepPooled pooled;  ///< several scenarios: the statistics over all of them per point
  /// Index of `metric` in `metrics`, or -1.
  int MetricIndex(const std::string& metric) const;
};

/// Builds the tables from `records` (any order; each run at most once).
SweepTables BuildSweepTables(const SweepDefinition& def, std::vector<SweepRecord> records);

/// The metric a sweep shows when none is asked for: the kind's first headline (the first metric
/// whose declared headline rank is the lowest); for records without metadata, the first whose
/// mean differs between points (or, with one point, whose min and max differ), else the first.
std::size_t DefaultMetric(const SweepTables& tables);

/// Points sorted by the mean of metric `m` (ascending, points without a value last) as an
/// aligned text table: the table a sweep of three or more keys shows instead of a figure.
/// Several scenarios: the points by their statistics over every scenario and seed.
std::string RankingText(const SweepDefinition& def, const SweepTables& tables, int m);

/// The axis title of metric `m`: its declared label with the unit in brackets, or its path.
std::string MetricAxisLabel(const SweepTables& tables, int m);

/// Writes runs.csv, aggregate.csv and (several scenarios) aggregate_over_scenarios.csv into
/// `dir`, each atomically. Returns their names.
std::vector<std::string> WriteSweepTables(const std::string& dir, const SweepTables& tables);

/// A CSV field (RFC 4180): quoted, with quotes doubled, when it holds a comma, quote or line break.
std::string CsvField(const std::string& s);

/// `name` suggestions for an unknown metric: the metrics that share its last part or contain it.
std::string SimilarMetrics(const std::vector<std::string>& metrics, const std::string& name);

}  // namespace formsim::sim
