// The PNG encoder's own deflate stream (issue 28, png_deflate.hpp): every image decodes to its
// pixels through zlib and through stb_image, the AVX2 and the plain C++ code write the same
// bytes, and Adler32 is zlib's adler32.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "app/export/png_deflate.hpp"
#include "app/export/png_writer.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using Pixels = std::vector<std::uint8_t>;

std::uint32_t BigEndian(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         p[3];
}

// Decodes `png` with zlib (chunk CRCs checked, IDATs inflated, filters undone: only "up" is
// written) and with stb_image; both must give `rgba`. The file is RGB exactly when every alpha
// is 255.
void ExpectDecodesTo(const std::vector<std::uint8_t>& png, int w, int h, const Pixels& rgba,
                     const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_GE(png.size(), 8u);
  ASSERT_EQ(0, std::memcmp(png.data(), "\x89PNG\r\n\x1a\n", 8));
  bool opaque = true;
  for (std::size_t i = 3; i < rgba.size(); i += 4) opaque = opaque && rgba[i] == 255;
  std::vector<std::uint8_t> z;
  int color_type = -1;
  for (std::size_t at = 8; at < png.size();) {
    ASSERT_LE(at + 12, png.size());
    const std::uint32_t n = BigEndian(&png[at]);
    ASSERT_LE(at + 12 + n, png.size());
    const std::string type(reinterpret_cast<const char*>(&png[at + 4]), 4);
    EXPECT_EQ(BigEndian(&png[at + 8 + n]), crc32(0, &png[at + 4], n + 4)) << type;
    if (type == "IHDR") {
      EXPECT_EQ(BigEndian(&png[at + 8]), static_cast<std::uint32_t>(w));
      EXPECT_EQ(BigEndian(&png[at + 12]), static_cast<std::uint32_t>(h));
      color_type = png[at + 17];
    }
    if (type == "IDAT") z.insert(z.end(), &png[at + 8], &png[at + 8 + n]);
    at += 12 + n;
  }
  ASSERT_EQ(color_type, opaque ? 2 : 6);
  const std::size_t comp = opaque ? 3 : 4, stride = comp * w;
  std::vector<std::uint8_t> raw((stride + 1) * h + 1);
  uLongf raw_n = raw.size();
  ASSERT_EQ(uncompress(raw.data(), &raw_n, z.data(), z.size()), Z_OK);
  ASSERT_EQ(raw_n, (stride + 1) * h);
  Pixels px;
  std::vector<std::uint8_t> above(stride, 0);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* r = &raw[y * (stride + 1)];
    ASSERT_EQ(r[0], 2) << "row " << y;
    for (std::size_t i = 0; i < stride; ++i)
      above[i] = static_cast<std::uint8_t>(above[i] + r[1 + i]);
    for (int x = 0; x < w; ++x) {
      px.insert(px.end(), &above[comp * x], &above[comp * x] + comp);
      if (opaque) px.push_back(255);
    }
  }
  EXPECT_TRUE(px == rgba) << "zlib";

  int sw = 0, sh = 0, sc = 0;
  std::uint8_t* s =
      stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &sw, &sh, &sc, 4);
  ASSERT_NE(s, nullptr) << stbi_failure_reason();
  EXPECT_EQ(sw, w);
  EXPECT_EQ(sh, h);
  EXPECT_TRUE(Pixels(s, s + rgba.size()) == rgba) << "stb_image";
  stbi_image_free(s);
}

// Encodes with the AVX2 code (when the CPU has it) and the plain code: the same bytes, decoded
// to the pixels.
void ExpectRoundTrip(int w, int h, const Pixels& rgba, const std::string& what) {
  const std::vector<std::uint8_t> png = EncodePng(w, h, rgba.data(), 96);
  ForcePngScalar(true);
  const std::vector<std::uint8_t> plain = EncodePng(w, h, rgba.data(), 96);
  ForcePngScalar(false);
  EXPECT_TRUE(png == plain) << what << ": the AVX2 and the plain code differ";
  ExpectDecodesTo(png, w, h, rgba, what);
}

// A flat background with a few thin lines and dots, `alpha` on a dot when not 255.
Pixels Drawing(int w, int h, std::uint32_t seed, std::uint8_t alpha = 255) {
  std::mt19937 rng(seed);
  Pixels px(4 * static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < px.size(); i += 4) {
    px[i] = 240;
    px[i + 1] = 240;
    px[i + 2] = 245;
    px[i + 3] = 255;
  }
  for (int k = 0; k < 5; ++k) {
    const int y = static_cast<int>(rng() % h);
    const std::uint8_t c = static_cast<std::uint8_t>(rng());
    for (int x = 0; x < w; ++x) px[4 * (static_cast<std::size_t>(y) * w + x)] = c;
    const int x = static_cast<int>(rng() % w);
    for (int yy = 0; yy < h; ++yy) px[4 * (static_cast<std::size_t>(yy) * w + x) + 1] = c;
  }
  for (int k = 0; k < 20; ++k) {
    const std::size_t p = rng() % (static_cast<std::size_t>(w) * h);
    px[4 * p + 2] = static_cast<std::uint8_t>(rng());
  }
  px[px.size() - 1] = alpha;  // the last pixel: the encoder learns of alpha late
  return px;
}

