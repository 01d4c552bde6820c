#pragma once
/// \file Video by piping raw RGBA frames to ffmpeg: MP4 (also .mkv, .mov) in H.264 yuv420p. The
/// file appears only when ffmpeg succeeded: it is written under a temporary name and renamed.

#include <cstdint>
#include <cstdio>
#include <string>
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

  /// Appends one frame (RGBA, top row first, width*height*4 bytes).
  void Write(const std::vector<std::uint8_t>& rgba);
  /// Ends the stream, waits for ffmpeg and moves the file into place; throws when it failed
  /// (nothing is left at the path then).
  void Close();
  /// Checks everything VideoWriter needs, without starting anything (fail before simulating):
  /// ffmpeg, an even size and a video extension (.mp4, .mkv, .mov; a .gif is sent to --gif).
  static void CheckAvailable(const std::string& path, int width, int height);

 private:
  std::FILE* pipe_ = nullptr;
  std::string path_, partial_;
  std::size_t frame_bytes_ = 0;
};

}  // namespace formsim::app
