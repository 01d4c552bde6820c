#pragma once
/// \file Animated GIF for slides through ffmpeg, with a palette made for the run: frames stream
/// to ffmpeg, which writes the palette of the whole run and a lossless copy of the frames (FFV1
/// in a temporary folder, so memory stays bounded however long the run); a second ffmpeg maps
/// the frames onto that palette and writes a looping GIF. The GIF appears only when both passes
/// succeeded.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace formsim::app {

class GifWriter {
 public:
  /// Starts ffmpeg for frames of `width` x `height` at `fps`; the GIF is `out_width` pixels wide
  /// (frames of another width are scaled, keeping the aspect). Throws std::runtime_error.
  GifWriter(const std::string& path, int width, int height, double fps, int out_width);
  ~GifWriter();
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;

  /// Appends one frame (RGBA, top row first, width*height*4 bytes).
  void Write(const std::vector<std::uint8_t>& rgba);
  /// Ends the stream, runs the palette pass and moves the GIF into place. Throws when ffmpeg
  /// failed (nothing is left at the path then).
  void Close();
  long frames() const { return frames_; }

  /// Checks the name (.gif), ffmpeg on PATH and the settings before anything is simulated.
  static void CheckAvailable(const std::string& path, double fps, int out_width);

 private:
  void Cleanup();
  std::FILE* pipe_ = nullptr;
  std::string path_, tmp_dir_;
  std::size_t frame_bytes_ = 0;
  double fps_;
  long frames_ = 0;
};

}  // namespace formsim::app
