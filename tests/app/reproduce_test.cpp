// formsim reproduce end to end (the built binary, few seeds, shortened runs): what it prints is
// tables.md, every number of it is the statistics of the sweep tables it wrote for the same
// runs; bad --seeds, paper and --tables name the flag; the bar chart on pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "app/export/figure_data.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/recorder.hpp"
#include "sim/study/reproduction.hpp"
#include "sim/study/reproduction_registry.hpp"
#include "sim/study/sweep_tables.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;
using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

// stdout into `dir`.md, stderr into `dir`.log.
int Reproduce(const std::string& args, const std::string& dir) {
  const int status =
      std::system((Binary() + " reproduce " + args + " >" + dir + ".md 2>" + dir + ".log").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}

// CSV fields, with "..." quoting (labels may hold commas).
std::vector<std::string> CsvFields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"')
        out.back() += '"', ++i;
      else
        quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

double Num(const std::string& s) {
  double v = NAN;
  sim::ParseFiniteDouble(s, &v);
  return v;
}

// A CSV file as rows of header -> field.
std::vector<std::map<std::string, std::string>> ReadCsv(const std::string& path) {
  const std::vector<std::string> lines = Lines(ReadText(path));
  std::vector<std::map<std::string, std::string>> rows;
  if (lines.empty()) return rows;
  const std::vector<std::string> head = CsvFields(lines[0]);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> f = CsvFields(lines[i]);
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < head.size() && c < f.size(); ++c) row[head[c]] = f[c];
    rows.push_back(row);
  }
  return rows;
}

void ExpectClose(double got, double want, const std::string& what) {
  EXPECT_NEAR(got, want, 1e-12 * std::max(1.0, std::abs(want))) << what;
}

// Shortened formation cases (2 s, seeds 1-3) and AGV's localisation table (20 s, seeds 1-2):
// every numeric cell is recomputed from the case's runs.csv (the largest of several metric
// paths in each run, scaled) and, for one path, equals aggregate.csv's statistics; every cell's
// text is in the printed row; stdout is tables.md.
TEST(ReproduceCli, TablesAreTheSweepTablesStatistics) {
  struct Check {
    std::string paper, args;
    std::size_t seeds;
  };
  for (const Check& k : {Check{"formation", "--seeds 1..3 --set duration=2", 3},
                         Check{"agv", "--seeds 1..2 --tables localisation --set duration=20", 2}}) {
    SCOPED_TRACE(k.paper);
    const std::string d = TempDir("reproduce_" + k.paper);
    ASSERT_EQ(Reproduce(k.paper + " " + k.args + " -q -j2 --out " + d, d), 0)
        << ReadText(d + ".log");
    const std::string printed = ReadText(d + ".md");
    EXPECT_EQ(printed, ReadText(d + "/tables.md"));
    EXPECT_NE(printed.find("(seeds " + k.args.substr(8, 4)), std::string::npos) << printed;
    const std::vector<std::string> md = Lines(printed);

    const auto cells = ReadCsv(d + "/cells.csv");
    ASSERT_FALSE(cells.empty());
    int numeric = 0;
    for (const auto& cell : cells) {
      const std::string what =
          cell.at("table") + " / " + cell.at("row") + " / " + cell.at("column");
      // The printed row (its labels, then the cells) holds the cell's text.
      std::string row_start = "|";
      for (std::size_t at = 0, next;; at = next + 3) {
        next = cell.at("row").find(" / ", at);
        row_start +=
            " " + cell.at("row").substr(at, next == std::string::npos ? next : next - at) + " |";
        if (next == std::string::npos) break;
      }
      bool found = false;
      for (const std::string& l : md)
        if (l.rfind(row_start, 0) == 0 &&
            l.find("| " + cell.at("text") + " |") != std::string::npos)
          found = true;
      EXPECT_TRUE(found) << what << ": '" << cell.at("text") << "' not printed in its row";
      if (cell.at("stat") == "count" || cell.at("stat") == "below" || cell.at("n") == "0") continue;

      // The column's scale, from the paper's definition.
      const sim::ReproPaper& paper = sim::FindReproPaper(k.paper);
      double scale = NAN;
      for (const sim::ReproTable& t : paper.tables)
        if (t.id == cell.at("table"))
          for (const sim::ReproColumn& c : t.columns)
            if (c.header == cell.at("column")) scale = c.scale;
      ASSERT_TRUE(std::isfinite(scale)) << what;

      // Per run: the largest of the metric's paths in runs.csv.
      const std::string dir = d + "/" + cell.at("case");
      std::vector<std::string> paths;
      for (std::size_t at = 0, next;; at = next + 1) {
        next = cell.at("metric").find(',', at);
        paths.push_back(cell.at("metric").substr(at, next == std::string::npos ? next : next - at));
        if (next == std::string::npos) break;
      }
      std::vector<double> values;
      for (const auto& run : ReadCsv(dir + "/runs.csv")) {
        double v = NAN;
        for (const std::string& p : paths) {
          ASSERT_TRUE(run.count(p)) << what << ": no column " << p << " in runs.csv";
          const double x = Num(run.at(p));
          if (std::isfinite(x) && !(x <= v)) v = x;
        }
        if (std::isfinite(v)) values.push_back(v * scale);
      }
      ASSERT_EQ(values.size(), k.seeds) << what;
      const sim::MetricStats s = sim::StatsOf(values);
      EXPECT_EQ(cell.at("n"), std::to_string(k.seeds)) << what;
      ExpectClose(Num(cell.at("mean")), s.mean, what + " mean");
      ExpectClose(Num(cell.at("std")), s.std, what + " std");
      ExpectClose(Num(cell.at("min")), s.min, what + " min");
      ExpectClose(Num(cell.at("max")), s.max, what + " max");
      if (paths.size() == 1) {
        const auto agg = ReadCsv(dir + "/aggregate.csv");
        ASSERT_EQ(agg.size(), 1u) << what;
        for (const char* stat : {"mean", "std", "min", "max"})
          ExpectClose(Num(cell.at(stat)), scale * Num(agg[0].at(paths[0] + "." + stat)),
                      what + " vs aggregate.csv " + stat);
      }
      ++numeric;
    }
    EXPECT_GT(numeric, k.paper == "formation" ? 60 : 12);
  }
}

