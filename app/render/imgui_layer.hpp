#pragma once
/// \file The ImGui context with our fonts and style, drawn by the OpenGL3 backend in the current
/// GL context (GLFW window or OSMesa buffer). Both modes go through the same calls, so identical
/// draw data gives identical pixels.

#include "app/render/fonts.hpp"
#include "app/render/theme.hpp"

namespace formsim::app {

class ImGuiLayer {
 public:
  /// Creates the ImGui context, loads fonts, sets the style of `theme` and initialises the
  /// OpenGL3 backend. A GL context must be current and loaded (LoadGl).
  explicit ImGuiLayer(const Theme& theme = GetTheme(ThemeId::kLight));
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  /// Starts a frame without a platform backend (headless): display size in logical pixels, the
  /// framebuffer being `fonts().scale` times larger, and the time step.
  void NewHeadlessFrame(int width, int height, float dt);
  /// Starts a frame after the platform backend's NewFrame (GUI).
  void NewFrame();
  /// Ends the frame and draws it into the current framebuffer, cleared to `clear` first.
  void Render(int fb_width, int fb_height, float clear_r, float clear_g, float clear_b);
  /// Rasterises the fonts `scale` times larger than their logical size (between frames).
  void SetFontScale(float scale);
  /// Switches the panels' colours (between frames).
  void SetTheme(const Theme& theme);

  const Fonts& fonts() const { return fonts_; }
  /// Whether Render may clear the frame to its first background's colour and leave out clears
  /// that change nothing (clear_hoist.hpp; the same pixels). On by default; tests compare both.
  void SetHoistClears(bool on) { hoist_clears_ = on; }
  /// Whether the last Render did so.
  bool hoisted_clear() const { return hoisted_clear_; }
  /// How many background clears the last Render left out (the hoisted one, and those that would
  /// have written the colour already there).
  int skipped_clears() const { return skipped_clears_; }

 private:
  Fonts fonts_;
  bool hoist_clears_ = true;
  bool hoisted_clear_ = false;
  int skipped_clears_ = 0;
};

}  // namespace formsim::app
