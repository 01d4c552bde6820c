#include "sim/study/sweep_tables.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "control/common/float_limits.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {
namespace {

using control::kNaN;

void AppendNumberOrEmpty(std::string& out, double v) {
  if (!std::isnan(v)) AppendDouble(out, v);
}

// ",n,mean,std,...": one metric's statistics as aggregate.csv writes them.
void AppendStats(std::string& out, const MetricStats& s) {
  out += "," + std::to_string(s.n);
  for (double v :
       {s.mean, s.std, s.min, s.max, s.median, s.q05, s.q95, s.sem, s.ci95_lo, s.ci95_hi}) {
    out += ',';
    AppendNumberOrEmpty(out, v);
  }
}

}  // namespace

const std::vector<std::string>& AggregateSuffixes() {
  static const std::vector<std::string> kSuffixes = {
      ".n", ".mean", ".std", ".min", ".max", ".median", ".q05", ".q95", ".sem", ".ci95_lo", ".ci95_hi"};
  return kSuffixes;
}

namespace {

// aggregate_over_scenarios.csv: per point, the statistics over every completed run of every
// scenario (the scenarios in order, each in seed order), from the values of each entry.
void BuildPooled(const SweepDefinition& def,
                 const std::vector<std::vector<std::vector<double>>>& values, SweepTables* t) {
  std::vector<std::size_t> order;  // pooled entry of each point, in point order
  std::vector<std::size_t> slot(def.points.size(), SIZE_MAX);
  for (std::size_t e = 0; e < t->points.size(); ++e)
    if (slot[t->points[e]] == SIZE_MAX) {
      slot[t->points[e]] = 0;
      order.push_back(t->points[e]);
    }
  std::sort(order.begin(), order.end());
  for (std::size_t i = 0; i < order.size(); ++i) slot[order[i]] = i;
  SweepPooled& pooled = t->pooled;
  pooled.points = order;
  pooled.scenarios.assign(order.size(), 0);
  pooled.runs.assign(order.size(), 0);
  pooled.failed.assign(order.size(), 0);
  std::vector<std::vector<std::vector<double>>> all(
      order.size(), std::vector<std::vector<double>>(t->metrics.size()));
  // Entries come in run order: scenario by scenario, so each point's values are in scenario order.
  for (std::size_t e = 0; e < t->points.size(); ++e) {
    const std::size_t i = slot[t->points[e]];
    ++pooled.scenarios[i];
    pooled.runs[i] += t->runs[e];
    pooled.failed[i] += t->failed[e];
    for (std::size_t c = 0; c < t->metrics.size(); ++c)
      all[i][c].insert(all[i][c].end(), values[e][c].begin(), values[e][c].end());
  }
  std::string& csv = pooled.csv;
  csv = "point";
  for (const SweepAxis& a : def.axes) csv += "," + CsvField(a.key);
  csv += ",scenarios,runs,failed";
  for (const std::string& m : t->metrics)
    for (const std::string& s : AggregateSuffixes()) csv += "," + CsvField(m + s);
  csv += "\n";
  for (std::size_t i = 0; i < order.size(); ++i) {
    csv += std::to_string(order[i]);
    for (std::size_t a = 0; a < def.axes.size(); ++a) csv += "," + CsvField(def.Value(order[i], a));
    csv += "," + std::to_string(pooled.scenarios[i]) + "," + std::to_string(pooled.runs[i]) + "," +
           std::to_string(pooled.failed[i]);
    pooled.stats.emplace_back();
    for (std::size_t c = 0; c < t->metrics.size(); ++c) {
      pooled.stats.back().push_back(StatsOf(all[i][c]));
      AppendStats(csv, pooled.stats.back().back());
    }
    csv += "\n";
  }
}

std::string Short(double v) {
  return std::isnan(v) ? "-" : FormatSignificant(v, 4);
}

}  // namespace

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

int SweepTables::MetricIndex(const std::string& metric) const {
  for (std::size_t i = 0; i < metrics.size(); ++i)
    if (metrics[i] == metric) return static_cast<int>(i);
  return -1;
}

