#include "app/render/offscreen_context.hpp"

#include <GL/osmesa.h>

#include <stdexcept>
#include <string>

#include "app/render/gl_api.hpp"

namespace formsim::app {

OffscreenContext::OffscreenContext(int width, int height) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (ctx == nullptr)
    throw std::runtime_error("OSMesa: cannot create an OpenGL 3.3 core context (libosmesa6)");
  context_ = ctx;
  Resize(width, height);
  // Pointers come from OSMesa itself, so they are valid in this context whatever else is linked.
  LoadGl(reinterpret_cast<GlGetProcAddress>(&OSMesaGetProcAddress), "OSMesa");
}

OffscreenContext::~OffscreenContext() {
  if (context_ != nullptr) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void OffscreenContext::Resize(int width, int height) {
  if (width <= 0 || height <= 0 || width > 8192 || height > 8192)
    throw std::runtime_error("offscreen size " + std::to_string(width) + "x" +
                             std::to_string(height) + " is out of range (1..8192)");
  width_ = width;
  height_ = height;
  if (buffers_.size() > 2 && buffers_.count({width, height}) == 0) buffers_.clear();
  buffer_ = &buffers_[{width, height}];
  buffer_->resize(static_cast<std::size_t>(width) * height * 4, 0);
  Bind();
}

void OffscreenContext::Bind() {
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), buffer_->data(), GL_UNSIGNED_BYTE,
                         width_, height_))
    throw std::runtime_error("OSMesa: cannot bind a " + std::to_string(width_) + "x" +
                             std::to_string(height_) + " buffer");
  // Row 0 of our buffer is the top of the image, as in PNG files.
  OSMesaPixelStore(OSMESA_Y_UP, 0);
}

void OffscreenContext::Finish() {
  GlFinish();
}

std::vector<std::uint8_t> OffscreenContext::TakePixels(std::vector<std::uint8_t> next) {
  std::vector<std::uint8_t> out = std::move(*buffer_);
  *buffer_ = std::move(next);
  buffer_->resize(static_cast<std::size_t>(width_) * height_ * 4);
  // OSMesa keeps its framebuffer (found again by format and size) and only copies into the
  // newly bound memory when a frame is finished.
  Bind();
  return out;
}

}  // namespace formsim::app
