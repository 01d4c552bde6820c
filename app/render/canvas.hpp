#pragma once
/// \file The one drawing interface of the world view and the plot widget: lines, polylines,
/// filled shapes, text and clipping in logical pixels (y down). ImGuiCanvas draws into an ImGui
/// draw list (the window, OSMesa frames and PNG figures); VectorCanvas records the same calls
/// for SVG and PDF. Figure code is written once, against this.

#include <imgui.h>

#include <array>
#include <string>
#include <vector>

#include "app/render/fonts.hpp"
#include "app/render/label_markup.hpp"
#include "sim/core/draw.hpp"

namespace formsim::app {

/// A dash pattern in pixels: on, off, on, off... (`count` entries; 0 = solid line).
struct LineDash {
  std::array<float, 4> lengths{};
  int count = 0;
  bool solid() const { return count == 0; }
  static LineDash Solid() { return {}; }
  static LineDash Dashes(float on, float off) { return {{on, off, 0, 0}, 2}; }
  static LineDash DashDot(float on, float gap, float dot) { return {{on, gap, dot, gap}, 4}; }
};

/// How a line is drawn.
struct Stroke {
  Stroke(sim::Color c, float w = 1.0f, LineDash d = LineDash::Solid())
      : color(c), width(w), dash(d) {}
  sim::Color color;
  float width;
  LineDash dash;
};

class Canvas {
 public:
  virtual ~Canvas() = default;

  /// Axis-aligned rectangle filled, corners rounded by `rounding` pixels.
  virtual void FillRect(ImVec2 min, ImVec2 max, sim::Color color, float rounding = 0) = 0;
  /// An opaque background under everything drawn after it: the same pixels as FillRect, which a
  /// GL canvas may produce more cheaply (a scissored clear instead of a shaded quad).
  virtual void FillBackground(ImVec2 min, ImVec2 max, sim::Color color) {
    FillRect(min, max, color);
  }
  /// Rectangle outline drawn inside [min, max].
  virtual void StrokeRect(ImVec2 min, ImVec2 max, sim::Color color, float width,
                          float rounding = 0) = 0;
  /// Open (or `closed`) polyline of `n` points.
  virtual void Polyline(const ImVec2* pts, int n, const Stroke& stroke, bool closed = false) = 0;
  /// Simple polygon (convex or not) filled.
  virtual void FillPolygon(const ImVec2* pts, int n, sim::Color color) = 0;
  /// The same without anti-aliased edges where the canvas has them: a shape a few pixels across
  /// in the window, whose outline is drawn over the edge anyway (level of detail).
  virtual void FillPolygonAliased(const ImVec2* pts, int n, sim::Color color) {
    FillPolygon(pts, n, color);
  }
  /// A filled polygon star-shaped from its first point (every point of it sees pts[0]), e.g. a
  /// robot's heading arrow, tip first; `cls` names what it is for vector files (SVG `class`).
  /// ImGui: anti-aliased triangles fanned from pts[0] (a concave arrow keeps smooth edges);
  /// vector canvases: one path. By default FillPolygon.
  virtual void FillFan(const ImVec2* pts, int n, sim::Color color, const std::string& /*cls*/) {
    FillPolygon(pts, n, color);
  }
  /// Opens a group of what is drawn until EndGroup (groups nest): vector canvases keep it (SVG
  /// `<g id class>`), so that a figure's parts (a robot) can be styled and found; others ignore
  /// it.
  virtual void BeginGroup(const std::string& /*id*/, const std::string& /*cls*/) {}
  virtual void EndGroup() {}
  /// The area between two curves sampled at the same x (upper[i].x == lower[i].x, ascending):
  /// a plot's band. The curves may touch or cross. By default the outline (upper forward, lower
  /// back) filled with the non-zero rule, which fills every lobe of a crossing band.
  virtual void FillBetween(const ImVec2* upper, const ImVec2* lower, int n, sim::Color color) {
    if (n < 2) return;
    std::vector<ImVec2> outline(upper, upper + n);
    for (int i = n; i-- > 0;) outline.push_back(lower[i]);
    FillPolygon(outline.data(), static_cast<int>(outline.size()), color);
  }
  virtual void FillCircle(ImVec2 center, float radius, sim::Color color) = 0;
  virtual void StrokeCircle(ImVec2 center, float radius, sim::Color color, float width) = 0;
  /// Text with the top-left corner of its line box at `pos` (ImGui's convention).
  virtual void Text(ImVec2 pos, FontRole font, sim::Color color, const std::string& text) = 0;
  /// Text rotated 90° counter-clockwise (reads bottom to top), centred on `center`: the usual
  /// y-axis label.
  void TextVertical(ImVec2 center, FontRole font, sim::Color color, const std::string& text) {
    DrawVertical(center, font, color, text, TextSize(font, text), false);
  }
  /// Width and line height of `text` in `font`, logical pixels.
  virtual ImVec2 TextSize(FontRole font, const std::string& text) const = 0;
  /// A label written with markup (label_markup.hpp), placed like Text. By default its Unicode
  /// form (MarkupText); vector canvases keep the runs (sub- and superscripts stay text).
  virtual void Label(ImVec2 pos, FontRole font, sim::Color color, const std::string& markup) {
    Text(pos, font, color, MarkupText(markup));
  }
  /// A markup label placed like TextVertical.
  void LabelVertical(ImVec2 center, FontRole font, sim::Color color, const std::string& markup) {
    DrawVertical(center, font, color, markup, LabelSize(font, markup), true);
  }
  /// Width and line height of a markup label as Label draws it.
  virtual ImVec2 LabelSize(FontRole font, const std::string& markup) const {
    return TextSize(font, MarkupText(markup));
  }
  /// Restricts drawing to [min, max] (intersected with the current clip) until PopClip.
  virtual void PushClip(ImVec2 min, ImVec2 max) = 0;
  virtual void PopClip() = 0;
  /// The rectangle drawing can currently reach (the innermost clip), logical pixels.
  virtual void Clip(ImVec2& min, ImVec2& max) const = 0;

  /// The line height of a font (its size in logical pixels).
  virtual float FontSize(FontRole font) const { return FontSpecOf(font).pixels; }
  void Line(ImVec2 a, ImVec2 b, const Stroke& stroke) {
    const ImVec2 p[2] = {a, b};
    Polyline(p, 2, stroke);
  }

 protected:
  /// What TextVertical and LabelVertical draw once measured: `text` (markup when `markup`), its
  /// line box `ext` centred on `center`, rotated 90° counter-clockwise about it.
  virtual void DrawVertical(ImVec2 center, FontRole font, sim::Color color, const std::string& text,
                            ImVec2 ext, bool markup) = 0;
};

}  // namespace formsim::app
