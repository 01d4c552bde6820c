#pragma once
/// \file An OSMesa (software, no display) OpenGL 3.3 core context rendering into our own RGBA
/// buffer. The only file that includes GL/osmesa.h is offscreen_context.cpp (it clashes with the
/// loader header that the rest of app uses).

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace formsim::app {

class OffscreenContext {
 public:
  /// Creates the context, binds a width x height buffer, loads the GL pointers.
  /// Throws std::runtime_error when OSMesa cannot give a 3.3 core context.
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  /// Rebinds the context to a buffer of a new size (e.g. figures after frames). The buffers of
  /// the last sizes are kept, so alternating between two sizes (video and GIF frames) costs no
  /// allocation.
  void Resize(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  /// The rendered image, RGBA, top row first, valid after Finish().
  const std::vector<std::uint8_t>& pixels() const { return *buffer_; }
  /// Waits for rendering to complete.
  void Finish();
  /// Hands the rendered image over without copying it; `next` (its contents do not matter:
  /// OSMesa writes every pixel of the bound buffer when a frame is finished) becomes the buffer
  /// the following frames are rendered into.
  std::vector<std::uint8_t> TakePixels(std::vector<std::uint8_t> next);

 private:
  void Bind();
  void* context_ = nullptr;
  std::map<std::pair<int, int>, std::vector<std::uint8_t>> buffers_;  ///< by size
  std::vector<std::uint8_t>* buffer_ = nullptr;                       ///< the bound one
  int width_ = 0, height_ = 0;
};

}  // namespace formsim::app
