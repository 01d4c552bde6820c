#pragma once
/// \file MP4 video by piping raw RGBA frames to ffmpeg (H.264, yuv420p).

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace formsim::app {

/// Full path of `program` found on PATH, or "" when absent.
std::string FindOnPath(const std::string& program);

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
  /// Ends the stream and waits for ffmpeg; throws when it failed.
  void Close();
  /// Checks everything VideoWriter needs, without starting anything (fail before simulating).
  static void CheckAvailable(int width, int height);

 private:
  std::FILE* pipe_ = nullptr;
  std::string path_;
  std::size_t frame_bytes_ = 0;
};

}  // namespace formsim::app