namespace {

// Where each metric's and each setting's column is, by name.
struct SweepColumnIndex {
  std::unordered_map<std::string, std::size_t> metric;
  std::unordered_map<std::string, std::size_t> setting;
};

// The metrics and settings of all runs (in the order they first appear) and what the kind
// declared about each metric.
SweepColumnIndex CollectSweepColumns(const std::vector<SweepRecord>& records, SweepTables* t) {
  SweepColumnIndex column;
  for (const SweepRecord& r : records) {
    for (const auto& m : r.metrics)
      if (column.metric.emplace(m.first, t->metrics.size()).second) t->metrics.push_back(m.first);
    for (const auto& m : r.settings)
      if (column.setting.emplace(m.first, t->settings.size()).second)
        t->settings.push_back(m.first);
  }
  // What the kind declared about each metric: from the first run (in run order) that says.
  t->info.resize(t->metrics.size());
  std::vector<bool> described(t->metrics.size(), false);
  for (const SweepRecord& r : records)
    for (const auto& [name, info] : r.info) {
      const auto it = column.metric.find(name);
      if (it == column.metric.end() || described[it->second]) continue;
      described[it->second] = true;
      t->info[it->second] = info;
    }
  return column;
}

// runs.csv: one row per run, its axes' values, seed, metrics, settings and status.
void WriteSweepRunsCsv(const SweepDefinition& def, const std::vector<SweepRecord>& records,
                       const SweepColumnIndex& column, SweepTables* t) {
  std::string& csv = t->runs_csv;
  csv = "run";
  const bool multi = def.MultiScenario();
  if (multi) csv += ",scenario";
  for (const SweepAxis& a : def.axes) csv += "," + CsvField(a.key);
  csv += ",seed";
  for (const std::string& m : t->metrics) csv += "," + CsvField(m);
  for (const std::string& m : t->settings) csv += "," + CsvField("settings." + m);
  csv += ",status,message\n";
  std::vector<double> row(t->metrics.size());
  for (const SweepRecord& r : records) {
    const std::size_t p = def.PointOf(r.run);
    csv += std::to_string(r.run);
    if (multi) csv += "," + CsvField(def.scenarios[def.ScenarioOf(r.run)].Name());
    for (std::size_t a = 0; a < def.axes.size(); ++a) csv += "," + CsvField(def.Value(p, a));
    csv += "," + std::to_string(def.SeedOf(r.run));
    std::fill(row.begin(), row.end(), kNaN);
    std::vector<bool> has(t->metrics.size(), false);
    for (const auto& m : r.metrics) {
      row[column.metric.at(m.first)] = m.second;
      has[column.metric.at(m.first)] = true;
    }
    for (std::size_t c = 0; c < row.size(); ++c) {
      csv += ',';
      if (has[c]) AppendDouble(csv, row[c]);  // a computed NaN stays visible as nan
    }
    std::vector<std::string> setting_cells(t->settings.size());
    for (const auto& m : r.settings)
      AppendDouble(setting_cells[column.setting.at(m.first)], m.second);
    for (const std::string& cell : setting_cells) csv += "," + cell;
    csv += "," + CsvField(r.status) + "," + CsvField(r.message) + "\n";
  }
}

// The completed runs' values per entry (one point of one scenario), for the statistics.
struct SweepEntryValues {
  std::vector<std::vector<std::vector<double>>> metrics;  // [entry][metric] -> values
  // [entry][setting]: the completed runs' common value ("" when they differ or none has it).
  std::vector<std::vector<std::string>> setting_text;
};

// Sorts the runs into entries (t's points, scenarios, runs and failed) and gathers the values
// of their completed runs, in seed order.
SweepEntryValues GatherSweepEntries(const SweepDefinition& def,
                                    const std::vector<SweepRecord>& records,
                                    const SweepColumnIndex& column, SweepTables* t) {
  SweepEntryValues values;
  std::vector<std::vector<bool>> setting_seen;
  std::size_t last_cell = 0;
  for (const SweepRecord& r : records) {
    // A cell: one point of one scenario (the point itself for one scenario).
    const std::size_t cell = r.run / def.seeds.size();
    if (t->points.empty() || last_cell != cell) {
      last_cell = cell;
      t->points.push_back(def.PointOf(r.run));
      t->scenarios.push_back(def.ScenarioOf(r.run));
      t->runs.push_back(0);
      t->failed.push_back(0);
      values.metrics.emplace_back(t->metrics.size());
      values.setting_text.emplace_back(t->settings.size());
      setting_seen.emplace_back(t->settings.size(), false);
    }
    ++t->runs.back();
    if (r.failed()) {
      ++t->failed.back();
      continue;
    }
    for (const auto& m : r.metrics)
      if (std::isfinite(m.second))
        values.metrics.back()[column.metric.at(m.first)].push_back(m.second);
    for (const auto& m : r.settings) {
      const std::size_t c = column.setting.at(m.first);
      std::string text;
      AppendDouble(text, m.second);
      std::string& common = values.setting_text.back()[c];
      if (!setting_seen.back()[c])
        common = text;
      else if (common != text)
        common.clear();
      setting_seen.back()[c] = true;
    }
  }
  return values;
}

// aggregate.csv: per entry, its axes' values, run counts, each metric's statistics (kept in
// t->stats) and the common settings.
void WriteSweepAggregateCsv(const SweepDefinition& def, const SweepEntryValues& values,
                            SweepTables* t) {
  const bool multi = def.MultiScenario();
  std::string& agg = t->aggregate_csv;
  agg = "point";
  if (multi) agg += ",scenario";
  for (const SweepAxis& a : def.axes) agg += "," + CsvField(a.key);
  agg += ",runs,failed";
  for (const std::string& m : t->metrics)
    for (const std::string& s : AggregateSuffixes()) agg += "," + CsvField(m + s);
  for (const std::string& m : t->settings) agg += "," + CsvField("settings." + m);
  agg += "\n";
  for (std::size_t e = 0; e < t->points.size(); ++e) {
    const std::size_t p = t->points[e];
    agg += std::to_string(p);
    if (multi) agg += "," + CsvField(def.scenarios[t->scenarios[e]].Name());
    for (std::size_t a = 0; a < def.axes.size(); ++a) agg += "," + CsvField(def.Value(p, a));
    agg += "," + std::to_string(t->runs[e]) + "," + std::to_string(t->failed[e]);
    t->stats.emplace_back();
    for (std::size_t c = 0; c < t->metrics.size(); ++c) {
      t->stats.back().push_back(StatsOf(values.metrics[e][c]));
      AppendStats(agg, t->stats.back().back());
    }
    for (const std::string& text : values.setting_text[e]) agg += "," + text;
    agg += "\n";
  }
}

}  // namespace

