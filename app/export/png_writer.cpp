#include "app/export/png_writer.hpp"

#include <stb_image.h>
#include <zlib.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "app/export/png_deflate.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace formsim::app {
namespace {

void PutU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

void Chunk(std::vector<std::uint8_t>& out, const char* type, const std::uint8_t* data,
           std::size_t n) {
  PutU32(out, static_cast<std::uint32_t>(n));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + n);
  PutU32(out, static_cast<std::uint32_t>(crc32(0, out.data() + start, static_cast<uInt>(n + 4))));
}

#if defined(__x86_64__) || defined(__i386__)
#define FORMSIM_PNG_FILTER_X86 1
#endif

// a - b in each byte, without borrows between bytes (Hacker's Delight 2-18).
std::uint64_t SubBytes(std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t kHigh = 0x8080808080808080ull;
  return ((a | kHigh) - (b & ~kHigh)) ^ ((a ^ ~b) & kHigh);
}

// One row of the PNG: each byte minus the byte above (filter "up"; row 0: minus zeros), alpha
// dropped when `comp` is 3. Returns false when `comp` is 3 and a pixel of the row is not opaque.
// Two pixels at a time in a 64-bit word; `out` may be written up to 8 bytes past the row.
bool FilterUpScalar(const std::uint8_t* src, const std::uint8_t* above, int width, int comp,
                    std::uint8_t* out) {
  const std::size_t w = static_cast<std::size_t>(width);
  std::size_t x = 0;
  if (comp == 4) {
    for (; x + 2 <= w; x += 2)
      StoreLE64(out + 4 * x, SubBytes(LoadLE64(src + 4 * x), LoadLE64(above + 4 * x)));
    for (std::size_t i = 4 * x; i < 4 * w; ++i)
      out[i] = static_cast<std::uint8_t>(src[i] - above[i]);
    return true;
  }
  std::uint64_t alpha = ~std::uint64_t{0};
  for (; x + 2 <= w; x += 2) {
    const std::uint64_t s = LoadLE64(src + 4 * x), d = SubBytes(s, LoadLE64(above + 4 * x));
    alpha &= s;
    StoreLE64(out + 3 * x, (d & 0xFFFFFF) | ((d >> 8) & 0xFFFFFF000000ull));  // RGBRGB
  }
  bool opaque = (alpha & 0xFF000000FF000000ull) == 0xFF000000FF000000ull;
  for (; x < w; ++x) {
    for (int c = 0; c < 3; ++c)
      out[3 * x + c] = static_cast<std::uint8_t>(src[4 * x + c] - above[4 * x + c]);
    opaque = opaque && src[4 * x + 3] == 255;
  }
  return opaque;
}

#ifdef FORMSIM_PNG_FILTER_X86
// As FilterUpScalar, 8 pixels at a time. `out` may be written up to 8 bytes past the row.
__attribute__((target("avx2"))) bool FilterUpAvx2(const std::uint8_t* src,
                                                  const std::uint8_t* above, int width, int comp,
                                                  std::uint8_t* out) {
  int x = 0;
  if (comp == 4) {
    const std::size_t n = static_cast<std::size_t>(width) * 4;
    std::size_t i = 0;
    for (; i + 32 <= n; i += 32) {
      const __m256i s = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + i));
      const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(above + i));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i), _mm256_sub_epi8(s, a));
    }
    for (; i < n; ++i) out[i] = static_cast<std::uint8_t>(src[i] - above[i]);
    return true;
  }
  // RGBA to RGB: each 128-bit lane packs its 4 pixels into 12 bytes, then the two lanes' 12
  // bytes are moved together (dwords 0-2 and 4-6).
  const __m256i pack = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1, 0,
                                        1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
  const __m256i join = _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 7, 7);
  __m256i alpha = _mm256_set1_epi8(-1);
  for (; x + 8 <= width; x += 8) {
    const __m256i s = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + 4 * x));
    const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(above + 4 * x));
    alpha = _mm256_and_si256(alpha, s);
    const __m256i d = _mm256_shuffle_epi8(_mm256_sub_epi8(s, a), pack);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 3 * x),
                        _mm256_permutevar8x32_epi32(d, join));
  }
  const unsigned full =
      static_cast<unsigned>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(alpha, _mm256_set1_epi8(-1))));
  const bool opaque = (full & 0x88888888u) == 0x88888888u;
  return FilterUpScalar(src + 4 * x, above + 4 * x, width - x, 3, out + 3 * x) && opaque;
}
#endif