Pixels Noise(int w, int h, std::uint32_t seed, bool alpha) {
  std::mt19937 rng(seed);
  Pixels px(4 * static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < px.size(); ++i)
    px[i] = i % 4 == 3 && !alpha ? 255 : static_cast<std::uint8_t>(rng());
  return px;
}

Pixels Flat(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
  Pixels px;
  for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i)
    px.insert(px.end(), {r, g, b, a});
  return px;
}

TEST(PngEncoder, NoiseWithAndWithoutAlpha) {
  ExpectRoundTrip(301, 67, Noise(301, 67, 1, false), "noise RGB");
  ExpectRoundTrip(97, 41, Noise(97, 41, 2, true), "noise RGBA");
}

TEST(PngEncoder, FlatImages) {
  ExpectRoundTrip(640, 360, Flat(640, 360, 0, 0, 0, 0), "all zero (transparent)");
  ExpectRoundTrip(640, 360, Flat(640, 360, 0, 0, 0, 255), "opaque black");
  ExpectRoundTrip(1000, 3, Flat(1000, 3, 255, 255, 255, 255), "white: runs > 258 in row 0");
  ExpectRoundTrip(777, 5, Flat(777, 5, 10, 200, 30, 255), "colour: no run in row 0");
}

TEST(PngEncoder, TinyAndThinImages) {
  ExpectRoundTrip(1, 1, Flat(1, 1, 0, 0, 0, 255), "1x1 black: two literals only");
  ExpectRoundTrip(1, 1, Flat(1, 1, 9, 8, 7, 6), "1x1 with alpha");
  ExpectRoundTrip(1, 1, Flat(1, 1, 2, 2, 2, 255), "1x1: one literal symbol");
  ExpectRoundTrip(1, 1000, Drawing(1, 1000, 3), "1x1000");
  ExpectRoundTrip(1000, 1, Drawing(1000, 1, 4), "1000x1");
  ExpectRoundTrip(8000, 1, Noise(8000, 1, 5, false), "8000x1 noise");
  ExpectRoundTrip(8000, 2, Drawing(8000, 2, 6, 0), "8000x2 with alpha");
  ExpectRoundTrip(20000, 3, Drawing(20000, 3, 7), "very wide rows");
}

TEST(PngEncoder, WidthsAroundTheSimdLanes) {
  for (int w = 1; w <= 70; ++w)
    for (int h : {1, 2, 7}) {
      ExpectRoundTrip(w, h, Drawing(w, h, w * 10 + h),
                      "drawing " + std::to_string(w) + "x" + std::to_string(h));
      ExpectRoundTrip(w, h, Drawing(w, h, w * 10 + h, 128),
                      "alpha " + std::to_string(w) + "x" + std::to_string(h));
    }
}

TEST(PngEncoder, RandomSparseImages) {
  std::mt19937 rng(28);
  for (int k = 0; k < 150; ++k) {
    const int w = 1 + static_cast<int>(rng() % 300), h = 1 + static_cast<int>(rng() % 20);
    const std::uint32_t density = 1 + rng() % 64;  // one pixel in `density` changes
    Pixels px = Flat(w, h, 50, 60, 70, 255);
    for (std::size_t i = 0; i < px.size(); ++i)
      if (rng() % density == 0 && (i % 4 != 3 || k % 3 == 0))
        px[i] = static_cast<std::uint8_t>(rng() % 4);
    ExpectRoundTrip(w, h, px, "random " + std::to_string(k));
  }
}

// A frame-sized drawing as the exporter writes it (pHYs absent), through WritePng and ReadPng.
TEST(PngEncoder, FrameSizedDrawingThroughFiles) {
  const std::string dir = testing::TempDir("png_encoder");
  const Pixels px = Drawing(1280, 720, 11);
  WritePng(dir + "/f.png", 1280, 720, px.data());
  int w = 0, h = 0;
  EXPECT_TRUE(ReadPng(dir + "/f.png", &w, &h) == px);
  // The same thread's buffers again for a smaller image with alpha, then a larger one.
  const Pixels small = Drawing(33, 5, 12, 0);
  WritePng(dir + "/s.png", 33, 5, small.data());
  EXPECT_TRUE(ReadPng(dir + "/s.png", &w, &h) == small);
  ExpectRoundTrip(1280, 720, px, "1280x720 again");
}

