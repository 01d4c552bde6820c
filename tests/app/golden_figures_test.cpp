// Golden images: a few study figures rendered small (480 x 300) and compared with the images
// stored in tests/fixtures/golden/, within a tolerance that absorbs anti-aliasing noise but not
// a moved legend, axis or band. When a change to the figures is intended, regenerate them:
//   FORMSIM_UPDATE_GOLDEN=1 build/tests/tests_app --gtest_filter='GoldenFigures.*'
// and look at the new images before committing them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include "app/export/png_writer.hpp"
#include "app/export/study_figures.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "sim/study/sweep.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;

constexpr int kFigureW = 480, kFigureH = 300;

std::string GoldenPath(const std::string& name) {
  return std::string(FORMSIM_SOURCE_DIR) + "/tests/fixtures/golden/" + name + ".png";
}

// How far two images are apart: the fraction of pixels whose largest channel difference is
// above 64 (a line or a letter that moved), and the mean absolute difference per channel.
struct Difference {
  double moved = 1.0, mean = 255.0;
};
Difference Compare(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  Difference d;
  if (a.size() != b.size() || a.empty()) return d;
  std::size_t moved = 0;
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); i += 4) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(static_cast<int>(a[i + c]) - static_cast<int>(b[i + c]));
      worst = std::max(worst, diff);
      sum += diff;
    }
    if (worst > 64) ++moved;
  }
  d.moved = static_cast<double>(moved) / static_cast<double>(a.size() / 4);
  d.mean = sum / static_cast<double>(a.size() / 4 * 3);
  return d;
}

// Renders `fig` and compares it with its golden image (or writes it when updating).
void ExpectGolden(const std::string& name, const PlotData& fig) {
  OffscreenRenderer r(kFigureW, kFigureH);
  const std::vector<std::uint8_t> px = r.RenderFigure(fig, kFigureW, kFigureH);
  const std::string path = GoldenPath(name);
  const char* update = std::getenv("FORMSIM_UPDATE_GOLDEN");
  if (update != nullptr && std::string(update) == "1") {
    fs::create_directories(fs::path(path).parent_path());
    WritePng(path, kFigureW, kFigureH, px.data());
    GTEST_SKIP() << "wrote " << path;
  }
  ASSERT_TRUE(fs::exists(path)) << path << " is missing; regenerate with FORMSIM_UPDATE_GOLDEN=1";
  int w = 0, h = 0;
  const std::vector<std::uint8_t> golden = ReadPng(path, &w, &h);
  ASSERT_EQ(w, kFigureW);
  ASSERT_EQ(h, kFigureH);
  const Difference d = Compare(px, golden);
  // Tolerance: 1% of the pixels may differ strongly, 3 levels on average.
  EXPECT_LE(d.moved, 0.01) << name << ": " << 100 * d.moved << "% of the pixels moved";
  EXPECT_LE(d.mean, 3.0) << name << ": mean difference " << d.mean;
  if (::testing::Test::HasFailure()) {
    const std::string got = testing::TempDir("golden_" + name) + ".png";
    WritePng(got, kFigureW, kFigureH, px.data());
    ADD_FAILURE() << "rendered image: " << got;
  }
}

std::vector<sim::SweepRecord> Records(const sim::SweepDefinition& d,
                                      const std::function<double(std::size_t, std::size_t)>& f) {
  std::vector<sim::SweepRecord> out;
  for (std::size_t r = 0; r < d.runs(); ++r) {
    sim::SweepRecord rec;
    rec.run = r;
    rec.status = "completed";
    rec.metrics = {{"m", f(d.PointOf(r), r % d.seeds.size())}};
    out.push_back(rec);
  }
  return out;
}

sim::ScenarioSource Source() {
  return sim::ScenarioSource::FromFile(testing::Scenario("formation_traj2_ukf"));
}

TEST(GoldenFigures, SweepLineWithItsBand) {
  // σ zero, non-zero and zero again along the key (the case of the band polygon).
  const sim::SweepDefinition d =
      sim::DefineSweep(Source(), {}, {"robots.R2.follow.k_l=0.1,0.3,1"}, {1, 2, 3, 4});
  const auto recs = Records(d, [](std::size_t p, std::size_t s) {
    return p == 1 ? 0.5 + 0.05 * static_cast<double>(s) : 0.2 + 0.1 * static_cast<double>(p);
  });
  PlotData fig;
  ASSERT_TRUE(SweepFigure(d, sim::BuildSweepTables(d, recs), recs, 0, &fig));
  ExpectGolden("sweep_line_ci95", fig);
}

TEST(GoldenFigures, SweepHeatmapWithIntervals) {
  const sim::SweepDefinition d = sim::DefineSweep(
      Source(), {}, {"robots.R2.follow.k_l=0.1,0.2,0.4", "robots.R2.follow.k_phi=0.1,0.2"}, {1, 2});
  const auto recs = Records(d, [](std::size_t p, std::size_t s) {
    return static_cast<double>(p) + 0.2 * static_cast<double>(s);
  });
  PlotData fig;
  ASSERT_TRUE(SweepFigure(d, sim::BuildSweepTables(d, recs), recs, 0, &fig));
  ExpectGolden("sweep_heatmap", fig);
}

TEST(GoldenFigures, SmallMultiplePanel) {
  const sim::SweepDefinition d =
      sim::DefineSweep(Source(), {},
                       {"robots.R2.follow.k_l=0.1,0.2", "robots.R2.follow.k_phi=0.1,0.2",
                        "robots.R3.follow.k_l=0.1,0.2"},
                       {1, 2});
  const auto recs = Records(d, [](std::size_t p, std::size_t s) {
    return static_cast<double>(p % 3) + 0.1 * static_cast<double>(s);
  });
  const auto panels = SweepPanels(d, sim::BuildSweepTables(d, recs), 0);
  ASSERT_EQ(panels.size(), 3u);
  ExpectGolden("sweep_small_multiple", panels[0]);
}

// The comparison itself: an image is within tolerance of itself, and a shifted copy is not.
TEST(GoldenFigures, ToleranceCatchesAShift) {
  OffscreenRenderer r(kFigureW, kFigureH);
  const sim::SweepDefinition d =
      sim::DefineSweep(Source(), {}, {"robots.R2.follow.k_l=0.1,0.3,1"}, {1, 2});
  const auto recs = Records(d, [](std::size_t p, std::size_t s) {
    return static_cast<double>(p) + 0.1 * static_cast<double>(s);
  });
  PlotData fig;
  ASSERT_TRUE(SweepFigure(d, sim::BuildSweepTables(d, recs), recs, 0, &fig));
  const std::vector<std::uint8_t> a = r.RenderFigure(fig, kFigureW, kFigureH);
  const Difference same = Compare(a, a);
  EXPECT_EQ(same.moved, 0.0);
  EXPECT_EQ(same.mean, 0.0);
  // Everything 6 pixels to the right (what a wider y label would do).
  std::vector<std::uint8_t> shifted(a.size(), 255);
  for (int y = 0; y < kFigureH; ++y)
    for (int x = 6; x < kFigureW; ++x)
      for (int c = 0; c < 4; ++c)
        shifted[(static_cast<std::size_t>(y) * kFigureW + x) * 4 + c] =
            a[(static_cast<std::size_t>(y) * kFigureW + x - 6) * 4 + c];
  const Difference moved = Compare(a, shifted);
  EXPECT_TRUE(moved.moved > 0.01 || moved.mean > 3.0)
      << "a 6-pixel shift must fail: " << moved.moved << " " << moved.mean;
}

}  // namespace
}  // namespace formsim::app
