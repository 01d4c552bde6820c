#include "sim/study/reproduction.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>
#include <set>
#include <stdexcept>

#include "control/common/float_limits.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/study/sweep.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {
namespace {

using control::kNaN;
const char* const kDash = "–";

std::string Substitute(const std::string& pattern, const std::string& key) {
  std::string out = pattern;
  for (std::size_t at = out.find("{}"); at != std::string::npos;
       at = out.find("{}", at + key.size()))
    out.replace(at, 2, key);
  return out;
}

// The value of `metric` (one path, or the largest of comma-separated paths) in one record, or
// NaN when the record has none of them.
double RecordValue(const SweepRecord& rec, const std::vector<std::string>& paths) {
  double best = kNaN;
  for (const std::string& p : paths)
    for (const auto& [name, v] : rec.metrics)
      if (name == p && std::isfinite(v) && !(v <= best)) best = v;
  return best;
}

std::string Number(double v, const ReproColumn& c) {
  return c.sci ? FormatScientific(v, c.digits) : FormatFixed(v, c.digits);
}

std::string RowName(const ReproRow& row) {
  std::string s;
  for (const std::string& l : row.labels) s += (s.empty() ? "" : " / ") + l;
  return s;
}

// The case of a cell: the column's (with the row's key) or the row's.
std::string CellCase(const ReproRow& row, const ReproColumn& col) {
  return col.case_id.empty() ? row.case_id : Substitute(col.case_id, row.key);
}

const char* StatName(CellStat s) {
  switch (s) {
    case CellStat::kMeanStd:
      return "mean_std";
    case CellStat::kMeanStdRange:
      return "mean_std_range";
    case CellStat::kMeanRange:
      return "mean_range";
    case CellStat::kCount:
      return "count";
    case CellStat::kBelow:
      return "below";
    case CellStat::kText:
      return "text";
  }
  return "?";
}

// What the cells of a table mean, for its title line.
std::string CellLegend(const ReproTable& t) {
  std::set<CellStat> used;
  for (const ReproColumn& c : t.columns) used.insert(c.stat);
  std::vector<std::string> parts;
  if (used.count(CellStat::kMeanStdRange))
    parts.push_back("mean ± std [min–max]");
  else if (used.count(CellStat::kMeanStd) && used.count(CellStat::kMeanRange))
    parts.push_back("mean ± std or mean [min–max]");
  else if (used.count(CellStat::kMeanStd))
    parts.push_back("mean ± std");
  else if (used.count(CellStat::kMeanRange))
    parts.push_back("mean [min–max]");
  if (used.count(CellStat::kCount) || used.count(CellStat::kBelow)) parts.push_back("k/n: runs");
  std::string s;
  for (const std::string& p : parts) s += (s.empty() ? "" : "; ") + p;
  return s;
}

}  // namespace

const ReproCase* ReproPaper::Case(const std::string& id) const {
  for (const ReproCase& c : cases)
    if (c.id == id) return &c;
  return nullptr;
}

