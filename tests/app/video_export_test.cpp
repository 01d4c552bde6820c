// Video export (issue 28): frames are converted to I420 by formsim (BT.709, limited range, 2x2
// chroma means) and piped to ffmpeg from a thread of the writer's own; the stream says which
// colours it holds, and decodes to the rendered frames within what 4:2:0 loses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "app/export/png_writer.hpp"
#include "app/export/yuv420.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;

using testing::Formsim;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

// BT.709 limited range in floating point, rounded: what each byte must be (within the 1/2^16
// of the fixed-point coefficients, which never moves a rounding here).
int RefY(double r, double g, double b) {
  return static_cast<int>(
      std::floor(16 + 219.0 / 255 * (0.2126 * r + 0.7152 * g + 0.0722 * b) + 0.5));
}
int RefU(double r, double g, double b) {
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  return static_cast<int>(std::floor(128 + 224.0 / 255 * (b - y) / 1.8556 + 0.5));
}
int RefV(double r, double g, double b) {
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  return static_cast<int>(std::floor(128 + 224.0 / 255 * (r - y) / 1.5748 + 0.5));
}

TEST(Yuv420, PrimariesGreysAndBlockMeansAreBt709LimitedRange) {
  struct Case {
    std::uint8_t r, g, b;
    int y, u, v;
  };
  // White and black at the ends of the limited range, grey without chroma, the primaries.
  const Case cases[] = {{255, 255, 255, 235, 128, 128}, {0, 0, 0, 16, 128, 128},
                        {128, 128, 128, 126, 128, 128}, {255, 0, 0, 63, 102, 240},
                        {0, 255, 0, 173, 42, 26},       {0, 0, 255, 32, 240, 118}};
  for (const Case& c : cases) {
    std::vector<std::uint8_t> rgba(4 * 4), out(I420Bytes(2, 2));
    for (int i = 0; i < 4; ++i) {
      rgba[4 * i] = c.r, rgba[4 * i + 1] = c.g, rgba[4 * i + 2] = c.b, rgba[4 * i + 3] = 255;
    }
    RgbaToI420(rgba.data(), 2, 2, out.data());
    for (int i = 0; i < 4; ++i)
      EXPECT_EQ(out[i], c.y) << int(c.r) << "," << int(c.g) << "," << int(c.b);
    EXPECT_EQ(out[4], c.u) << int(c.r) << "," << int(c.g) << "," << int(c.b);
    EXPECT_EQ(out[5], c.v) << int(c.r) << "," << int(c.g) << "," << int(c.b);
    EXPECT_EQ(RefY(c.r, c.g, c.b), c.y);
  }
  // Random pictures of sizes that are and are not multiples of the SIMD width: every byte as
  // the formula gives it, chroma from the mean of each 2x2 block; alpha plays no part.
  std::mt19937 rng(7);
  for (const std::pair<int, int>& size :
       std::vector<std::pair<int, int>>{{2, 2}, {6, 4}, {18, 10}, {34, 2}, {1282, 6}}) {
    // Plain names (a lambda below uses them; clang 14 cannot capture structured bindings).
    const int w = size.first, h = size.second;
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(4) * w * h), out(I420Bytes(w, h));
    for (auto& b : rgba) b = static_cast<std::uint8_t>(rng());
    RgbaToI420(rgba.data(), w, h, out.data());
    auto px = [&](int x, int y, int c) {
      return rgba[4 * (static_cast<std::size_t>(y) * w + x) + c];
    };
    int bad = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        bad += std::abs(out[static_cast<std::size_t>(y) * w + x] -
                        RefY(px(x, y, 0), px(x, y, 1), px(x, y, 2))) > 0;
    for (int y = 0; y < h / 2; ++y)
      for (int x = 0; x < w / 2; ++x) {
        double m[3];
        for (int c = 0; c < 3; ++c)
          m[c] = (px(2 * x, 2 * y, c) + px(2 * x + 1, 2 * y, c) + px(2 * x, 2 * y + 1, c) +
                  px(2 * x + 1, 2 * y + 1, c)) /
                 4.0;
        const std::size_t at = static_cast<std::size_t>(y) * (w / 2) + x;
        bad += std::abs(out[static_cast<std::size_t>(w) * h + at] - RefU(m[0], m[1], m[2])) > 0;
        bad += std::abs(out[static_cast<std::size_t>(w) * h + (w / 2) * (h / 2) + at] -
                        RefV(m[0], m[1], m[2])) > 0;
      }
    // The fixed point may round a value that lies within 2^-16 of a half the other way.
    EXPECT_LE(bad, (w * h * 3 / 2) / 1000 + 1) << w << "x" << h;
  }
}

