#pragma once
/// \file Canvas over an ImGui draw list: what the GUI window, headless frames and PNG figures are
/// drawn with. Dashes are cut into segments, concave polygons ear-clipped, vertical text rotated
/// vertex by vertex (ImGui has none of these).

#include <imgui.h>

#include <cstdint>

#include "app/render/canvas.hpp"
#include "app/render/fonts.hpp"

namespace formsim::app {

/// Draws `markup`'s runs (label_markup.hpp's AtlasRuns) with its top left at `pos`, in font `f`
/// at `size`: each run's baseline is the line's, moved by its shift. y is rounded to 1/`snap`
/// (x too with `snap_x`). The window's label items and ImGuiCanvas::Label share it.
void DrawMarkupRuns(ImDrawList* dl, ImFont* f, float size, ImVec2 pos, ImU32 col,
                    const std::string& markup, float snap, bool snap_x);
/// The width DrawMarkupRuns takes for `markup` in `f` at `size`.
float MarkupRunsWidth(ImFont* f, float size, const std::string& markup);

inline ImU32 ToImColor(sim::Color c) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a));
}

class ImGuiCanvas : public Canvas {
 public:
  /// Draws into `list` with `fonts` (whose `scale` says how much larger than logical size the
  /// atlas is; text is drawn at logical size). `list` must outlive the canvas.
  ImGuiCanvas(ImDrawList* list, const Fonts& fonts);

  void FillRect(ImVec2 min, ImVec2 max, sim::Color color, float rounding) override;
  /// On whole framebuffer pixels, a draw callback that clears the rectangle (scissored) to the
  /// colour: llvmpipe runs the textured fragment shader for every pixel of a quad, while a
  /// clear is a fill. The pixels are the same (tested); elsewhere a FillRect.
  void FillBackground(ImVec2 min, ImVec2 max, sim::Color color) override;
  void StrokeRect(ImVec2 min, ImVec2 max, sim::Color color, float width, float rounding) override;
  void Polyline(const ImVec2* pts, int n, const Stroke& stroke, bool closed) override;
  void FillPolygon(const ImVec2* pts, int n, sim::Color color) override;
  /// ImGui's fill without its one-pixel fringe of anti-aliasing triangles.
  void FillPolygonAliased(const ImVec2* pts, int n, sim::Color color) override;
  void FillBetween(const ImVec2* upper, const ImVec2* lower, int n, sim::Color color) override;
  /// Each triangle of the fan through ImGui's anti-aliased convex fill, wound as it wants.
  void FillFan(const ImVec2* pts, int n, sim::Color color, const std::string& cls) override;
  void FillCircle(ImVec2 center, float radius, sim::Color color) override;
  void StrokeCircle(ImVec2 center, float radius, sim::Color color, float width) override;
  void Text(ImVec2 pos, FontRole font, sim::Color color, const std::string& text) override;
  float FontSize(FontRole font) const override;
  ImVec2 TextSize(FontRole font, const std::string& text) const override;
  /// Markup: Unicode scripts where the atlas has them, other scripts smaller on a shifted
  /// baseline (label_markup.hpp's AtlasRuns).
  void Label(ImVec2 pos, FontRole font, sim::Color color, const std::string& markup) override;
  ImVec2 LabelSize(FontRole font, const std::string& markup) const override;
  void PushClip(ImVec2 min, ImVec2 max) override;
  void PopClip() override;
  void Clip(ImVec2& min, ImVec2& max) const override {
    min = dl_->GetClipRectMin();
    max = dl_->GetClipRectMax();
  }

  /// FillBackground as a clear (true) or always as a quad (false: a draw list that is not rendered
  /// by the GL backend, or kept and appended again later).
  void SetClearBackgrounds(bool on) { clear_backgrounds_ = on; }
  /// Strokes on whole pixels (the window's level of detail): at a one-to-one framebuffer scale a
  /// stroke of whole-pixel width is drawn by ImGui from its baked anti-aliased line texture, two
  /// triangles a segment instead of six, which a software rasteriser pays for per triangle.
  /// Widths round to the nearest whole pixel, at least one. Off: exported frames and figures
  /// keep their widths.
  void SetWholePixelLines(bool on) { whole_pixel_lines_ = on; }

 private:
  /// The width a stroke is drawn with: `width`, or on whole pixels (SetWholePixelLines).
  float StrokeWidth(float width) const;
  bool clear_backgrounds_ = true;
  bool whole_pixel_lines_ = false;
  /// Draws the text flat (Text or Label), then turns the vertices it added 90°
  /// counter-clockwise about `center`: ImGui has no rotated text.
  void DrawVertical(ImVec2 center, FontRole font, sim::Color color, const std::string& text,
                    ImVec2 ext, bool markup) override;
  void DashedPolyline(const ImVec2* pts, int n, ImU32 col, float width, const LineDash& dash);
  ImDrawList* dl_;
  const Fonts& fonts_;
};

/// A FillBackground done as a clear: its rectangle in framebuffer pixels (x0, y0 the top-left
/// pixel, x1, y1 one past the bottom-right, rows counted from the top) and its packed colour.
struct BackgroundClear {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  std::uint32_t rgba = 0;
};
/// Whether `cmd` of `dd` is such a clear, and which.
bool DecodeBackgroundClear(const ImDrawData& dd, const ImDrawCmd& cmd, BackgroundClear* out);
/// Turns such a clear into a command that does nothing (it was done before the frame's draws).
void SkipBackgroundClear(ImDrawCmd& cmd);
/// Whether `cmd` is a clear that SkipBackgroundClear turned into nothing.
bool IsSkippedBackgroundClear(const ImDrawCmd& cmd);

}  // namespace formsim::app