void CheckPaper(const ReproPaper& p) {
  auto fail = [&](const std::string& what) {
    throw std::logic_error("reproduce " + p.name + ": " + what);
  };
  std::set<std::string> ids;
  for (const ReproCase& c : p.cases)
    if (c.id.empty() || !ids.insert(c.id).second) fail("case id '" + c.id + "' empty or repeated");
  std::set<std::string> tables;
  for (const ReproTable& t : p.tables) {
    if (t.id.empty() || !tables.insert(t.id).second)
      fail("table id '" + t.id + "' empty or repeated");
    const long texts = std::count_if(t.columns.begin(), t.columns.end(), [](const ReproColumn& c) {
      return c.stat == CellStat::kText;
    });
    for (const ReproColumn& c : t.columns)
      if ((c.stat == CellStat::kText) != c.metric.empty() ||
          (c.stat == CellStat::kBelow) == c.versus.empty())
        fail("table " + t.id + ", column '" + c.header + "': metric/versus do not fit its stat");
    for (const ReproRow& r : t.rows) {
      const std::string where = "table " + t.id + ", row '" + RowName(r) + "': ";
      if (r.labels.size() != t.label_headers.size()) fail(where + "label count");
      if (r.text_only()) {
        if (r.texts.size() != t.columns.size()) fail(where + "one text per column");
        continue;
      }
      if (static_cast<long>(r.texts.size()) != texts) fail(where + "text count");
      for (const ReproColumn& c : t.columns) {
        if (c.stat == CellStat::kText) continue;
        const std::string id = CellCase(r, c);
        if (!p.Case(id)) fail(where + "column '" + c.header + "': no case '" + id + "'");
      }
    }
  }
  for (const ReproFigure& f : p.figures) {
    if (!tables.count(f.table)) fail("figure " + f.id + ": no table '" + f.table + "'");
    for (const auto& s : f.series)
      for (const auto& c : f.categories)
        if (!p.Case(Substitute(s.case_id, c.second)))
          fail("figure " + f.id + ": no case '" + Substitute(s.case_id, c.second) + "'");
  }
}

ReproPaper SelectTables(const ReproPaper& paper, const std::string& ids) {
  if (ids.empty()) return paper;
  ReproPaper out = paper;
  out.tables.clear();
  out.figures.clear();
  out.cases.clear();
  std::string known;
  for (const ReproTable& t : paper.tables) known += (known.empty() ? "" : ", ") + t.id;
  std::set<std::string> want;
  for (const std::string& id : SplitAt(ids, ',')) {
    if (std::none_of(paper.tables.begin(), paper.tables.end(),
                     [&](const ReproTable& t) { return t.id == id; }))
      throw std::runtime_error("--tables '" + id + "': " + paper.name + " has tables " + known);
    want.insert(id);
  }
  std::set<std::string> cases;
  for (const ReproTable& t : paper.tables)
    if (want.count(t.id)) {
      out.tables.push_back(t);
      for (const ReproRow& r : t.rows)
        for (const ReproColumn& c : t.columns)
          if (!r.text_only() && c.stat != CellStat::kText) cases.insert(CellCase(r, c));
    }
  for (const ReproFigure& f : paper.figures)
    if (want.count(f.table)) {
      out.figures.push_back(f);
      for (const auto& s : f.series)
        for (const auto& c : f.categories) cases.insert(Substitute(s.case_id, c.second));
    }
  for (const ReproCase& c : paper.cases)
    if (cases.count(c.id)) out.cases.push_back(c);
  return out;
}

