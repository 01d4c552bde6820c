#pragma once
/// \file RGBA to planar YUV 4:2:0 (I420) as H.264 video stores it: BT.709, limited range, each
/// chroma sample the mean of a 2x2 block. Done here, not by ffmpeg: swscale's default
/// (bicubic) conversion took half of ffmpeg's CPU per frame, and the frame piped is 2.7x
/// smaller.

#include <cstddef>
#include <cstdint>

namespace formsim::app {

/// Converts `rgba` (width x height, top row first, alpha ignored) into `i420`: the Y plane
/// (width x height), then U and V (width/2 x height/2 each). Width and height must be even.
/// Integer arithmetic: the same bytes on every machine.
void RgbaToI420(const std::uint8_t* rgba, int width, int height, std::uint8_t* i420);

/// Bytes of an I420 frame of that (even) size.
inline std::size_t I420Bytes(int width, int height) {
  return static_cast<std::size_t>(width) * height * 3 / 2;
}

}  // namespace formsim::app
