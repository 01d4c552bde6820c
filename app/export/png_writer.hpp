#pragma once
/// \file PNG files from RGBA pixels (our own deflate, png_deflate.hpp; read back with stb_image),
/// and a pool of worker threads that encodes frames while the next one renders, using every core.

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace formsim::app {

/// Encodes an RGBA image (top row first) as PNG bytes (RGB when every pixel is opaque).
/// `dpi` > 0 records the resolution (pHYs), so documents place the picture at its printed size.
std::vector<std::uint8_t> EncodePng(int width, int height, const std::uint8_t* rgba,
                                    double dpi = 0);

/// Encodes an RGBA image (top row first) as PNG (RGB when every pixel is opaque) and writes it.
/// Throws std::runtime_error naming the file on failure. Returns the encoding time in seconds.
double WritePng(const std::string& path, int width, int height, const std::uint8_t* rgba,
                double dpi = 0);

/// Decodes a PNG file into RGBA (for tests and tools). Throws on failure.
std::vector<std::uint8_t> ReadPng(const std::string& path, int* width, int* height);

class PngPool {
 public:
  /// `threads` <= 0: one per hardware thread. At most `max_queued` images wait (memory bound).
  explicit PngPool(int threads = 0, std::size_t max_queued = 6);
  ~PngPool();
  PngPool(const PngPool&) = delete;
  PngPool& operator=(const PngPool&) = delete;

  /// Queues an image; blocks while the queue is full. Rethrows a worker's earlier error.
  void Submit(std::string path, int width, int height, std::vector<std::uint8_t> rgba);
  /// A copy of `rgba` in the buffer of an image already written, when there is one: a new
  /// megabyte-sized buffer per frame costs page faults.
  std::vector<std::uint8_t> Copy(const std::vector<std::uint8_t>& rgba);
  /// The buffer of an image already written (its old pixels), or an empty one.
  std::vector<std::uint8_t> Spare();
  /// Waits until everything queued is written. Rethrows the first worker error.
  void Wait();
  int threads() const { return static_cast<int>(workers_.size()); }
  /// Summed encode time of all workers, seconds (CPU-side, for --timing).
  double encode_seconds() const;
  /// Time Submit spent blocked on a full queue, seconds.
  double blocked_seconds() const { return blocked_; }
  long written() const;

 private:
  struct Job {
    std::string path;
    int w, h;
    std::vector<std::uint8_t> px;
  };
  void Work();
  std::vector<std::thread> workers_;
  std::deque<Job> queue_;
  std::vector<std::vector<std::uint8_t>> spare_;  ///< buffers of written images, for Copy
  mutable std::mutex mu_;
  std::condition_variable cv_, space_, idle_;
  std::size_t max_queued_;
  int busy_ = 0;
  bool stop_ = false;
  std::string error_;
  double encode_ = 0, blocked_ = 0;
  long written_ = 0;
};

}  // namespace formsim::app
