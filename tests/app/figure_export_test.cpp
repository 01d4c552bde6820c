// Figures for papers and slides: sizes and formats, themes, one drawing path onto raster and
// vector canvases (same text metrics, same look), SVG that is XML with text and paths, PDFs that
// poppler reads with the text extractable and the fonts embedded, PNG at a chosen dpi.
#include "app/export/figure_export.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <regex>

#include "app/cli/progress.hpp"
#include "app/export/export.hpp"
#include "app/export/figure_data.hpp"
#include "app/export/png_writer.hpp"
#include "app/export/svg_writer.hpp"
#include "app/export/video_writer.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/label_markup.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "app/render/vector_canvas.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::ReadText;
using testing::RunShell;
using testing::Scenario;
using testing::TempDir;

// The text a markup label's runs spell (what the SVG's and the PDF's text hold).
std::string Plain(const std::string& label) {
  std::string out;
  for (const MarkupRun& r : ParseMarkup(label).runs) out += r.text;
  return out;
}

// Output of a shell command (stdout and stderr), and its exit code.
std::string Shell(const std::string& cmd, int* rc, const std::string& dir) {
  const std::string log = dir + "/shell.txt";
  *rc = RunShell(cmd, log);
  return ReadText(log);
}

// The value of "Key:   value" in pdfinfo's output.
std::string InfoField(const std::string& info, const std::string& key) {
  const auto at = info.find(key + ":");
  if (at == std::string::npos) return "";
  const auto start = info.find_first_not_of(' ', at + key.size() + 1);
  return info.substr(start, info.find('\n', start) - start);
}

