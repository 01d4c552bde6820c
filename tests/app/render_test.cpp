// Headless rendering checked on pixels: the world view shows every robot in its colour where
// the simulation says it is, exported figures have axes, --frames writes the right files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "app/export/export.hpp"
#include "app/export/figure_data.hpp"
#include "app/export/png_writer.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::NonBackgroundFraction;
using testing::Scenario;
using testing::TempDir;

struct Pixel {
  int r, g, b;
};

Pixel PixelAt(const std::vector<std::uint8_t>& px, int w, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 4;
  return {px[i], px[i + 1], px[i + 2]};
}

// Smallest colour distance to `want` within `radius` pixels of (cx, cy).
double NearestColour(const std::vector<std::uint8_t>& px, int w, int h, ImVec2 c, int radius,
                     Pixel want) {
  double best = 1e9;
  for (int y = static_cast<int>(c.y) - radius; y <= static_cast<int>(c.y) + radius; ++y)
    for (int x = static_cast<int>(c.x) - radius; x <= static_cast<int>(c.x) + radius; ++x) {
      if (x < 0 || y < 0 || x >= w || y >= h) continue;
      const Pixel p = PixelAt(px, w, x, y);
      best = std::min(
          best, std::sqrt(double((p.r - want.r) * (p.r - want.r) + (p.g - want.g) * (p.g - want.g) +
                                 (p.b - want.b) * (p.b - want.b))));
    }
  return best;
}

TEST(HeadlessRender, RobotsAppearInTheirColourWhereTheSimSaysTheyAre) {
  sim::Session s(Scenario("formation_traj2"), {}, -1);
  while (s.exp().time() < 3.0) s.Step();
  const int w = 640, h = 360;
  OffscreenRenderer r(w, h);
  View view;
  AutoFit fit;
  const auto& px = r.RenderWorld(s.exp(), view, fit, true, "test");
  ASSERT_EQ(px.size(), static_cast<std::size_t>(w * h * 4));
  EXPECT_GT(NonBackgroundFraction(px), 0.03) << "the frame is (nearly) blank";

  const auto& robots = s.exp().world().robots();
  ASSERT_FALSE(robots.empty());
  for (const auto& robot : robots) {
    const sim::Color c = sim::PaletteColor(robot->def().color_index);
    const Pixel want{int(c.r * 255), int(c.g * 255), int(c.b * 255)};
    const ImVec2 p = view.ToScreen(robot->pose().p());
    ASSERT_TRUE(p.x > 0 && p.x < w && p.y > 0 && p.y < h) << robot->name() << " is off screen";
    // The body is filled with the robot colour at 85 % opacity: allow for that blend.
    EXPECT_LT(NearestColour(px, w, h, p, 6, want), 60.0) << robot->name();
    // ... and far from the robot that colour must not be everywhere (the check can fail).
  }
  // The colour of R1 is not found in an empty corner of the view.
  const sim::Color c0 = sim::PaletteColor(robots[0]->def().color_index);
  EXPECT_GT(NearestColour(px, w, h, ImVec2(w - 20, 20), 6,
                          Pixel{int(c0.r * 255), int(c0.g * 255), int(c0.b * 255)}),
            60.0);
}

TEST(HeadlessRender, FiguresHaveAxesTicksAndData) {
  sim::Session s(Scenario("formation_traj2"), {"duration=2"}, -1);
  while (!s.exp().finished()) s.Step();
  const auto figures = s.exp().Figures();
  ASSERT_FALSE(figures.empty());
  OffscreenRenderer r(320, 240);
  for (const auto& fig : figures) {
    const PlotData data = ResolveFigure(fig, s.exp().recorder());
    ASSERT_TRUE(data.error.empty()) << fig.id << ": " << data.error;
    const int w = 800, h = 500;
    const auto& px = r.RenderFigure(data, w, h);
    const PlotLayout& L = r.last_plot_layout();
    EXPECT_GE(L.x_ticks.size(), 2u) << fig.id;
    EXPECT_GE(L.y_ticks.size(), 2u) << fig.id;
    // Light paper background in the corner, dark axis lines along the left and bottom edges.
    const Pixel corner = PixelAt(px, w, 2, 2);
    EXPECT_GT(corner.r + corner.g + corner.b, 3 * 245) << fig.id;
    int dark_left = 0, dark_bottom = 0;
    const int ax = static_cast<int>(std::round(L.area_min.x)),
              by = static_cast<int>(std::round(L.area_max.y));
    for (int y = static_cast<int>(L.area_min.y) + 2; y < static_cast<int>(L.area_max.y) - 2; ++y) {
      const Pixel p0 = PixelAt(px, w, ax, y),
                  p1 = PixelAt(px, w, ax - 1, y);  // the frame straddles the edge
      dark_left += std::min(p0.r + p0.g + p0.b, p1.r + p1.g + p1.b) < 300;
    }
    for (int x = static_cast<int>(L.area_min.x) + 2; x < static_cast<int>(L.area_max.x) - 2; ++x) {
      const Pixel p0 = PixelAt(px, w, x, by), p1 = PixelAt(px, w, x, by + 1);
      dark_bottom += std::min(p0.r + p0.g + p0.b, p1.r + p1.g + p1.b) < 300;
    }
    const int hh = static_cast<int>(L.area_max.y - L.area_min.y) - 4;
    const int ww = static_cast<int>(L.area_max.x - L.area_min.x) - 4;
    EXPECT_GT(dark_left, hh * 9 / 10) << fig.id << ": no y axis";
    EXPECT_GT(dark_bottom, ww * 9 / 10) << fig.id << ": no x axis";
    // Tick labels: dark pixels left of the y axis.
    int label_ink = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < ax - 4; ++x) {
        const Pixel p = PixelAt(px, w, x, y);
        label_ink += p.r + p.g + p.b < 300;
      }
    EXPECT_GT(label_ink, 50) << fig.id << ": no tick labels";
    // Some coloured data inside the axes.
    int coloured = 0;
    for (int y = static_cast<int>(L.area_min.y) + 3; y < by - 3; ++y)
      for (int x = ax + 3; x < static_cast<int>(L.area_max.x) - 3; ++x) {
        const Pixel p = PixelAt(px, w, x, y);
        coloured += std::max({p.r, p.g, p.b}) - std::min({p.r, p.g, p.b}) > 60;
      }
    EXPECT_GT(coloured, 100) << fig.id << ": no data drawn";
  }
}