// A rendered frame: the same bytes from both code paths, its pixels back, and at most 1.5x the
// bytes zlib at level 2 makes of the same filtered rows (the encoder before issue 28: 1.25x).
TEST(PngEncoder, RenderedFrame) {
  sim::Session s(testing::Scenario("formation_traj2"), {"duration=2.0"}, -1);
  while (!s.exp().finished()) s.Step();
  OffscreenRenderer r(1280, 720);
  View view;
  AutoFit fit;
  const Pixels px = r.RenderWorld(s.exp(), view, fit, true, "pixels");
  ExpectRoundTrip(r.width(), r.height(), px, "frame");
  const std::vector<std::uint8_t> png = EncodePng(r.width(), r.height(), px.data());
  const std::uint32_t idat_n = BigEndian(&png[33]);
  ASSERT_EQ(0, std::memcmp(&png[37], "IDAT", 4));
  std::vector<std::uint8_t> raw((3 * 1280 + 1) * 720);
  uLongf raw_n = raw.size();
  ASSERT_EQ(uncompress(raw.data(), &raw_n, &png[41], idat_n), Z_OK);
  std::vector<std::uint8_t> z(compressBound(raw_n));
  uLongf z_n = z.size();
  ASSERT_EQ(compress2(z.data(), &z_n, raw.data(), raw_n, 2), Z_OK);
  EXPECT_LT(idat_n, 1.5 * z_n) << "zlib level 2: " << z_n;
}

// The deflate stream alone: nothing, one byte, one repeated byte (a single literal symbol and
// matches), runs of every length near the match limits.
TEST(PngEncoder, DeflateStreamsInflate) {
  auto check = [](const std::vector<std::vector<std::uint8_t>>& rows, const std::string& what) {
    std::vector<std::uint8_t> all;
    for (const auto& r : rows) all.insert(all.end(), r.begin(), r.end());
    for (std::size_t distance = 1; distance <= 4; ++distance) {
      std::vector<std::vector<std::uint8_t>> out(2);
      for (int scalar = 0; scalar < 2; ++scalar) {
        ForcePngScalar(scalar == 1);
        RunDeflater d;
        d.Reset(distance);
        for (const auto& r : rows) {
          std::vector<std::uint8_t> buf(kRowPadBefore + r.size() + kRowPadAfter, 0xA5);
          std::copy(r.begin(), r.end(), buf.begin() + kRowPadBefore);
          d.AddRow(buf.data() + kRowPadBefore, r.size());
        }
        d.Finish(out[scalar]);
      }
      ForcePngScalar(false);
      EXPECT_TRUE(out[0] == out[1]) << what << ", distance " << distance;
      std::vector<std::uint8_t> back(all.size() + 1);
      uLongf n = back.size();
      ASSERT_EQ(uncompress(back.data(), &n, out[0].data(), out[0].size()), Z_OK) << what;
      back.resize(n);
      EXPECT_TRUE(back == all) << what << ", distance " << distance;
    }
  };
  check({}, "nothing");
  check({{7}}, "one byte");
  check({std::vector<std::uint8_t>(100000, 0x42)}, "one symbol: a literal and matches");
  for (std::size_t n = 1; n < 800; n += (n < 270 ? 1 : 37))
    check({std::vector<std::uint8_t>(n, 0),
           {1, 2, 3},
           std::vector<std::uint8_t>(n + 1, 9),
           Noise(static_cast<int>(n), 1, static_cast<std::uint32_t>(n), true)},
          "runs of " + std::to_string(n));
}

TEST(PngEncoder, Adler32IsZlibs) {
  std::mt19937 rng(5);
  std::vector<std::size_t> lengths;
  for (std::size_t n = 0; n <= 130; ++n) lengths.push_back(n);
  for (std::size_t n : {5535, 5536, 5537, 5551, 5552, 5553, 11072, 11104, 11105, 100000, 3000001})
    lengths.push_back(n);
  for (std::size_t n : lengths)
    for (int fill = 0; fill < 3; ++fill) {
      std::vector<std::uint8_t> v(n + 1);  // + 1: never a null pointer (zlib's adler32 returns 1)
      for (auto& b : v) b = fill == 0 ? 0xFF : fill == 1 ? 0 : static_cast<std::uint8_t>(rng());
      for (std::uint32_t start : {1u, 0xFFF0FFF0u, 0x12345678u % 65521u}) {
        const std::uint32_t want =
            static_cast<std::uint32_t>(adler32(start, v.data(), static_cast<uInt>(n)));
        EXPECT_EQ(Adler32(start, v.data(), n), want) << n << " " << fill;
        ForcePngScalar(true);
        EXPECT_EQ(Adler32(start, v.data(), n), want) << n << " " << fill << " plain";
        ForcePngScalar(false);
      }
    }
}

}  // namespace
}  // namespace formsim::app