SweepTables BuildSweepTables(const SweepDefinition& def, std::vector<SweepRecord> records) {
  std::sort(records.begin(), records.end(),
            [](const SweepRecord& a, const SweepRecord& b) { return a.run < b.run; });
  for (std::size_t i = 1; i < records.size(); ++i)
    if (records[i].run == records[i - 1].run)
      throw std::runtime_error("run " + std::to_string(records[i].run) + " is recorded twice");
  SweepTables t;
  const SweepColumnIndex column = CollectSweepColumns(records, &t);
  WriteSweepRunsCsv(def, records, column, &t);
  // Statistics per point (per scenario and point) over its completed runs, in seed order.
  const SweepEntryValues values = GatherSweepEntries(def, records, column, &t);
  WriteSweepAggregateCsv(def, values, &t);
  if (def.MultiScenario()) BuildPooled(def, values.metrics, &t);
  return t;
}

std::size_t DefaultMetric(const SweepTables& t) {
  int best = 0;
  std::size_t pick = 0;
  for (std::size_t m = 0; m < t.info.size(); ++m)
    if (t.info[m].headline > 0 && (best == 0 || t.info[m].headline < best)) {
      best = t.info[m].headline;
      pick = m;
    }
  if (best > 0) return pick;
  for (std::size_t m = 0; m < t.metrics.size(); ++m) {
    double lo = kNaN, hi = kNaN;
    for (const auto& point : t.stats) {
      const MetricStats& s = point[m];
      if (s.n == 0) continue;
      for (double v :
           t.stats.size() == 1 ? std::vector<double>{s.min, s.max} : std::vector<double>{s.mean}) {
        if (!(v >= lo)) lo = v;
        if (!(v <= hi)) hi = v;
      }
    }
    if (lo < hi) return m;
  }
  return 0;
}

