// A paper's reproduction (sim/study/reproduction.hpp) on made-up records: each kind of cell, the
// largest of several metric paths, counts, the check of a definition, --tables, and the bar
// figure's heights and error bars.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "sim/study/reproduction.hpp"

namespace formsim::sim {
namespace {

// One case "c" whose records carry a = 1, 2, 3 ... (one per seed), b = 10 - a, and in run 2
// a failure (left out of every statistic).
ReproResults FakeResults(int runs) {
  ReproResults res;
  res.seeds_text = "1..n";
  ReproCaseRuns& c = res.cases["c"];
  for (int r = 0; r < runs; ++r) {
    SweepRecord rec;
    rec.run = static_cast<std::size_t>(r);
    rec.status = "completed";
    rec.metrics = {{"a", r + 1.0}, {"b", 10.0 - (r + 1.0)}, {"x.k.m", 0.5 * (r + 1.0)}};
    c.records.push_back(rec);
  }
  SweepRecord failed;
  failed.run = static_cast<std::size_t>(runs);
  failed.status = "numerical_fault";
  failed.metrics = {{"a", 1e9}, {"b", 1e9}};
  c.records.push_back(failed);
  return res;
}

ReproColumn Col(const std::string& metric, CellStat stat, double scale = 1.0, int digits = 1) {
  ReproColumn c;
  c.header = metric;
  c.metric = metric;
  c.stat = stat;
  c.scale = scale;
  c.digits = digits;
  return c;
}

ReproTable OneRowTable(std::vector<ReproColumn> cols, const std::string& key = "") {
  ReproTable t;
  t.id = "t";
  t.title = "T";
  t.label_headers = {"row"};
  t.columns = std::move(cols);
  t.rows = {ReproRow{{"r"}, "c", key, {}}};
  return t;
}

std::string Cell(const ReproTable& t, std::size_t col, const ReproResults& res) {
  return ComputeCell(t, t.rows[0], t.columns[col], res).text;
}

TEST(Reproduction, CellsSummariseTheCompletedRunsOverTheSeeds) {
  const ReproResults res = FakeResults(3);  // a = 1, 2, 3 (the failed run's 1e9 left out)
  ReproColumn below = Col("a", CellStat::kBelow);
  below.versus = "b";
  ReproColumn sci = Col("a", CellStat::kMeanStd, 1e-3, 2);
  sci.sci = true;
  const ReproTable t =
      OneRowTable({Col("a", CellStat::kMeanStd), Col("a", CellStat::kMeanStdRange, 10.0),
                   Col("a", CellStat::kMeanRange, 1.0, 2), Col("a", CellStat::kCount), below, sci,
                   Col("nope", CellStat::kMeanStd)});
  EXPECT_EQ(Cell(t, 0, res), "2.0 ± 1.0");
  EXPECT_EQ(Cell(t, 1, res), "20.0 ± 10.0 [10.0–30.0]");
  EXPECT_EQ(Cell(t, 2, res), "2.00 [1.00–3.00]");
  EXPECT_EQ(Cell(t, 3, res), "3/4");  // non-zero in 3 of the 4 runs (one failed)
  EXPECT_EQ(Cell(t, 4, res), "3/4");  // a < b = 9, 8, 7
  EXPECT_EQ(Cell(t, 5, res), "2.0e-3 ± 1.0e-3");
  EXPECT_EQ(Cell(t, 6, res), "–");  // no such metric: a dash, not a zero
  const ReproCell c = ComputeCell(t, t.rows[0], t.columns[1], res);
  EXPECT_EQ(c.values, (std::vector<double>{10.0, 20.0, 30.0}));
  EXPECT_EQ(c.stats.n, 3u);
  EXPECT_DOUBLE_EQ(c.stats.std, 10.0);
  // One seed: no spread to show.
  EXPECT_EQ(Cell(t, 0, FakeResults(1)), "1.0");
}

TEST(Reproduction, KeysAndSeveralPathsPickTheMetricOfEachRun) {
  const ReproResults res = FakeResults(4);  // a = 1..4, b = 9..6
  // "{}" is the row's key; "a,b": the larger of the two in each run (9, 8, 7, 6).
  const ReproTable t = OneRowTable(
      {Col("x.{}.m", CellStat::kMeanRange, 1.0, 2), Col("a,b", CellStat::kMeanRange)}, "k");
  EXPECT_EQ(Cell(t, 0, res), "1.25 [0.50–2.00]");
  EXPECT_EQ(Cell(t, 1, res), "7.5 [6.0–9.0]");
  EXPECT_EQ(MetricValues(res.cases.at("c"), "b,a"), (std::vector<double>{9, 8, 7, 6}));
}

TEST(Reproduction, TablesTextIsMarkdownWithSeedsNoteAndRerunCommand) {
  ReproPaper p;
  p.name = "demo";
  p.cases = {{"c", "formation_traj2", {}}};
  ReproTable t = OneRowTable({Col("a", CellStat::kMeanStd)});
  t.rows.insert(t.rows.begin(), ReproRow{{"paper"}, "", "", {"2.5"}});
  t.note = "A note.";
  p.tables = {t};
  CheckPaper(p);
  const std::string text = ReproTablesText(p, FakeResults(3));
  EXPECT_EQ(text,
            "**T** (seeds 1..n; mean ± std)\n\n| row | a |\n|---|---|\n| paper | 2.5 |\n"
            "| r | 2.0 ± 1.0 |\n\nA note.\n\nRerun: `formsim reproduce demo --seeds 1..n "
            "--tables t`\n\n");
  const std::string csv = ReproCellsCsv(p, FakeResults(3));
  EXPECT_NE(csv.find("t,r,a,c,a,mean_std,3,2,1,1,3,2.0 ± 1.0\n"), std::string::npos) << csv;
}

TEST(Reproduction, DefinitionsAndTableSelectionAreChecked) {
  ReproPaper p;
  p.name = "demo";
  p.cases = {{"c", "formation_traj2", {}}};
  p.tables = {OneRowTable({Col("a", CellStat::kMeanStd)})};
  CheckPaper(p);
  ReproPaper bad = p;
  bad.tables[0].rows[0].case_id = "missing";
  EXPECT_THROW(CheckPaper(bad), std::logic_error);
  bad = p;
  bad.cases.push_back(p.cases[0]);  // a repeated id
  EXPECT_THROW(CheckPaper(bad), std::logic_error);
  bad = p;
  bad.tables[0].columns.push_back(Col("a", CellStat::kBelow));  // no `versus`
  EXPECT_THROW(CheckPaper(bad), std::logic_error);

  EXPECT_EQ(SelectTables(p, "t").tables.size(), 1u);
  try {
    SelectTables(p, "t,u");
    FAIL() << "an unknown table was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "--tables 'u': demo has tables t");
  }
}

TEST(Reproduction, BarFigureHasMeansAndErrorBarsPerCategory) {
  ReproFigure f;
  f.id = "bars";
  f.table = "t";
  f.categories = {{"first", "a"}, {"second", "b"}};
  f.series = {{"s", "c", "{}"}};
  const ReproResults res = FakeResults(3);  // a = 1, 2, 3; b = 9, 8, 7
  FigureSpec spec = ReproBarFigure(f, res);
  EXPECT_EQ(spec.categories, (std::vector<std::string>{"first", "second"}));
  ASSERT_EQ(spec.series.size(), 1u);
  const SeriesSpec& s = spec.series[0];
  EXPECT_TRUE(s.bars);
  EXPECT_EQ(s.x, (std::vector<double>{0, 1}));
  EXPECT_EQ(s.y, (std::vector<double>{2, 8}));
  EXPECT_EQ(s.err_lo, (std::vector<double>{1, 7}));  // mean - sample std
  EXPECT_EQ(s.err_hi, (std::vector<double>{3, 9}));
  f.range = true;
  f.scale = 2.0;
  spec = ReproBarFigure(f, res);
  EXPECT_EQ(spec.series[0].y, (std::vector<double>{4, 16}));
  EXPECT_EQ(spec.series[0].err_lo, (std::vector<double>{2, 14}));  // min-max
  EXPECT_EQ(spec.series[0].err_hi, (std::vector<double>{6, 18}));
}

}  // namespace
}  // namespace formsim::sim
