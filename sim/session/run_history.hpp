#pragma once
/// \file The history of a tuning session: one row for every run that reached its end or was
/// reset, with when, how far it got, the settings that differ from the scenario's text, the seed
/// and the headline metrics (Metrics::Headlines). A row keeps its scenario text and run log, so
/// it can be replayed exactly later (pinned) and its settings restored. Saved as YAML beside a
/// saved scenario (`<name>.history.yaml`) and read back when that scenario is opened.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/core/metrics.hpp"
#include "sim/core/setting_changes.hpp"
#include "sim/session/run_log.hpp"
#include "sim/session/session.hpp"

namespace formsim::sim {

struct HistoryRow {
  int number = 0;    ///< 1, 2, ... in the order the rows were added (`restore N`)
  std::string when;  ///< local time the row was added, "2024-05-01 14:32:05"
  double t_end = 0;  ///< simulated time the run reached, s
  long steps = 0;
  std::string status;  ///< "completed", "reset", "numerical_fault", "interrupted", "branched"
  std::uint64_t seed = 0;
  std::shared_ptr<const ScenarioSource> source;  ///< the text the run was read from
  RunLog log;                                    ///< replays the run exactly
  /// Tunables at the end of the run that differ from its text: key, value (YAML text).
  std::vector<std::pair<std::string, std::string>> settings;
  std::vector<Metrics::HeadlineValue> metrics;
  /// Edits, drags and actions applied while it ran (the settings are the ones at its end).
  int mid_run_changes() const;
  /// The value of tunable `key` in this run at its end ("" when it is not a tunable).
  /// `text_params`: the tunables of `source` read without overrides.
  std::string Value(const std::string& key, const ParamTable& text_params) const;
};

class RunHistory {
 public:
  /// A row for the current run of `session`, as it stands. Throws ScenarioError when the
  /// session's own text no longer reads (it did when the run was built).
  static HistoryRow RowOf(const Session& session, const std::string& status);

  /// Adds a row, numbered after the last one.
  void Add(HistoryRow row);
  const std::vector<HistoryRow>& rows() const { return rows_; }
  const HistoryRow* Find(int number) const;
  bool empty() const { return rows_.empty(); }
  void Clear() { rows_.clear(); }

  /// The history as YAML (each scenario text once, by SHA-256).
  std::string ToYaml() const;
  void Save(const std::string& path) const;  ///< atomically; throws std::runtime_error
  /// Reads a history. Throws std::runtime_error naming file:line and the key.
  static RunHistory Parse(const std::string& text, const std::string& file);
  static RunHistory Load(const std::string& path);
  /// `<folder>/<stem>.history.yaml` for the scenario `scenario_file`.
  static std::string PathFor(const std::string& scenario_file);

 private:
  std::vector<HistoryRow> rows_;
};

/// The settings that differ between two runs (`from` and `to` map keys to values; keys missing
/// on one side are left out), in the order of `from`, each tunable named by ShortKey.
std::vector<SettingChange> DifferencesOf(
    const std::vector<std::pair<std::string, std::string>>& from,
    const std::vector<std::pair<std::string, std::string>>& to, const ParamTable& params);
/// "k_l 0.15 -> 0.4, seed 1 -> 7": the settings that differ between two runs, each tunable named
/// by the shortest tail of its key that no other tunable of `params` shares. `from` and `to` map
/// keys to values; keys missing on one side are left out.
std::string DescribeDifferences(const std::vector<std::pair<std::string, std::string>>& from,
                                const std::vector<std::pair<std::string, std::string>>& to,
                                const ParamTable& params);
/// The shortest dotted tail of `key` that names no other tunable of `params` ("k_l", or
/// "R2.follow.k_l" when several robots have a k_l).
std::string ShortKey(const std::string& key, const ParamTable& params);

}  // namespace formsim::sim