TEST(VideoExport, StreamIsTaggedBt709AndDecodesToTheRenderedFrames) {
  const std::string dir = TempDir("video_export");
  ASSERT_EQ(Formsim("run formation_traj2 --set duration=1 --fps 10 --size 320x180 -q --video " +
                        dir + "/v.mp4 --frames " + dir + "/f --out " + dir + "/o",
                    dir + "/run.log"),
            0)
      << ReadText(dir + "/run.log");
  // One second at 10 frames/s: 10 PNG frames, and as many in the video.
  ASSERT_TRUE(fs::exists(dir + "/f/frame_00009.png"));
  ASSERT_FALSE(fs::exists(dir + "/f/frame_00010.png"));
  ASSERT_EQ(RunShell("ffprobe -v error -show_entries stream=pix_fmt,color_space,color_range,"
                     "color_primaries,color_transfer,nb_frames -of compact " +
                         dir + "/v.mp4",
                     dir + "/probe.txt"),
            0);
  const std::string probe = ReadText(dir + "/probe.txt");
  for (const char* want : {"pix_fmt=yuv420p", "color_range=tv", "color_space=bt709",
                           "color_transfer=bt709", "color_primaries=bt709", "nb_frames=10"})
    EXPECT_NE(probe.find(want), std::string::npos) << want << " in " << probe;
  // The first and last frames, decoded by ffmpeg with the stream's own colour tags.
  for (int k : {0, 9}) {
    const std::string png = dir + "/d" + std::to_string(k) + ".png";
    ASSERT_EQ(RunShell("ffmpeg -v error -y -i " + dir + "/v.mp4 -vf 'select=eq(n\\," +
                           std::to_string(k) + ")' -frames:v 1 " + png,
                       dir + "/dec.log"),
              0)
        << ReadText(dir + "/dec.log");
    char name[40];
    std::snprintf(name, sizeof(name), "/f/frame_%05d.png", k);
    int w = 0, h = 0, dw = 0, dh = 0;
    const std::vector<std::uint8_t> frame = ReadPng(dir + name, &w, &h);
    const std::vector<std::uint8_t> decoded = ReadPng(png, &dw, &dh);
    ASSERT_EQ(dw, w);
    ASSERT_EQ(dh, h);
    double sq = 0;
    for (std::size_t i = 0; i < frame.size(); ++i)
      if (i % 4 != 3) sq += (frame[i] - decoded[i]) * (frame[i] - decoded[i]);
    const double psnr = 10 * std::log10(255.0 * 255.0 / (sq / (frame.size() * 3 / 4)));
    // ffmpeg's own conversion (BT.601, read as such) gave 39 dB on these frames and shifted
    // the background by one level; formsim's gives 41-42.
    EXPECT_GT(psnr, 38.0) << "frame " << k;
    // The background (the commonest colour) decodes, on average, within half a level of what
    // was rendered: no shift of the whole picture's colour.
    auto colour = [&](std::size_t i) {
      return static_cast<std::uint32_t>(frame[i] | frame[i + 1] << 8 | frame[i + 2] << 16);
    };
    std::map<std::uint32_t, int> count;
    for (std::size_t i = 0; i < frame.size(); i += 4) ++count[colour(i)];
    const std::uint32_t bg = std::max_element(count.begin(), count.end(), [](auto& a, auto& b) {
                               return a.second < b.second;
                             })->first;
    double shift[3] = {0, 0, 0};
    for (std::size_t i = 0; i < frame.size(); i += 4)
      if (colour(i) == bg)
        for (int c = 0; c < 3; ++c) shift[c] += decoded[i + c] - frame[i + c];
    for (int c = 0; c < 3; ++c)
      EXPECT_LE(std::abs(shift[c] / count[bg]), 0.5) << "frame " << k << " channel " << c;
  }
}

}  // namespace
}  // namespace formsim::app
