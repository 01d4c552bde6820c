// Log-scale y axes (app/render/plot_log_scale.hpp, PlotData::log_y): decade ticks labelled
// 10^k, values <= 0 left out with a note instead of a crash, and an exponential decay drawn as
// a straight line.
#include "app/render/plot_log_scale.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "app/export/figure_export.hpp"

namespace formsim::app {
namespace {

TEST(PlotLogScale, DecadeTicksAndLabels) {
  double step = 0;
  EXPECT_EQ(DecadeTicks(-4.3, 0.2, 6, &step), (std::vector<double>{-4, -3, -2, -1, 0}));
  EXPECT_EQ(step, 1);
  // Many decades: every m-th, on multiples of m.
  EXPECT_EQ(DecadeTicks(-12.2, 0.1, 5, &step), (std::vector<double>{-12, -9, -6, -3, 0}));
  EXPECT_EQ(step, 3);
  // Less than two whole decades: 1, 2, 5 times powers of ten, labelled as values.
  const std::vector<double> t125 = DecadeTicks(-1.9, -0.1, 6, &step);
  EXPECT_EQ(step, 0);
  std::string labels;
  for (double t : t125) labels += DecadeLabel(t, step) + " ";
  EXPECT_EQ(labels, "0.02 0.05 0.1 0.2 0.5 ");
  // Within one decade: every digit.
  labels.clear();
  for (double t : DecadeTicks(std::log10(0.25), std::log10(0.55), 6, &step))
    labels += DecadeLabel(t, step) + " ";
  EXPECT_EQ(labels, "0.3 0.4 0.5 ");
  EXPECT_EQ(DecadeLabel(-3, 1), "10⁻³");
  EXPECT_EQ(DecadeLabel(0, 1), "10⁰");
  EXPECT_EQ(DecadeLabel(12, 3), "10¹²");
  EXPECT_EQ(DecadeLabel(0.5, 0), "3.16");
  EXPECT_EQ(SuperscriptInt(-40), "⁻⁴⁰");
}

TEST(PlotLogScale, NonPositiveValuesAreDroppedAndCounted) {
  PlotData d;
  d.log_y = true;
  PlotSeries s;
  s.x = {0, 1, 2, 3, 4};
  s.y = {1, 0.1, 0, -1, std::nan("")};
  d.series.push_back(s);
  d.reference_lines = {0.0, 10.0};
  long dropped = 0;
  bool applies = false;
  const PlotData out = LogYData(d, &dropped, &applies);
  EXPECT_TRUE(applies);
  EXPECT_EQ(dropped, 2);  // 0 and -1; the NaN was a gap already
  ASSERT_EQ(out.series[0].y.size(), 5u);
  EXPECT_DOUBLE_EQ(out.series[0].y[0], 0.0);
  EXPECT_DOUBLE_EQ(out.series[0].y[1], -1.0);
  EXPECT_TRUE(std::isnan(out.series[0].y[2]) && std::isnan(out.series[0].y[3]));
  EXPECT_EQ(out.reference_lines, std::vector<double>{1.0});
  // Bars keep their linear axis.
  d.series[0].bars = true;
  LogYData(d, &dropped, &applies);
  EXPECT_FALSE(applies);
}

// The largest distance of the recorded data line's points from the chord between its ends, px.
double Bend(const VectorFigure& fig) {
  const VectorOp* line = nullptr;
  for (const VectorOp& op : fig.ops)
    if (op.kind == VectorOp::Kind::kPath && (line == nullptr || op.pts.size() > line->pts.size()))
      line = &op;
  if (line == nullptr) return -1;
  const ImVec2 a = line->pts.front(), b = line->pts.back();
  const double len = std::hypot(b.x - a.x, b.y - a.y);
  double worst = 0;
  for (const ImVec2& p : line->pts)
    worst = std::max(worst, std::abs((b.x - a.x) * (a.y - p.y) - (a.x - p.x) * (b.y - a.y)) / len);
  return worst;
}

std::string AllText(const VectorFigure& fig) {
  std::string out;
  for (const VectorOp& op : fig.ops)
    if (op.kind == VectorOp::Kind::kText) out += op.text + "\n";
  return out;
}

TEST(PlotLogScale, ExponentialDecayIsAStraightLine) {
  PlotData d;
  d.title = "decay";
  d.x_label = "t [s]";
  d.y_label = "e_{l} [m]";
  PlotSeries s;
  s.label = "e_{l}";
  for (int i = 0; i <= 400; ++i) {
    s.x.push_back(0.025 * i);
    s.y.push_back(0.5 * std::exp(-0.9 * s.x.back()));
  }
  s.y.back() = 0.0;  // a value the log axis cannot show
  d.series.push_back(s);
  const Theme& theme = GetTheme(ThemeId::kLight);
  const VectorFigure linear = RecordPlot(d, 640, 400, theme);
  EXPECT_GT(Bend(linear), 40.0) << "on a linear axis the decay bends";
  EXPECT_EQ(AllText(linear).find("10⁻"), std::string::npos);
  d.log_y = true;
  const VectorFigure log = RecordPlot(d, 640, 400, theme);
  EXPECT_LT(Bend(log), 1.0) << "on a log axis the decay is straight";
  const std::string text = AllText(log);
  EXPECT_NE(text.find("10⁻¹\n"), std::string::npos) << text;
  EXPECT_NE(text.find("10⁻³\n"), std::string::npos) << text;
  EXPECT_NE(text.find("log y: 1 value ≤ 0 not drawn"), std::string::npos) << text;
  // All values <= 0: nothing drawn, a note, no crash.
  for (double& y : d.series[0].y) y = -y;
  const std::string none = AllText(RecordPlot(d, 640, 400, theme));
  EXPECT_NE(none.find("log y: 401 values ≤ 0 not drawn"), std::string::npos) << none;
}

}  // namespace
}  // namespace formsim::app
