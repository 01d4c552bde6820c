#pragma once
/// \file The ImGui context with our fonts and style, drawn by the OpenGL3 backend in the current
/// GL context (GLFW window or OSMesa buffer). Both modes go through the same calls, so identical
/// draw data gives identical pixels.

#include "app/fonts.hpp"

namespace formsim::app {

class ImGuiLayer {
 public:
  /// Creates the ImGui context, loads fonts, sets the light style and initialises the OpenGL3
  /// backend. A GL context must be current and loaded (LoadGl).
  ImGuiLayer();
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  /// Starts a frame without a platform backend (headless): display size and time step given.
  void NewHeadlessFrame(int width, int height, float dt);
  /// Starts a frame after the platform backend's NewFrame (GUI).
  void NewFrame();
  /// Ends the frame and draws it into the current framebuffer, cleared to `clear` first.
  void Render(int fb_width, int fb_height, float clear_r, float clear_g, float clear_b);

  const Fonts& fonts() const { return fonts_; }

 private:
  Fonts fonts_;
};

}  // namespace formsim::app