// Fraction of pixels whose colours differ by more than 45 levels (summed over R, G, B) once
// both pictures are blurred over 5x5 pixels. Two rasterisers drawing the same figure differ in
// how anti-aliasing spreads a line over neighbouring pixels, which the blur evens out; a missing
// or moved line, label or legend does not.
double DifferentPixels(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
                       int w, int h) {
  auto blur = [&](const std::vector<std::uint8_t>& px, int c) {
    // Summed-area table of one channel, then a 5x5 mean at every pixel.
    std::vector<long> sat(static_cast<std::size_t>(w + 1) * (h + 1), 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        sat[(y + 1) * (w + 1) + x + 1] = px[(static_cast<std::size_t>(y) * w + x) * 4 + c] +
                                         sat[y * (w + 1) + x + 1] + sat[(y + 1) * (w + 1) + x] -
                                         sat[y * (w + 1) + x];
    std::vector<int> out(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int x0 = std::max(0, x - 2), x1 = std::min(w, x + 3);
        const int y0 = std::max(0, y - 2), y1 = std::min(h, y + 3);
        const long sum = sat[y1 * (w + 1) + x1] - sat[y0 * (w + 1) + x1] - sat[y1 * (w + 1) + x0] +
                         sat[y0 * (w + 1) + x0];
        out[static_cast<std::size_t>(y) * w + x] = static_cast<int>(sum / ((x1 - x0) * (y1 - y0)));
      }
    return out;
  };
  std::vector<int> diff(static_cast<std::size_t>(w) * h, 0);
  for (int c = 0; c < 3; ++c) {
    const auto ba = blur(a, c), bb = blur(b, c);
    for (std::size_t i = 0; i < diff.size(); ++i) diff[i] += std::abs(ba[i] - bb[i]);
  }
  long far = 0;
  for (int d : diff) far += d > 45;
  return static_cast<double>(far) / diff.size();
}

TEST(FigureSize, PixelsAndPaperUnits) {
  const FigureSize px = ParseFigureSize("960x600", "--plot-size");
  EXPECT_EQ(px.LayoutWidth(), 960);
  EXPECT_EQ(px.LayoutHeight(), 600);
  EXPECT_EQ(px.PngWidth(192), 1920);
  EXPECT_DOUBLE_EQ(px.LayoutScale(), 1.0);
  const FigureSize cm = ParseFigureSize("8.5cmx6cm", "--plot-size");
  EXPECT_EQ(cm.width.Text(), "8.5cm");
  EXPECT_NEAR(cm.width.Pixels(), 8.5 / 2.54 * 96, 1e-9);
  EXPECT_EQ(cm.PngWidth(300), 1004);  // 8.5 cm at 300 dpi
  EXPECT_EQ(cm.PngHeight(300), 709);
  // Paper sizes are laid out 4/3 larger, so 16 px labels print at 9 pt.
  EXPECT_EQ(cm.LayoutWidth(), 428);
  const FigureSize in = ParseFigureSize("3.5inx2.5in", "--plot-size");
  EXPECT_EQ(in.PngWidth(96), 336);
  EXPECT_EQ(ParseFigureSize("85mmx60mm", "--plot-size").PngWidth(300), 1004);
  for (const char* bad : {"8.5cm", "8.5cmx6", "1cmx1cm", "axb", "960x600x2", "-5x600", "960X",
                          "9000x600", "10ptx10pt"}) {
    try {
      ParseFigureSize(bad, "--plot-size");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::runtime_error& e) {
      // The flag the user typed is named, not --size.
      EXPECT_EQ(std::string(e.what()).rfind("--plot-size '", 0), 0u) << e.what();
    }
  }
  EXPECT_THROW(ParseDpi(10), std::runtime_error);
  EXPECT_DOUBLE_EQ(ParseDpi(300), 300);
}

TEST(FigureFormats, ListsExtensionsAndFolderNames) {
  EXPECT_EQ(ParseFigureFormats("pdf,png", "--plot-format"),
            (std::vector<FigureFormat>{FigureFormat::kPng, FigureFormat::kPdf}));
  EXPECT_EQ(ParseFigureFormats("SVG,svg", "--plot-format"),
            std::vector<FigureFormat>{FigureFormat::kSvg});
  EXPECT_THROW(ParseFigureFormats("png,jpg", "--plot-format"), std::runtime_error);
  EXPECT_THROW(ParseFigureFormats("", "--plot-format"), std::runtime_error);
  EXPECT_EQ(FormatOfFile("a/b.PDF", "--snapshot"), FigureFormat::kPdf);
  EXPECT_THROW(FormatOfFile("a/b.jpg", "--snapshot"), std::runtime_error);
  EXPECT_THROW(CheckFolderName("p.svg", "--plots", ""), std::runtime_error);
  EXPECT_NO_THROW(CheckFolderName("plots", "--plots", ""));
}

TEST(Themes, ParseAndPrintStylesAreGreyAndDistinct) {
  EXPECT_EQ(ParseTheme("high-contrast"), ThemeId::kHighContrast);
  EXPECT_THROW(ParseTheme("blue"), std::runtime_error);
  const Theme& print = GetTheme(ThemeId::kPrint);
  std::vector<std::array<float, 4>> patterns;
  for (int i = 0; i < 5; ++i) {
    const SeriesLook look = print.Series(sim::PaletteColor(i), i, false);
    EXPECT_FLOAT_EQ(look.color.r, look.color.g) << "print series " << i << " is not grey";
    EXPECT_FLOAT_EQ(look.color.g, look.color.b);
    std::array<float, 4> p = look.dash.lengths;
    p[3] += 100.0f * look.dash.count;
    for (const auto& q : patterns) EXPECT_NE(p, q) << "series " << i << " repeats a dash pattern";
    patterns.push_back(p);
  }
  // Dark themes turn black ink light and keep colours colourful.
  const Theme& dark = GetTheme(ThemeId::kDark);
  EXPECT_GT(dark.Ink({0.1f, 0.1f, 0.1f, 1}).r, 0.7f);
  const sim::Color blue = dark.Ink(sim::PaletteColor(0));
  EXPECT_GT(blue.b - blue.r, 0.3f);
}

// A short formation run whose figures every test below draws.
class FigureRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    session_ = new sim::Session(Scenario("formation_traj2_ukf"), {"duration=3"}, -1);
    while (!session_->exp().finished()) session_->Step();
  }
  static void TearDownTestSuite() {
    delete session_;
    session_ = nullptr;
  }
  static PlotData Figure(const std::string& id) {
    for (const auto& f : session_->exp().Figures())
      if (f.id == id) return ResolveFigure(f, session_->exp().recorder());
    ADD_FAILURE() << "no figure " << id;
    return {};
  }
  static sim::Session* session_;
};
sim::Session* FigureRun::session_ = nullptr;

