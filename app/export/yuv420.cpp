#include "app/export/yuv420.hpp"

#include <cstddef>

namespace formsim::app {
namespace {

// BT.709 in limited range, scaled by 2^16: Y = 16 + 219/255 (0.2126 R + 0.7152 G + 0.0722 B),
// Cb = 128 + 224/255 (B - Y') / 1.8556, Cr = 128 + 224/255 (R - Y') / 1.5748. The chroma rows
// sum to zero (grey has no colour) and the luma row to 219/255.
constexpr int kYr = 11966, kYg = 40254, kYb = 4064;
constexpr int kUr = -6597, kUg = -22187, kUb = 28784;
constexpr int kVr = 28784, kVg = -26147, kVb = -2637;
static_assert(kUr + kUg + kUb == 0 && kVr + kVg + kVb == 0, "grey must have no chroma");

// A pixel as one 32-bit word (R in the low byte on little- and big-endian alike: assembled
// from the bytes), so that the loops below run in SIMD lanes.
inline std::uint32_t Pixel(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16;
}

inline std::uint8_t Luma(std::uint32_t px) {
  const int r = static_cast<int>(px & 0xFF), g = static_cast<int>(px >> 8 & 0xFF),
            b = static_cast<int>(px >> 16 & 0xFF);
  return static_cast<std::uint8_t>((kYr * r + kYg * g + kYb * b + (16 << 16) + (1 << 15)) >> 16);
}

// With AVX2 (chosen at load time where the CPU has it) the loops below run 8 pixels a step
// with 32-bit multiplies; SSE2 has none and takes ~2.5x the instructions. Integer arithmetic:
// the same bytes either way.
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
#define FORMSIM_YUV_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define FORMSIM_YUV_CLONES
#endif

}  // namespace

FORMSIM_YUV_CLONES void RgbaToI420(const std::uint8_t* rgba, int width, int height,
                                   std::uint8_t* i420) {
  const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  std::uint8_t* y_plane = i420;
  std::uint8_t* u_plane = i420 + w * h;
  std::uint8_t* v_plane = u_plane + (w / 2) * (h / 2);
  // Two rows at a time: their luma, and one row of chroma from the 2x2 blocks they make.
  for (std::size_t r = 0; r + 1 < h; r += 2) {
    const std::uint8_t* a = rgba + r * w * 4;
    const std::uint8_t* b = a + w * 4;
    std::uint8_t* ya = y_plane + r * w;
    std::uint8_t* yb = ya + w;
    std::uint8_t* u = u_plane + (r / 2) * (w / 2);
    std::uint8_t* v = v_plane + (r / 2) * (w / 2);
    for (std::size_t x = 0; x < w; ++x) ya[x] = Luma(Pixel(a + 4 * x));
    for (std::size_t x = 0; x < w; ++x) yb[x] = Luma(Pixel(b + 4 * x));
    for (std::size_t k = 0; k < w / 2; ++k) {
      const std::uint32_t p0 = Pixel(a + 8 * k), p1 = Pixel(a + 8 * k + 4);
      const std::uint32_t q0 = Pixel(b + 8 * k), q1 = Pixel(b + 8 * k + 4);
      auto sum = [&](int shift) {
        return static_cast<int>((p0 >> shift & 0xFF) + (p1 >> shift & 0xFF) + (q0 >> shift & 0xFF) +
                                (q1 >> shift & 0xFF));
      };
      const int sr = sum(0), sg = sum(8), sb = sum(16);
      // Sums of four: the scale is 2^18, rounded.
      u[k] = static_cast<std::uint8_t>((kUr * sr + kUg * sg + kUb * sb + (128 << 18) + (1 << 17)) >>
                                       18);
      v[k] = static_cast<std::uint8_t>((kVr * sr + kVg * sg + kVb * sb + (128 << 18) + (1 << 17)) >>
                                       18);
    }
  }
}

}  // namespace formsim::app