ReproResults RunPaper(const ReproPaper& paper, const std::vector<std::uint64_t>& seeds,
                      const std::string& seeds_text, const std::vector<std::string>& sets,
                      const std::string& out, TaskPool& pool, const ReproProgress& progress,
                      const std::function<bool()>& stop) {
  ReproResults res;
  res.seeds = seeds;
  res.seeds_text = seeds_text;
  // Each case is a sweep of its scenario without varied keys; its own overrides, then `sets`.
  std::vector<ScenarioSource> sources;
  std::vector<ReproCaseRuns*> cases;
  std::vector<std::string> dirs;
  for (const ReproCase& c : paper.cases) {
    sources.push_back(ScenarioSource::FromFile(ResolveScenario(c.scenario)));
    std::vector<std::string> all = c.sets;
    all.insert(all.end(), sets.begin(), sets.end());
    ReproCaseRuns& runs = res.cases[c.id];
    runs.def = DefineSweep(sources.back(), CliOverrides(all, -1), {}, seeds);
    cases.push_back(&runs);
    dirs.push_back((fs::path(out) / c.id).string());
  }
  // A previous reproduction's records in these folders are replaced, never mixed in.
  for (std::size_t i = 0; i < cases.size(); ++i) {
    std::error_code ec;
    fs::remove_all(fs::path(dirs[i]) / "runs", ec);
    fs::remove(ManifestPath(dirs[i]), ec);
    WriteManifest(dirs[i], cases[i]->def);
  }
  // One list of (case, run) for the pool, so that every core stays busy to the end.
  std::vector<std::pair<std::size_t, std::size_t>> jobs;
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (std::size_t r = 0; r < cases[i]->def.runs(); ++r) jobs.emplace_back(i, r);
  std::mutex mu;
  std::size_t done = 0;
  pool.ForEach(
      jobs.size(),
      [&](std::size_t j) {
        const auto [i, r] = jobs[j];
        ReproCaseRuns& runs = *cases[i];
        const std::optional<SweepRecord> rec = RunSweepRun(sources[i], runs.def, r, stop);
        if (!rec) return;
        WriteRecord(dirs[i], runs.def, *rec);
        std::lock_guard<std::mutex> lock(mu);
        runs.records.push_back(*rec);
        ++done;
        if (rec->failed()) ++res.failed;
        if (progress) progress(done, res.failed, jobs.size());
      },
      stop);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    ReproCaseRuns& runs = *cases[i];
    std::sort(runs.records.begin(), runs.records.end(),
              [](const SweepRecord& a, const SweepRecord& b) { return a.run < b.run; });
    runs.tables = BuildSweepTables(runs.def, runs.records);
    WriteSweepTables(dirs[i], runs.tables);
    SyncFileSystem(dirs[i]);
  }
  return res;
}

std::vector<double> MetricValues(const ReproCaseRuns& runs, const std::string& metric,
                                 double scale) {
  const std::vector<std::string> paths = SplitAt(metric, ',');
  std::vector<double> out;
  for (const SweepRecord& r : runs.records) {
    if (r.failed()) continue;
    const double v = RecordValue(r, paths);
    if (!std::isnan(v)) out.push_back(v * scale);
  }
  return out;
}

ReproCell ComputeCell(const ReproTable& table, const ReproRow& row, const ReproColumn& col,
                      const ReproResults& results) {
  ReproCell cell;
  cell.stats = StatsOf({});
  if (row.text_only() || col.stat == CellStat::kText) {
    long k = 0;
    for (const ReproColumn& c : table.columns) {
      if (&c == &col) break;
      k += row.text_only() || c.stat == CellStat::kText;
    }
    cell.text = row.texts.at(static_cast<std::size_t>(k));
    return cell;
  }
  cell.text = kDash;
  cell.case_id = CellCase(row, col);
  const auto it = results.cases.find(cell.case_id);
  if (it == results.cases.end()) return cell;
  const ReproCaseRuns& runs = it->second;
  cell.metric = Substitute(col.metric, row.key);
  const std::size_t total = runs.records.size();
  if (col.stat == CellStat::kBelow) {
    const std::vector<std::string> a = SplitAt(cell.metric, ','),
                                   b = SplitAt(Substitute(col.versus, row.key), ',');
    cell.metric += " < " + Substitute(col.versus, row.key);
    for (const SweepRecord& r : runs.records) {
      if (r.failed()) continue;
      const double x = RecordValue(r, a), y = RecordValue(r, b);
      if (!std::isnan(x) && !std::isnan(y)) cell.values.push_back(x < y ? 1.0 : 0.0);
    }
  } else {
    cell.values = MetricValues(runs, cell.metric, col.scale);
  }
  cell.stats = StatsOf(cell.values);
  if (cell.values.empty()) return cell;
  const MetricStats& s = cell.stats;
  auto spread = [&] { return std::isnan(s.std) ? std::string() : " ± " + Number(s.std, col); };
  auto range = [&] { return " [" + Number(s.min, col) + kDash + Number(s.max, col) + "]"; };
  switch (col.stat) {
    case CellStat::kMeanStd:
      cell.text = Number(s.mean, col) + spread();
      break;
    case CellStat::kMeanStdRange:
      cell.text = Number(s.mean, col) + spread() + range();
      break;
    case CellStat::kMeanRange:
      cell.text = Number(s.mean, col) + range();
      break;
    case CellStat::kCount:
    case CellStat::kBelow: {
      long k = 0;
      for (double v : cell.values) k += v != 0.0;
      cell.text = std::to_string(k) + "/" + std::to_string(total);
      break;
    }
    case CellStat::kText:
      break;
  }
  return cell;
}