// An axis label names its quantity, not just a unit ("[rad]" alone said nothing).
TEST_F(FigureRun, AxisLabelsNameTheirQuantity) {
  int figures = 0;
  for (const auto& f : session_->exp().Figures()) {
    for (const std::string& label : {f.x_label, f.y_label})
      EXPECT_FALSE(!label.empty() && label[0] == '[') << f.id << ": label '" << label << "'";
    ++figures;
  }
  EXPECT_GT(figures, 5);
}

TEST_F(FigureRun, VectorTextIsMeasuredExactlyAsTheRasterText) {
  OffscreenRenderer r(320, 240);
  r.RenderFigure(Figure("phi_error"), 320, 240);  // builds the font atlas
  ImDrawList list(ImGui::GetDrawListSharedData());
  ImGuiCanvas raster(&list, r.fonts());
  VectorCanvas vector(320, 240);
  for (FontRole f : {FontRole::kSmall, FontRole::kLabel, FontRole::kTitle, FontRole::kUi}) {
    for (const char* s :
         {"e_φ R1-R2", "−0.05", "(a) Robot trajectories", "×10⁻⁴", "t [s]", "σ ≈ 3 mm, 224.7°"}) {
      EXPECT_NEAR(raster.TextSize(f, s).x, vector.TextSize(f, s).x, 0.02)
          << s << " in role " << static_cast<int>(f);
      EXPECT_FLOAT_EQ(raster.TextSize(f, s).y, vector.TextSize(f, s).y);
    }
  }
}

TEST_F(FigureRun, EachThemeHasItsOwnBackground) {
  const PlotData data = Figure("distance_error");
  std::map<ThemeId, std::array<int, 3>> figure_bg, world_bg;
  for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint, ThemeId::kHighContrast}) {
    const Theme& theme = GetTheme(id);
    OffscreenRenderer r(400, 250, theme);
    const auto& px = r.RenderFigure(data, 400, 250);
    figure_bg[id] = {px[0], px[1], px[2]};
    EXPECT_NEAR(px[0], theme.background.r * 255, 1.0) << theme.name;
    View view;
    AutoFit fit;
    const auto& w = r.RenderWorld(session_->exp(), view, fit, true, "");
    const std::size_t corner = (static_cast<std::size_t>(240) * 400 + 390) * 4;  // bottom right
    world_bg[id] = {w[corner], w[corner + 1], w[corner + 2]};
  }
  for (auto a = figure_bg.begin(); a != figure_bg.end(); ++a)
    for (auto b = std::next(a); b != figure_bg.end(); ++b) {
      EXPECT_NE(a->second, b->second)
          << GetTheme(a->first).name << " vs " << GetTheme(b->first).name << " (figures)";
      EXPECT_NE(world_bg[a->first], world_bg[b->first])
          << GetTheme(a->first).name << " vs " << GetTheme(b->first).name << " (world)";
    }
}