// The velocity bar chart is written (PNG, SVG and PDF) from the shortened Fig. 6 cases.
TEST(ReproduceCli, VelocityWritesItsBarChart) {
  const std::string d = TempDir("reproduce_velocity");
  ASSERT_EQ(Reproduce("velocity --seeds 1..2 --tables fig6 --set duration=3 -q -j2 --out " + d, d),
            0)
      << ReadText(d + ".log");
  EXPECT_GT(fs::file_size(d + "/fig6_speed_rmse.png"), 10000u);
  EXPECT_GT(fs::file_size(d + "/fig6_speed_rmse.svg"), 1000u);
  EXPECT_GT(fs::file_size(d + "/fig6_speed_rmse.pdf"), 1000u);
  const std::string printed = ReadText(d + ".md");
  EXPECT_NE(printed.find("| the paper's: one inverse depth along the anchor's bearing | R_fused"),
            std::string::npos)
      << printed;
  EXPECT_NE(printed.find("/2 |"), std::string::npos) << "fused < odometry counted over 2 runs";
}

// Every paper declares figures, each drawn from its own tables' cases.
TEST(ReproduceFigures, EveryPaperHasFigures) {
  for (const char* name : {"formation", "agv", "inspection", "velocity"}) {
    const sim::ReproPaper& paper = sim::FindReproPaper(name);
    EXPECT_FALSE(paper.figures.empty()) << name;
    sim::CheckPaper(paper);  // every series' case exists for every category
  }
}