TEST(HeadlessExport, FramesSnapshotAndPlotsHaveTheRightCountAndSize) {
  const std::string dir = TempDir("export_frames");
  sim::Session s(Scenario("formation_traj2"), {"duration=1.0"}, -1);
  ExportOptions opt;
  opt.frames_dir = dir + "/frames";
  opt.snapshots = {dir + "/snap.png"};
  opt.plots_dir = dir + "/plots";
  opt.fps = 12;
  opt.width = 320;
  opt.height = 200;
  opt.plot_size = ParseFigureSize("400x300", "--plot-size");
  const ExportStats st = RunWithExport(s, opt);
  EXPECT_TRUE(s.exp().finished());
  const long expected = FrameCount(1.0, s.exp().dt(), 12);
  EXPECT_EQ(expected, 12);
  EXPECT_EQ(st.frames, expected);
  long files = 0;
  for (const auto& e : std::filesystem::directory_iterator(opt.frames_dir)) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, expected);
  int w = 0, h = 0;
  for (long k : {0L, expected - 1}) {
    char name[32];
    std::snprintf(name, sizeof(name), "/frame_%05ld.png", k);
    const auto px = ReadPng(opt.frames_dir + name, &w, &h);
    EXPECT_EQ(w, 320);
    EXPECT_EQ(h, 200);
    EXPECT_GT(NonBackgroundFraction(px), 0.02);
  }
  ReadPng(opt.snapshots[0], &w, &h);
  EXPECT_EQ(w, 320);
  for (const auto& fig : s.exp().Figures()) {
    ReadPng(opt.plots_dir + "/" + fig.id + ".png", &w, &h);
    EXPECT_EQ(w, 400);
    EXPECT_EQ(h, 300);
  }
}

TEST(HeadlessExport, PngRoundTripIsLossless) {
  std::vector<std::uint8_t> px(37 * 23 * 4);
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = static_cast<std::uint8_t>(i * 7 + i / 13);
  const std::string dir = TempDir("png_roundtrip");
  WritePng(dir + "/a.png", 37, 23, px.data());  // with alpha (not all opaque)
  int w = 0, h = 0;
  EXPECT_EQ(ReadPng(dir + "/a.png", &w, &h), px);
  for (std::size_t i = 3; i < px.size(); i += 4) px[i] = 255;
  WritePng(dir + "/b.png", 37, 23, px.data());  // opaque: stored as RGB
  EXPECT_EQ(ReadPng(dir + "/b.png", &w, &h), px);
}

TEST(HeadlessExport, BadOptionsFailBeforeSimulating) {
  int w = 0, h = 0;
  EXPECT_THROW(ParseSize("1280", &w, &h), std::runtime_error);
  EXPECT_THROW(ParseSize("10x10", &w, &h), std::runtime_error);
  ParseSize("1280x720", &w, &h);
  EXPECT_EQ(w, 1280);
  ExportOptions opt;
  opt.video = TempDir("bad_video") + "/v.mp4";
  opt.width = 321;  // odd: H.264 yuv420p needs even sizes
  EXPECT_THROW(PrepareExport(opt), std::runtime_error);
  opt.width = 320;
  opt.fps = 0;
  EXPECT_THROW(PrepareExport(opt), std::runtime_error);
}

}  // namespace
}  // namespace formsim::app