std::string RankingText(const SweepDefinition& def, const SweepTables& t, int m) {
  // Several scenarios: the points ranked by their statistics over every scenario and seed.
  const bool multi = def.MultiScenario();
  const std::vector<std::size_t>& points = multi ? t.pooled.points : t.points;
  const std::vector<std::size_t>& runs = multi ? t.pooled.runs : t.runs;
  const std::vector<std::size_t>& failed = multi ? t.pooled.failed : t.failed;
  const std::vector<std::vector<MetricStats>>& stats = multi ? t.pooled.stats : t.stats;
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto mean = [&](std::size_t e) { return m >= 0 ? stats[e][m].mean : kNaN; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double x = mean(a), y = mean(b);
    if (std::isnan(x) || std::isnan(y)) return !std::isnan(x) && std::isnan(y);
    return x < y;
  });
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> head = {"rank"};
  for (const SweepAxis& a : def.axes) head.push_back(a.key);
  for (const char* h : {"runs", "failed", "n", "mean", "std", "min", "max"}) head.push_back(h);
  rows.push_back(head);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t e = order[k];
    std::vector<std::string> r = {std::to_string(k + 1)};
    for (std::size_t a = 0; a < def.axes.size(); ++a) r.push_back(def.Value(points[e], a));
    r.push_back(std::to_string(runs[e]));
    r.push_back(std::to_string(failed[e]));
    const MetricStats s = m >= 0 ? stats[e][m] : MetricStats{};
    r.push_back(std::to_string(s.n));
    for (double v : {s.mean, s.std, s.min, s.max}) r.push_back(Short(v));
    rows.push_back(r);
  }
  std::vector<std::size_t> width(head.size(), 0);
  for (const auto& r : rows)
    for (std::size_t c = 0; c < r.size(); ++c) width[c] = std::max(width[c], r[c].size());
  std::string out = "points sorted by the mean of " +
                    (m >= 0 ? t.metrics[m] : std::string("(no metric)")) +
                    (multi ? " over every scenario and seed (" +
                                 std::to_string(def.scenarios.size()) + " scenarios)"
                           : std::string(" over the seeds")) +
                    ", smallest first\n";
  for (const auto& r : rows) {
    std::string line;
    for (std::size_t c = 0; c < r.size(); ++c) {
      if (c) line += "  ";
      line += r[c] + std::string(width[c] - r[c].size(), ' ');
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

std::string MetricAxisLabel(const SweepTables& t, int m) {
  if (m < 0 || m >= static_cast<int>(t.metrics.size())) return "";
  return m < static_cast<int>(t.info.size()) ? t.info[m].AxisLabel(t.metrics[m]) : t.metrics[m];
}

std::vector<std::string> WriteSweepTables(const std::string& dir, const SweepTables& t) {
  WriteFileAtomic((fs::path(dir) / "runs.csv").string(), t.runs_csv);
  WriteFileAtomic((fs::path(dir) / "aggregate.csv").string(), t.aggregate_csv);
  if (t.pooled.csv.empty()) return {"runs.csv", "aggregate.csv"};
  WriteFileAtomic((fs::path(dir) / kPooledCsv).string(), t.pooled.csv);
  return {"runs.csv", "aggregate.csv", kPooledCsv};
}

std::string SimilarMetrics(const std::vector<std::string>& metrics, const std::string& name) {
  const std::string last = name.substr(name.rfind('.') + 1);
  std::string out;
  int shown = 0;
  for (const std::string& m : metrics) {
    const std::string mlast = m.substr(m.rfind('.') + 1);
    if ((mlast == last || m.find(name) != std::string::npos) && shown < 8) {
      out += (out.empty() ? "" : ", ") + m;
      ++shown;
    }
  }
  if (out.empty())
    for (std::size_t i = 0; i < metrics.size() && i < 8; ++i) out += (i ? ", " : "") + metrics[i];
  return out;
}

}  // namespace formsim::sim