// `reproduce formation --out` writes its figures as PNG, SVG (valid XML) and PDF (fonts
// embedded), beside tables.md and cells.csv; --tables selects the figures of its tables only.
TEST(ReproduceCli, FormationWritesItsFiguresInThreeFormats) {
  const std::string d = TempDir("reproduce_formation_figures");
  ASSERT_EQ(Reproduce("formation --seeds 1..2 --set duration=2 -q -j2 --out " + d, d), 0)
      << ReadText(d + ".log");
  for (const std::string stem : {"errors_phi12_printed", "errors_phi12_per_sample"}) {
    EXPECT_GT(fs::file_size(d + "/" + stem + ".png"), 5000u) << stem;
    EXPECT_GT(fs::file_size(d + "/" + stem + ".svg"), 1000u) << stem;
    EXPECT_GT(fs::file_size(d + "/" + stem + ".pdf"), 1000u) << stem;
    if (std::system("command -v xmllint >/dev/null 2>&1") == 0)
      EXPECT_EQ(RunShell("xmllint --noout " + d + "/" + stem + ".svg", d + ".xmllint"), 0)
          << ReadText(d + ".xmllint");
    else
      std::fprintf(stderr, "xmllint missing (libxml2-utils): SVG not validated\n");
    if (std::system("command -v pdffonts >/dev/null 2>&1") == 0) {
      EXPECT_EQ(RunShell("pdfinfo " + d + "/" + stem + ".pdf", d + ".pdfinfo"), 0)
          << ReadText(d + ".pdfinfo");
      const std::string info = ReadText(d + ".pdfinfo");
      const std::size_t pages = info.find("Pages:");
      ASSERT_NE(pages, std::string::npos) << info;
      std::stringstream count(info.substr(pages + 6));
      int n = 0;
      count >> n;
      EXPECT_EQ(n, 1) << info;
      ASSERT_EQ(RunShell("pdffonts " + d + "/" + stem + ".pdf", d + ".pdffonts"), 0);
      // Header, rule, then one line per font; its "emb" column says yes for each.
      const std::vector<std::string> fonts = Lines(ReadText(d + ".pdffonts"));
      ASSERT_GT(fonts.size(), 2u) << "the figure has text";
      for (std::size_t i = 2; i < fonts.size(); ++i) {
        std::stringstream ss(fonts[i].substr(fonts[0].find("emb")));
        std::string emb;
        ss >> emb;
        EXPECT_EQ(emb, "yes") << fonts[i];
      }
    } else {
      std::fprintf(stderr, "pdffonts missing (poppler-utils): PDF not checked\n");
    }
  }
  const std::string inspection = TempDir("reproduce_inspection_figures");
  ASSERT_EQ(Reproduce("inspection --seeds 1 --tables localisation --set duration=20 -q -j2 --out " +
                          inspection,
                      inspection),
            0)
      << ReadText(inspection + ".log");
  EXPECT_TRUE(fs::exists(inspection + "/localisation_error.png"));
  EXPECT_FALSE(fs::exists(inspection + "/tracking_lateral.png")) << "not a selected table's";
}

TEST(ReproduceCli, BadInputNamesTheFlag) {
  const std::string d = TempDir("reproduce_bad");
  struct Bad {
    std::string args, message;
  };
  for (const Bad& b :
       {Bad{"formation --seeds 5..1", "--seeds '5..1'"}, Bad{"formation --seeds 1,x", "--seeds"},
        Bad{"formation --seeds 1,1", "--seeds"}, Bad{"formation --seeds ''", "--seeds"},
        Bad{"nope", "no paper 'nope' (papers: formation, agv, inspection, velocity)"},
        Bad{"agv --tables nope", "--tables 'nope': agv has tables localisation, outliers"},
        Bad{"formation --jobs -1", "--jobs"}}) {
    EXPECT_EQ(Reproduce(b.args + " --out " + d + "/out", d), 2) << b.args;
    const std::string err = ReadText(d + ".log");
    EXPECT_NE(err.find(b.message), std::string::npos) << b.args << ": " << err;
    EXPECT_TRUE(ReadText(d + ".md").empty()) << b.args;
    EXPECT_FALSE(fs::exists(d + "/out"))
        << b.args << ": nothing is written before the input is checked";
  }
}

// --- the bar chart on pixels ---------------------------------------------------------------

using testing::At;
using testing::Distance;
using testing::Rgb;