std::string ReproTablesText(const ReproPaper& paper, const ReproResults& results) {
  std::string out;
  for (const ReproTable& t : paper.tables) {
    out += "**" + t.title + "** (seeds " + results.seeds_text + "; " + CellLegend(t) + ")\n\n";
    std::string head = "|", rule = "|";
    for (const std::string& h : t.label_headers) head += " " + h + " |", rule += "---|";
    for (const ReproColumn& c : t.columns) head += " " + c.header + " |", rule += "---|";
    out += head + "\n" + rule + "\n";
    for (const ReproRow& r : t.rows) {
      std::string line = "|";
      for (const std::string& l : r.labels) line += " " + l + " |";
      for (const ReproColumn& c : t.columns)
        line += " " + ComputeCell(t, r, c, results).text + " |";
      out += line + "\n";
    }
    out += "\n";
    if (!t.note.empty()) out += t.note + "\n\n";
    out += "Rerun: `formsim reproduce " + paper.name + " --seeds " + results.seeds_text +
           " --tables " + t.id + "`\n\n";
  }
  return out;
}

std::string ReproCellsCsv(const ReproPaper& paper, const ReproResults& results) {
  std::string out = "table,row,column,case,metric,stat,n,mean,std,min,max,text\n";
  for (const ReproTable& t : paper.tables)
    for (const ReproRow& r : t.rows)
      for (const ReproColumn& c : t.columns) {
        if (c.stat == CellStat::kText || r.text_only()) continue;
        const ReproCell cell = ComputeCell(t, r, c, results);
        out += CsvField(t.id) + "," + CsvField(RowName(r)) + "," + CsvField(c.header) + "," +
               CsvField(cell.case_id) + "," + CsvField(cell.metric) + "," + StatName(c.stat) + "," +
               std::to_string(cell.stats.n);
        for (double v : {cell.stats.mean, cell.stats.std, cell.stats.min, cell.stats.max}) {
          out += ",";
          if (!std::isnan(v)) AppendDouble(out, v);
        }
        out += "," + CsvField(cell.text) + "\n";
      }
  return out;
}

FigureSpec ReproBarFigure(const ReproFigure& f, const ReproResults& results) {
  std::vector<std::string> labels;
  for (const auto& c : f.categories) labels.push_back(c.first);
  std::vector<SeriesSpec> series;
  for (std::size_t k = 0; k < f.series.size(); ++k) {
    const ReproFigure::Series& s = f.series[k];
    std::vector<double> mid, lo, hi;
    for (const auto& c : f.categories) {
      const auto it = results.cases.find(Substitute(s.case_id, c.second));
      const MetricStats st =
          StatsOf(it == results.cases.end()
                      ? std::vector<double>{}
                      : MetricValues(it->second, Substitute(s.metric, c.second), f.scale));
      const double d = std::isnan(st.std) ? 0.0 : st.std;
      mid.push_back(st.mean);
      lo.push_back(f.range ? st.min : st.mean - d);
      hi.push_back(f.range ? st.max : st.mean + d);
    }
    series.push_back(Bars(s.label, mid, lo, hi, static_cast<int>(k)));
  }
  return BarFigure(f.id, f.title + " (seeds " + results.seeds_text + ")", f.y_label, labels,
                   std::move(series));
}

}  // namespace formsim::sim