// The buffers of one thread, reused between images: each frame would otherwise allocate (and
// the kernel zero) megabytes.
struct PngBuffers {
  RunDeflater deflater;
  std::vector<std::uint8_t> row;    ///< one filtered row, with RunDeflater's padding
  std::vector<std::uint8_t> zeros;  ///< the row "above" row 0
};

// Buffers larger than this (a 4K picture or more) are let go after use.
constexpr std::size_t kKeepBytes = std::size_t{64} << 20;

}  // namespace

// PNG with every row under the "up" filter (our pictures are flat backgrounds and thin lines:
// rows repeat, so most filtered bytes are zero), deflated by RunDeflater (png_deflate.hpp) as
// the rows are filtered: the image is read once. A 1280x720 frame of formation_traj2 takes
// 0.7-0.8 ms (7.3 M instructions) against 6.5 ms (79 M) with zlib at level 2, for 1.25x the
// bytes (issue 28: exporting at 200 fps on 2 cores). Without AVX2 (and in the browser): 2.2 ms.
std::vector<std::uint8_t> EncodePng(int width, int height, const std::uint8_t* rgba, double dpi) {
  thread_local PngBuffers b;
  const std::size_t w = static_cast<std::size_t>(width);
  if (b.zeros.size() < 4 * w) b.zeros.resize(4 * w);  // never written: stays zero
  const bool avx2 = PngUsesAvx2();
  // RGB when nothing is transparent: 25 % less to compress. Known only at the end of the image,
  // so the rows are deflated as RGB and the image restarted as RGBA at the first row with alpha.
  bool opaque = true;
  for (bool again = true; again;) {
    again = false;
    const int comp = opaque ? 3 : 4;
    const std::size_t stride = w * comp;
    b.row.resize(kRowPadBefore + stride + 1 + kRowPadAfter);
    std::uint8_t* row = b.row.data() + kRowPadBefore;
    row[0] = 2;              // filter type "up"
    b.deflater.Reset(comp);  // matches repeat the pixel before
    for (int y = 0; y < height; ++y) {
      const std::uint8_t* src = rgba + static_cast<std::size_t>(y) * w * 4;
      const std::uint8_t* above = y > 0 ? src - w * 4 : b.zeros.data();
#ifdef FORMSIM_PNG_FILTER_X86
      const bool row_opaque = avx2 ? FilterUpAvx2(src, above, width, comp, row + 1)
                                   : FilterUpScalar(src, above, width, comp, row + 1);
#else
      const bool row_opaque = FilterUpScalar(src, above, width, comp, row + 1);
#endif
      if (!row_opaque) {
        opaque = false;
        again = true;
        break;
      }
      b.deflater.AddRow(row, stride + 1);
    }
  }
  (void)avx2;

  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  PutU32(ihdr, static_cast<std::uint32_t>(width));
  PutU32(ihdr, static_cast<std::uint32_t>(height));
  ihdr.insert(ihdr.end(), {8, static_cast<std::uint8_t>(opaque ? 2 : 6), 0, 0, 0});
  Chunk(png, "IHDR", ihdr.data(), ihdr.size());
  if (dpi > 0) {
    std::vector<std::uint8_t> phys;
    const auto per_metre = static_cast<std::uint32_t>(std::lround(dpi / 0.0254));
    PutU32(phys, per_metre);
    PutU32(phys, per_metre);
    phys.push_back(1);  // unit: metre
    Chunk(png, "pHYs", phys.data(), phys.size());
  }
  // IDAT, the zlib stream written in place: its length is known once it is written.
  const std::size_t idat = png.size();
  PutU32(png, 0);
  png.insert(png.end(), {'I', 'D', 'A', 'T'});
  b.deflater.Finish(png);
  const std::size_t zn = png.size() - idat - 8;
  for (int k = 0; k < 4; ++k) png[idat + k] = static_cast<std::uint8_t>(zn >> (24 - 8 * k));
  PutU32(png,
         static_cast<std::uint32_t>(crc32(0, png.data() + idat + 4, static_cast<uInt>(zn + 4))));
  Chunk(png, "IEND", nullptr, 0);
  b.deflater.Trim(kKeepBytes);
  if (b.row.capacity() > kKeepBytes) std::vector<std::uint8_t>().swap(b.row);
  if (b.zeros.capacity() > kKeepBytes) std::vector<std::uint8_t>().swap(b.zeros);
  return png;
}

