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

// One deflate stream and its buffers per thread, reset between images: each frame would
// otherwise allocate (and the kernel zero) megabytes.
struct Deflater {
  Deflater() {
    // Level 2 with memLevel 7 (a 32 k-entry hash): on our frames 7 % less CPU than memLevel 8
    // for 0.3 % more bytes. libdeflate was measured too (issue 28): its level 1 takes 1.6x the
    // CPU of this on our long runs of zeros (it hashes every byte inside a match), its
    // higher levels more.
    if (deflateInit2(&zs, 2, Z_DEFLATED, 15, 7, Z_DEFAULT_STRATEGY) != Z_OK)
      throw std::runtime_error("zlib deflateInit failed");
  }
  ~Deflater() { deflateEnd(&zs); }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;
  z_stream zs{};
  std::vector<std::uint8_t> raw, z;  ///< filtered rows, compressed stream
};

// Buffers larger than this (a 4K picture or more) are let go after use.
constexpr std::size_t kKeepBytes = std::size_t{64} << 20;

}  // namespace

// PNG with every row under the "up" filter (our pictures are flat backgrounds and thin lines:
// rows repeat) compressed by zlib at level 2: 2-3x faster than stb_image_write's encoder at a
// similar size, which matters when frames are exported at 30 fps.
std::vector<std::uint8_t> EncodePng(int width, int height, const std::uint8_t* rgba, double dpi) {
  thread_local Deflater d;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  bool opaque = true;
  for (std::size_t i = 0; i < n && opaque; ++i) opaque = rgba[4 * i + 3] == 255;
  const int comp = opaque ? 3 : 4;  // RGB when nothing is transparent: 25 % less to compress
  const std::size_t stride = static_cast<std::size_t>(width) * comp;
  std::vector<std::uint8_t>& raw = d.raw;
  raw.resize((stride + 1) * height);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* src = rgba + static_cast<std::size_t>(y) * width * 4;
    const std::uint8_t* above = y > 0 ? src - static_cast<std::size_t>(width) * 4 : nullptr;
    std::uint8_t* out = &raw[y * (stride + 1)];
    out[0] = 2;  // filter type "up": the difference to the pixel above (row 0: to zero)
    ++out;
    if (above == nullptr) {
      for (int x = 0; x < width; ++x)
        for (int c = 0; c < comp; ++c) out[comp * x + c] = src[4 * x + c];
    } else if (opaque) {
      for (int x = 0; x < width; ++x) {
        out[3 * x] = static_cast<std::uint8_t>(src[4 * x] - above[4 * x]);
        out[3 * x + 1] = static_cast<std::uint8_t>(src[4 * x + 1] - above[4 * x + 1]);
        out[3 * x + 2] = static_cast<std::uint8_t>(src[4 * x + 2] - above[4 * x + 2]);
      }
    } else {
      for (std::size_t i = 0; i < stride; ++i)
        out[i] = static_cast<std::uint8_t>(src[i] - above[i]);
    }
  }

  z_stream& zs = d.zs;
  if (deflateReset(&zs) != Z_OK) throw std::runtime_error("zlib deflateReset failed");
  d.z.resize(deflateBound(&zs, static_cast<uLong>(raw.size())));
  zs.next_in = raw.data();
  zs.avail_in = static_cast<uInt>(raw.size());
  zs.next_out = d.z.data();
  zs.avail_out = static_cast<uInt>(d.z.size());
  const int rc = deflate(&zs, Z_FINISH);
  const std::size_t zn = zs.total_out;
  if (rc != Z_STREAM_END) throw std::runtime_error("zlib deflate failed");

  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  png.reserve(zn + 80);
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
  Chunk(png, "IDAT", d.z.data(), zn);
  if (raw.capacity() > kKeepBytes) {
    std::vector<std::uint8_t>().swap(raw);
    std::vector<std::uint8_t>().swap(d.z);
  }
  Chunk(png, "IEND", nullptr, 0);
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
    if (f == nullptr) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
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

std::vector<std::uint8_t> PngPool::Copy(const std::vector<std::uint8_t>& rgba) {
  std::vector<std::uint8_t> out;
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (!spare_.empty()) {
      out = std::move(spare_.back());
      spare_.pop_back();
    }
  }
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
