#pragma once
/// \file A paper's reproduction (`formsim reproduce`): its cases (a scenario with overrides),
/// each run over the seeds through the sweep engine (one sweep without varied keys per case,
/// written under OUT/<case> as `formsim sweep` writes it), and its tables and bar charts, every
/// number read from the runs' metrics (Metrics::Scalars paths) and summarised over the seeds.
/// A paper is data (sim/<kind>/<kind>_paper.cpp, registered in reproduction_registry.hpp); this
/// file runs and formats any of them.
///
/// Cells show the mean over the completed runs with the sample standard deviation and/or the
/// range of the per-seed values ("8.6 ± 2.8", "17.8 ± 2.3 [13.0–22.1]", "1.7 [1.2–2.3]"), a count
/// of runs ("9/10"), or a text (the paper's own figures). Tables are printed as Markdown, so the
/// docs/papers/ pages hold exactly what the command prints.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sim/core/figure_spec.hpp"
#include "sim/study/sweep_spec.hpp"
#include "sim/study/sweep_store.hpp"
#include "sim/study/sweep_tables.hpp"
#include "sim/core/task_pool.hpp"

namespace formsim::sim {

/// One case: a shipped scenario (or a path) with overrides, run for every seed.
struct ReproCase {
  std::string id;                 ///< unique in its paper; the folder OUT/<id>
  std::string scenario;           ///< shipped scenario name or YAML path
  std::vector<std::string> sets;  ///< "key=value" overrides, as --set
};

/// How a cell summarises the per-seed values of its metric.
enum class CellStat {
  kMeanStd,       ///< "8.6 ± 2.8"
  kMeanStdRange,  ///< "17.8 ± 2.3 [13.0–22.1]"
  kMeanRange,     ///< "1.7 [1.2–2.3]"
  kCount,         ///< completed runs whose value is not zero (a flag): "9/10"
  kBelow,         ///< completed runs whose value is below `versus`'s in the same run: "8/10"
  kText,          ///< the row's text for this column (e.g. what the paper reports)
};

/// A column of a table.
struct ReproColumn {
  std::string header;
  /// The metric: a dotted path of Metrics::Scalars; "{}" is replaced by the row's key. Several
  /// paths separated by commas: the largest of them in each run (e.g. the worst link).
  std::string metric;
  CellStat stat = CellStat::kMeanStd;
  double scale = 1.0;  ///< applied to every value (m -> mm: 1000)
  int digits = 1;      ///< decimals, or significant digits when `sci`
  bool sci = false;    ///< numbers as 7.2e-2 (mean and spread with digits significant digits)
  std::string versus;  ///< kBelow: the metric compared with ("{}" replaced as in `metric`)
  /// The case of this column's cells, "{}" replaced by the row's key (e.g. "wet_{}" for a row
  /// per speed); empty: the row's case.
  std::string case_id;
};

/// A row: labels, and the case whose runs fill its cells (or texts only: the paper's figures).
struct ReproRow {
  std::vector<std::string> labels;  ///< one per label column of the table
  std::string case_id;              ///< the cells' case (unless a column names its own)
  std::string key;                  ///< replaces "{}" in the columns' metrics and cases
  /// The kText cells in column order; a row of texts only (no case, and no column naming
  /// one): one text per column.
  std::vector<std::string> texts;
  bool text_only() const { return case_id.empty() && key.empty(); }
};

/// A table as printed (Markdown) with its title.
struct ReproTable {
  std::string id;     ///< selects it: --tables ID
  std::string title;  ///< printed above it, followed by the seeds and how cells read
  std::vector<std::string> label_headers;
  std::vector<ReproColumn> columns;
  std::vector<ReproRow> rows;
  std::string note;  ///< printed below it (conditions, what a row means); may be empty
};

/// A bar chart over the seeds: for each category, one bar per series at the mean of its metric
/// with an error bar of ± one standard deviation (or the min-max range).
struct ReproFigure {
  std::string id;     ///< file stem under OUT
  std::string table;  ///< written when this table is selected
  std::string title, y_label;
  std::vector<std::pair<std::string, std::string>> categories;  ///< label, key ("{}" in metrics)
  struct Series {
    std::string label;
    std::string case_id;  ///< "{}" replaced by the category's key (a case per category)
    std::string metric;   ///< "{}" replaced by the category's key
  };
  std::vector<Series> series;
  double scale = 1.0;
  bool range = false;  ///< error bars min-max instead of ± std
};

/// One paper: its cases, tables and figures.
struct ReproPaper {
  std::string name;   ///< "agv": `formsim reproduce agv`
  std::string title;  ///< "Omnidirectional Mecanum AGV (paper 002)"
  int number = 0;     ///< the paper's number (2 for paper 002): papers are listed in this order
  std::vector<ReproCase> cases;
  std::vector<ReproTable> tables;
  std::vector<ReproFigure> figures;
  const ReproCase* Case(const std::string& id) const;
};

/// Checks a definition: unique case and table ids, rows naming existing cases, one label per
/// label column and one text per text column. Throws std::logic_error saying what is wrong.
void CheckPaper(const ReproPaper& paper);

/// The paper with only the tables `ids` (comma-separated; empty: all), the figures drawn from
/// them and the cases they use. Throws std::runtime_error naming --tables and the table ids.
ReproPaper SelectTables(const ReproPaper& paper, const std::string& ids);

/// The runs of one case.
struct ReproCaseRuns {
  SweepDefinition def;
  std::vector<SweepRecord> records;  ///< sorted by run (= by seed)
  SweepTables tables;
};

/// Everything a reproduction ran, by case id.
struct ReproResults {
  std::vector<std::uint64_t> seeds;
  std::string seeds_text;  ///< as given ("1..10")
  std::map<std::string, ReproCaseRuns> cases;
  std::size_t failed = 0;  ///< runs that did not complete (fault or error)
};

/// Where a reproduction stands: runs done (and failed) of all.
using ReproProgress = std::function<void(std::size_t done, std::size_t failed, std::size_t total)>;

/// Runs every case of `paper` for every seed on `pool` (`sets` are added to every case's
/// overrides, after its own). Each case is a sweep in `out`/<case id>: its manifest, one record
/// per run and its runs.csv and aggregate.csv (a previous reproduction's records there are
/// replaced). Results never depend on the number of threads. Returns with the runs finished so
/// far when `stop()` turns true.
ReproResults RunPaper(const ReproPaper& paper, const std::vector<std::uint64_t>& seeds,
                      const std::string& seeds_text, const std::vector<std::string>& sets,
                      const std::string& out, TaskPool& pool, const ReproProgress& progress = {},
                      const std::function<bool()>& stop = {});

/// One cell computed: the per-seed values it summarises and its text.
struct ReproCell {
  std::string text;            ///< as printed
  std::string case_id;         ///< empty for rows without a case
  std::string metric;          ///< with the row's key substituted
  std::vector<double> values;  ///< per completed run, scaled (kBelow: 1 or 0 per run)
  MetricStats stats;           ///< of `values`
};

/// The cell of `row` and `column` of `table`.
ReproCell ComputeCell(const ReproTable& table, const ReproRow& row, const ReproColumn& column,
                      const ReproResults& results);

/// The tables as Markdown: for each, its title with the seeds, the table, its note, and the
/// command that reruns it.
std::string ReproTablesText(const ReproPaper& paper, const ReproResults& results);

/// Every numeric cell with its source, for checks: table, row (its labels joined by " / "),
/// column, case, metric, stat, n, mean, std, min, max (scaled), as CSV.
std::string ReproCellsCsv(const ReproPaper& paper, const ReproResults& results);

/// The figure as a bar chart spec (categories on x, one bar series per series).
FigureSpec ReproBarFigure(const ReproFigure& figure, const ReproResults& results);

/// The per-seed values of `metric` in the completed runs of `runs` (comma-separated paths: the
/// largest in each run), scaled; runs without the metric are left out.
std::vector<double> MetricValues(const ReproCaseRuns& runs, const std::string& metric,
                                 double scale = 1.0);

}  // namespace formsim::sim