double WritePng(const std::string& path, int width, int height, const std::uint8_t* rgba,
                double dpi) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<std::uint8_t> png = EncodePng(width, height, rgba, dpi);
  // A device or pipe (/dev/full, /dev/stdout) is written as it is: never renamed over.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr)
      throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    const bool ok = std::fwrite(png.data(), 1, png.size(), f) == png.size() && std::fflush(f) == 0;
    const std::string why = std::strerror(errno);
    if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write " + path + ": " + why);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  // Through a temporary name: a failed write (full disk) leaves no truncated PNG behind.
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  const bool ok = std::fwrite(png.data(), 1, png.size(), f) == png.size() && std::fflush(f) == 0;
  const std::string why = std::strerror(errno);
  if (std::fclose(f) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<std::uint8_t> ReadPng(const std::string& path, int* width, int* height) {
  int comp = 0;
  unsigned char* data = stbi_load(path.c_str(), width, height, &comp, 4);
  if (data == nullptr) throw std::runtime_error("cannot read PNG " + path);
  std::vector<std::uint8_t> out(data, data + static_cast<std::size_t>(*width) * *height * 4);
  stbi_image_free(data);
  return out;
}

PngPool::PngPool(int threads, std::size_t max_queued) : max_queued_(max_queued) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { Work(); });
}

PngPool::~PngPool() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  space_.notify_all();
  for (auto& t : workers_) t.join();
}

void PngPool::Submit(std::string path, int width, int height, std::vector<std::uint8_t> rgba) {
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mu_);
  space_.wait(lock, [&] { return queue_.size() < max_queued_ || !error_.empty(); });
  blocked_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!error_.empty()) throw std::runtime_error(error_);
  queue_.push_back({std::move(path), width, height, std::move(rgba)});
  lock.unlock();
  cv_.notify_one();
}

std::vector<std::uint8_t> PngPool::Spare() {
  std::vector<std::uint8_t> out;
  std::lock_guard<std::mutex> lock(mu_);
  if (!spare_.empty()) {
    out = std::move(spare_.back());
    spare_.pop_back();
  }
  return out;
}

std::vector<std::uint8_t> PngPool::Copy(const std::vector<std::uint8_t>& rgba) {
  std::vector<std::uint8_t> out = Spare();
  out.assign(rgba.begin(), rgba.end());
  return out;
}

void PngPool::Wait() {
  std::unique_lock<std::mutex> lock(mu_);
  idle_.wait(lock, [&] { return (queue_.empty() && busy_ == 0) || !error_.empty(); });
  if (!error_.empty()) throw std::runtime_error(error_);
}

double PngPool::encode_seconds() const {
  std::lock_guard<std::mutex> lock(mu_);
  return encode_;
}

long PngPool::written() const {
  std::lock_guard<std::mutex> lock(mu_);
  return written_;
}

void PngPool::Work() {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mu_);
      cv_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping
      job = std::move(queue_.front());
      queue_.pop_front();
      ++busy_;
    }
    space_.notify_one();
    double secs = 0;
    std::string err;
    try {
      secs = WritePng(job.path, job.w, job.h, job.px.data());
    } catch (const std::exception& e) {
      err = e.what();
    }
    {
      std::lock_guard<std::mutex> lock(mu_);
      --busy_;
      encode_ += secs;
      if (spare_.size() < max_queued_) spare_.push_back(std::move(job.px));
      if (err.empty())
        ++written_;
      else if (error_.empty())
        error_ = err;
    }
    idle_.notify_all();
    space_.notify_all();
  }
}

}  // namespace formsim::app