TEST_F(FigureRun, PngAtADpiHasTheScaledSizeAndItsResolution) {
  const std::string dir = TempDir("figure_dpi");
  OffscreenRenderer r(320, 240, GetTheme(ThemeId::kLight), 300.0f / 96.0f);
  const auto& px = r.RenderFigure(Figure("phi_error"), 428, 302);
  EXPECT_EQ(r.width(), 1338);
  EXPECT_EQ(r.height(), 944);
  ASSERT_EQ(px.size(), 1338u * 944u * 4u);
  WritePng(dir + "/a.png", r.width(), r.height(), px.data(), 300);
  const std::string bytes = ReadText(dir + "/a.png");
  const auto at = bytes.find("pHYs");
  ASSERT_NE(at, std::string::npos) << "no resolution chunk";
  const auto u8 = [&](std::size_t i) { return static_cast<unsigned char>(bytes[i]); };
  const unsigned ppm = u8(at + 4) << 24 | u8(at + 5) << 16 | u8(at + 6) << 8 | u8(at + 7);
  EXPECT_EQ(ppm, 11811u);  // 300 dpi in pixels per metre
}

// The same figure as PNG, SVG and PDF through the export of `formsim run`.
TEST_F(FigureRun, SvgAndPdfKeepTextAndPathsAndLookLikeThePng) {
  const std::string dir = TempDir("figure_vector");
  sim::Session s(Scenario("formation_traj2_ukf"), {"duration=3"}, -1);
  ExportOptions opt;
  opt.plots_dir = dir + "/plots";
  opt.plot_formats = {FigureFormat::kPng, FigureFormat::kSvg, FigureFormat::kPdf};
  opt.snapshots = {dir + "/world.svg", dir + "/world.pdf", dir + "/world.png"};
  opt.width = 640;
  opt.height = 400;
  const ExportStats st = RunWithExport(s, opt);
  ASSERT_TRUE(st.error.empty()) << st.error;
  const auto figures = s.exp().Figures();
  ASSERT_GE(figures.size(), 4u);
  EXPECT_EQ(st.figure_files, static_cast<long>(3 * figures.size()));
  int rc = 0;
  for (const auto& fig : figures) {
    const std::string stem = opt.plots_dir + "/" + fig.id;
    const PlotData data = ResolveFigure(fig, s.exp().recorder());
    // SVG: well-formed XML, text as <text>, lines as <path>, no embedded picture.
    Shell("xmllint --noout " + stem + ".svg", &rc, dir);
    EXPECT_EQ(rc, 0) << fig.id << ".svg is not well-formed XML";
    const std::string svg = ReadText(stem + ".svg");
    auto count = [&](const std::string& what) {
      std::size_t n = 0;
      for (std::size_t p = svg.find(what); p != std::string::npos; p = svg.find(what, p + 1)) ++n;
      return n;
    };
    EXPECT_GE(count("<text "), 6u) << fig.id;
    EXPECT_GE(count("<path "), data.series.size()) << fig.id;
    EXPECT_EQ(count("<image"), 0u) << fig.id;
    // The y label is one <text> (its scripts <tspan>s in it), spelling the label's runs.
    const std::string flat = std::regex_replace(svg, std::regex("<tspan[^>]*>|</tspan>"), "");
    EXPECT_NE(flat.find(">" + Plain(data.y_label) + "</text>"), std::string::npos) << fig.id;
    // PDF: poppler opens it, one page of the figure's size, every font embedded, and the axis
    // labels and legend entries come back as text.
    const std::string info = Shell("pdfinfo " + stem + ".pdf", &rc, dir);
    ASSERT_EQ(rc, 0) << info;
    EXPECT_EQ(InfoField(info, "Pages"), "1") << info;
    EXPECT_EQ(InfoField(info, "Page size"), "720 x 450 pts") << info;
    const std::string fonts = Shell("pdffonts " + stem + ".pdf", &rc, dir);
    ASSERT_EQ(rc, 0) << fonts;
    EXPECT_NE(fonts.find("DejaVuSans"), std::string::npos) << fonts;
    EXPECT_EQ(fonts.find(" no "), std::string::npos) << "a font is not embedded:\n" << fonts;
    const std::string text = Shell("pdftotext " + stem + ".pdf -", &rc, dir);
    ASSERT_EQ(rc, 0) << text;
    EXPECT_NE(text.find(Plain(data.x_label)), std::string::npos) << fig.id << ":\n" << text;
    EXPECT_NE(text.find(Plain(data.y_label)), std::string::npos) << fig.id << ":\n" << text;
    EXPECT_NE(text.find(Plain(data.title)), std::string::npos) << fig.id << ":\n" << text;
    for (const auto& series : data.series) {
      if (series.label.empty()) continue;
      EXPECT_NE(text.find(Plain(series.label)), std::string::npos)
          << fig.id << ": " << series.label;
    }
    // The PDF drawn back at 96 dpi looks like the PNG: nearly every pixel within a small
    // difference (anti-aliasing differs at edges).
    Shell("pdftoppm -r 96 -png -singlefile " + stem + ".pdf " + dir + "/back", &rc, dir);
    ASSERT_EQ(rc, 0);
    int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
    const auto png = ReadPng(stem + ".png", &w1, &h1);
    const auto back = ReadPng(dir + "/back.png", &w2, &h2);
    ASSERT_EQ(w1, w2);
    ASSERT_EQ(h1, h2);
    EXPECT_LT(DifferentPixels(png, back, w1, h1), 0.01) << fig.id << ": PDF and PNG differ";
  }
  // The world view as SVG and PDF, the same picture as the PNG.
  const std::string world = ReadText(dir + "/world.svg");
  EXPECT_NE(world.find(">R1</text>"), std::string::npos);
  EXPECT_NE(world.find("<path "), std::string::npos);
  const std::string text = Shell("pdftotext " + dir + "/world.pdf -", &rc, dir);
  EXPECT_NE(text.find("R3"), std::string::npos) << text;
  EXPECT_NE(text.find("t = 3.00 s"), std::string::npos) << text;
  Shell("pdftoppm -r 96 -png -singlefile " + dir + "/world.pdf " + dir + "/wback", &rc, dir);
  int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
  const auto png = ReadPng(dir + "/world.png", &w1, &h1);
  const auto back = ReadPng(dir + "/wback.png", &w2, &h2);
  ASSERT_EQ(w1, w2);
  ASSERT_EQ(h1, h2);
  EXPECT_LT(DifferentPixels(png, back, w1, h1), 0.01) << "world PDF and PNG differ";
  // ... and a different picture is told apart: the check can fail.
  const auto other = ReadPng(dir + "/plots/phi_error.png", &w2, &h2);
  EXPECT_GT(DifferentPixels(ReadPng(dir + "/plots/distance_error.png", &w1, &h1), other, w1, h1),
            0.02);
}

TEST_F(FigureRun, PaperSizedPdfHasThePhysicalPageSize) {
  const std::string dir = TempDir("figure_paper");
  const FigureSize size = ParseFigureSize("8.5cmx6cm", "--plot-size");
  const PlotData data = Figure("trajectories");
  WriteVectorFigure(
      RecordPlot(data, size.LayoutWidth(), size.LayoutHeight(), GetTheme(ThemeId::kPrint)),
      FigureFormat::kPdf, size, data.title, dir + "/t.pdf");
  int rc = 0;
  const std::string info = Shell("pdfinfo " + dir + "/t.pdf", &rc, dir);
  EXPECT_EQ(InfoField(info, "Page size"), "240.945 x 170.079 pts") << info;
  const std::string svg = SvgDocument(
      RecordPlot(data, size.LayoutWidth(), size.LayoutHeight(), GetTheme(ThemeId::kPrint)), size,
      data.title);
  EXPECT_NE(svg.find("width=\"8.5cm\" height=\"6cm\" viewBox=\"0 0 428 302\""), std::string::npos);
  // Print: series told apart by dashes in greys.
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
}

}  // namespace
}  // namespace formsim::app
