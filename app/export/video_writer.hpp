#pragma once
/// \file Video by piping raw frames to ffmpeg: MP4 (also .mkv, .mov) in H.264 yuv420p, BT.709.
/// The frames are converted to I420 here and written to ffmpeg by a thread of the writer's own,
/// so rendering goes on while ffmpeg reads. The file appears only when ffmpeg succeeded: it is
/// written under a temporary name and renamed.

#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace formsim::app {

/// Full path of `program` found on PATH, or "" when absent.
std::string FindOnPath(const std::string& program);

/// Quotes `s` for /bin/sh.
std::string ShellQuote(const std::string& s);

/// A temporary name next to `path` with the same extension: "dir/.name.partial.ext".
std::string PartialPath(const std::string& path);

/// After ffmpeg ended with `status` (from pclose or system) writing `partial`: moves it to
/// `path` when ffmpeg succeeded, else removes it; throws std::runtime_error naming `path` when
/// ffmpeg failed or the file could not be moved. Nothing is left at either name on failure.
void FinishPartial(int status, const std::string& partial, const std::string& path);

class VideoWriter {
 public:
  /// Checks that ffmpeg is on PATH and the size is even (yuv420p), then starts it writing `path`.
  /// Throws std::runtime_error with a clear message otherwise.
  VideoWriter(const std::string& path, int width, int height, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends one frame (RGBA, top row first, width*height*4 bytes): converted to I420 and
  /// queued; blocks while two frames wait. Throws when ffmpeg stopped taking frames.
  void Write(const std::vector<std::uint8_t>& rgba);
  /// Ends the stream, waits for ffmpeg and moves the file into place; throws when it failed
  /// (nothing is left at the path then).
  void Close();
  /// Checks everything VideoWriter needs, without starting anything (fail before simulating):
  /// ffmpeg, an even size and a video extension (.mp4, .mkv, .mov; a .gif is sent to --gif).
  static void CheckAvailable(const std::string& path, int width, int height);

 private:
  void Pump();        ///< the writer thread: queued frames into the pipe, in order
  void StopPump();    ///< the writer thread finishes what is queued and ends
  std::FILE* pipe_ = nullptr;
  std::string path_, partial_;
  int width_ = 0, height_ = 0;
  std::size_t frame_bytes_ = 0;
  // Frames in I420 between Write and the writer thread: at most two wait, and written
  // buffers are reused (a new megabyte-sized buffer per frame costs page faults).
  std::vector<std::vector<std::uint8_t>> queue_, spare_;
  std::mutex mu_;
  std::condition_variable queued_, taken_;
  bool stop_ = false, failed_ = false;
  std::thread pump_;
};

}  // namespace formsim::app