// Two series over three categories: each bar stands on zero in its half of the category's 80%
// (series 0 left of the category's x, series 1 right), filled in its colour up to its mean; the
// error bar is drawn at the bar's centre from mean - std to mean + std, with nothing above it.
TEST(ReproduceFigure, BarsStandSideBySideWithTheirErrorBars) {
  const std::vector<double> m0 = {1.0, 2.0, 3.0}, m1 = {2.5, 0.5, 1.5}, e = {0.4, 0.6, 0.2};
  auto lo = [&](const std::vector<double>& m) {
    std::vector<double> v;
    for (std::size_t i = 0; i < m.size(); ++i) v.push_back(m[i] - e[i]);
    return v;
  };
  auto hi = [&](const std::vector<double>& m) {
    std::vector<double> v;
    for (std::size_t i = 0; i < m.size(); ++i) v.push_back(m[i] + e[i]);
    return v;
  };
  const sim::FigureSpec spec = sim::BarFigure(
      "bars", "Bars", "value", {"a", "b", "c"},
      {sim::Bars("s0", m0, lo(m0), hi(m0), 0), sim::Bars("s1", m1, lo(m1), hi(m1), 1)});
  const PlotData data = ResolveFigure(spec, sim::Recorder());
  EXPECT_EQ(data.x_tick_labels, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_FALSE(data.x_is_time);
  const int w = 900, h = 560;
  OffscreenRenderer r(w, h);
  const auto& px = r.RenderFigure(data, w, h);
  const PlotLayout& L = r.last_plot_layout();
  // One error bar reaches below zero (0.5 - 0.6): the axis goes down to show it.
  EXPECT_LT(L.y0, -0.1);
  EXPECT_GE(L.y1, 3.2);
  EXPECT_LE(L.x0, -0.4);
  EXPECT_GE(L.x1, 2.4);
  auto sx = [&](double x) {
    return static_cast<float>(L.area_min.x +
                              (x - L.x0) / (L.x1 - L.x0) * (L.area_max.x - L.area_min.x));
  };
  auto sy = [&](double y) {
    return static_cast<float>(L.area_max.y -
                              (y - L.y0) / (L.y1 - L.y0) * (L.area_max.y - L.area_min.y));
  };
  const sim::Color bg = r.theme().background;
  auto faded = [&](int k) {  // the series colour at 75% over the background
    const sim::Color c = sim::PaletteColor(k);
    return sim::Color{0.75f * c.r + 0.25f * bg.r, 0.75f * c.g + 0.25f * bg.g,
                      0.75f * c.b + 0.25f * bg.b, 1};
  };
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 2; ++j) {
      const double mean = (j == 0 ? m0 : m1)[static_cast<std::size_t>(k)];
      const double err = e[static_cast<std::size_t>(k)];
      // The slot's centre: 0.8 of the category split in two, centres at ∓0.2.
      const double xc = k + (j == 0 ? -0.2 : 0.2);
      const std::string where = "category " + std::to_string(k) + ", series " + std::to_string(j);
      // Inside the bar, off its centre line and the error bar's caps (± 0.1 around it).
      const Rgb in = At(px, w, sx(xc - 0.15), sy(0.5 * mean));
      EXPECT_LT(Distance(in, faded(j)), 20.0)
          << where << ": " << in.r << "," << in.g << "," << in.b;
      // The bar starts at zero: below it, background.
      EXPECT_LT(Distance(At(px, w, sx(xc - 0.15), sy(0.0) + 4), bg), 20.0) << where;
      // Above the top of the error bar: background.
      EXPECT_LT(Distance(At(px, w, sx(xc), sy(mean + err) - 6), bg), 20.0) << where;
      // Beside the bar, in the gap between categories (x = k ± 0.45): background.
      EXPECT_LT(Distance(At(px, w, sx(k + (j == 0 ? -0.45 : 0.45)), sy(0.3 * mean)), bg), 20.0)
          << where;
      // The error bar: dark at the centre between the mean and mean + std (above the bar).
      const float y_err = sy(mean + 0.5 * err);
      int dark = 0;
      for (int dx = -2; dx <= 2; ++dx) {
        const Rgb p = At(px, w, sx(xc) + static_cast<float>(dx), y_err);
        dark = std::max(dark, 255 * 3 - (p.r + p.g + p.b));
      }
      EXPECT_GT(dark, 300) << where << ": no error bar above the mean";
      // Beside the error bar, above the bar: background.
      EXPECT_LT(Distance(At(px, w, sx(xc - 0.15), y_err), bg), 20.0) << where;
    }
  }
}

}  // namespace
}  // namespace formsim::app
