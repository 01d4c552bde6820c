// Every figure of every shipped scenario recorded as SVG: the label markup of the figure
// sources (e_{l}, φ_{est}, \sigma^{2}) is drawn as <tspan>s with a baseline shift, and no text
// node shows a literal underscore, a brace or a backslash. Bad markup in a figure is refused
// naming the figure's text.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "app/export/figure_data.hpp"
#include "app/export/figure_export.hpp"
#include "app/export/figure_requests.hpp"
#include "app/export/pdf_writer.hpp"
#include "app/export/svg_writer.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

// The character data of every <text> and <title> element (tags inside, the tspans, removed).
std::vector<std::string> TextNodes(const std::string& svg) {
  std::vector<std::string> out;
  static const std::regex element("<(text|title)[^>]*>(.*?)</\\1>");
  static const std::regex tag("<[^>]*>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), element);
       it != std::sregex_iterator(); ++it)
    out.push_back(std::regex_replace((*it)[2].str(), tag, ""));
  return out;
}

// The figures of a scenario after a few steps (enough for every series to have data).
std::vector<std::pair<sim::FigureSpec, PlotData>> FiguresOf(const std::string& file) {
  sim::Session s(file, std::vector<sim::Override>{});
  for (int i = 0; i < 20 && !s.exp().finished(); ++i) s.exp().Step();
  std::vector<std::pair<sim::FigureSpec, PlotData>> out;
  for (const sim::FigureSpec& f : s.exp().Figures())
    out.emplace_back(f, ResolveFigure(f, s.exp().recorder()));
  return out;
}

class ShippedFigureMarkup : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedFigureMarkup, SvgTextHasNoLiteralUnderscore) {
  const auto figures = FiguresOf(GetParam());
  ASSERT_FALSE(figures.empty());
  FigureSize size;
  for (const auto& [spec, data] : figures) {
    ASSERT_EQ(data.error, "") << spec.id;
    const std::string svg =
        SvgDocument(RecordPlot(data, 640, 400, GetTheme(ThemeId::kLight)), size, data.title);
    const auto nodes = TextNodes(svg);
    EXPECT_GE(nodes.size(), 3u) << spec.id;
    for (const std::string& t : nodes)
      EXPECT_EQ(t.find_first_of("_\\{}"), std::string::npos)
          << std::filesystem::path(GetParam()).stem().string() << "/" << spec.id << ": '" << t
          << "'";
  }
}

std::string Name(const ::testing::TestParamInfo<std::string>& info) {
  return std::filesystem::path(info.param).stem().string();
}
INSTANTIATE_TEST_SUITE_P(Shipped, ShippedFigureMarkup, ::testing::ValuesIn(sim::ShippedScenarios()),
                         Name);

TEST(FigureMarkup, SubscriptsAreTspansWithABaselineShift) {
  for (const auto& [spec, data] : FiguresOf(testing::Scenario("formation_traj2"))) {
    if (spec.id != "distance_error") continue;
    ASSERT_EQ(data.y_label, "e_{l} [m]");
    const std::string svg = SvgDocument(RecordPlot(data, 640, 400, GetTheme(ThemeId::kLight)),
                                        FigureSize(), data.title);
    // The y label, the title and each legend entry: e with a subscript l, still one <text>.
    EXPECT_NE(svg.find(">e<tspan baseline-shift=\"sub\" font-size=\""), std::string::npos);
    EXPECT_GE(testing::CountOf(svg, "<tspan baseline-shift=\"sub\""), 4) << svg;
    EXPECT_NE(svg.find("\">l</tspan> [m]</text>"), std::string::npos) << svg;
    EXPECT_NE(svg.find("\">des</tspan>"), std::string::npos) << svg;
    return;
  }
  FAIL() << "formation_traj2 has no distance_error figure";
}

TEST(FigureMarkup, UnknownCommandInAFigureIsRefusedNamingIt) {
  sim::FigureSpec f =
      sim::TimeFigure("gain", "Gain \\kappa", "k [1]",
                      {sim::Line("e_{l} R1", "t"), sim::Line("e_{\\lamda} R2", "t")});
  const std::string e = FigureMarkupError(f);
  EXPECT_NE(e.find("series 2"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown markup command '\\lamda'"), std::string::npos) << e;
  EXPECT_NE(e.find("\\lambda"), std::string::npos) << "the accepted names are listed: " << e;
  f.series.pop_back();
  EXPECT_EQ(FigureMarkupError(f), "");
  f.y_label = "x^{2";
  EXPECT_NE(FigureMarkupError(f).find("y label: '^{' without its closing '}'"), std::string::npos)
      << FigureMarkupError(f);
  // Resolving reports it instead of drawing (the GUI shows it; export refuses the figure).
  EXPECT_NE(ResolveFigure(f, sim::Recorder()).error.find("y label"), std::string::npos);
}

TEST(FigureMarkup, ExportRequestsAreCheckedBeforeARun) {
  const std::vector<sim::FigureSpec> figs = {
      sim::PlaneFigure("trajectories", "Paths", {sim::Path("R1", "R1.x", "R1.y")}),
      sim::TimeFigure("distance_error", "e_{l}", "e_{l} [m]", {sim::Line("e_{l} R1", "R1.e_l")}),
      sim::TimeFigure("phi_error", "e_{\\phi}", "e_{\\phi} [rad]", {sim::Line("e", "R1.e_phi")})};
  EXPECT_NO_THROW(CheckFigureRequests(figs, {"distance_error", "phi_error"}));
  auto message = [&](const std::vector<sim::FigureSpec>& f, const std::set<std::string>& log_y) {
    try {
      CheckFigureRequests(f, log_y);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(message(figs, {"trajectories"}),
            "--log-y 'trajectories': no time plot of that name (the time plots: distance_error, "
            "phi_error)");
  std::vector<sim::FigureSpec> bad = figs;
  bad[2].series.push_back(sim::Line("e_{\\phy} R2", "R2.e_phi"));
  const std::string e = message(bad, {});
  EXPECT_EQ(e.rfind("figure 'phi_error' series 2: unknown markup command '\\phy'", 0), 0u) << e;
  EXPECT_EQ(ParseFigureNames(" a, b ,c", "--log-y"), (std::set<std::string>{"a", "b", "c"}));
  EXPECT_THROW(ParseFigureNames("a,,b", "--log-y"), std::runtime_error);
}

TEST(FigureMarkup, PdfIsByteDeterministic) {
  for (const auto& [spec, data] : FiguresOf(testing::Scenario("formation_traj2"))) {
    if (spec.id != "distance_error") continue;
    const VectorFigure fig = RecordPlot(data, 640, 400, GetTheme(ThemeId::kLight));
    const std::string a = PdfDocument(fig, FigureSize(), data.title);
    const std::string b = PdfDocument(fig, FigureSize(), data.title);
    ASSERT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == b) << "two exports of one figure differ";
    EXPECT_NE(a.find("/CreationDate (20000101000000Z)"), std::string::npos)
        << "the fixed creation date is missing";
    return;
  }
  FAIL() << "formation_traj2 has no distance_error figure";
}

}  // namespace
}  // namespace formsim::app
