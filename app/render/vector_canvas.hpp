#pragma once
/// \file A Canvas that records what is drawn (a VectorFigure), for SVG and PDF: lines stay
/// paths, text stays text, measured with the same fonts and metrics as the PNG twin.

#include <string>
#include <vector>

#include "app/render/canvas.hpp"

namespace formsim::app {

/// One recorded drawing call.
struct VectorOp {
  enum class Kind {
    kFillRect,
    kStrokeRect,
    kPath,
    kFillPath,
    kFillCircle,
    kStrokeCircle,
    kText,
    kPushClip,
    kPopClip,
    kBeginGroup,  ///< text: the group's id, cls: its class
    kEndGroup
  };
  Kind kind = Kind::kFillRect;
  std::vector<ImVec2> pts;  ///< rect: min, max; path: its points; circle, text: one point
  sim::Color color;
  float width = 0;  ///< stroke width
  float size = 0;   ///< rounding (rects), radius (circles)
  bool closed = false;
  LineDash dash;
  FontRole font = FontRole::kUi;
  bool vertical = false;  ///< text rotated 90° counter-clockwise about pts[0]
  std::string text;       ///< text: pts[0] is the left end of the baseline (before rotating)
  bool markup = false;    ///< `text` is label markup: drawn as its runs (ParseMarkup)
  std::string cls;        ///< fill path, group: what it is (SVG `class`, e.g. "heading")
};

/// A figure as drawing calls in logical pixels (1/96 inch), y down.
struct VectorFigure {
  float width = 0, height = 0;
  std::vector<VectorOp> ops;
};

class VectorCanvas : public Canvas {
 public:
  /// Records onto a `width` x `height` figure. Throws when the fonts are missing.
  VectorCanvas(float width, float height);

  void FillRect(ImVec2 min, ImVec2 max, sim::Color color, float rounding) override;
  void StrokeRect(ImVec2 min, ImVec2 max, sim::Color color, float width, float rounding) override;
  void Polyline(const ImVec2* pts, int n, const Stroke& stroke, bool closed) override;
  void FillPolygon(const ImVec2* pts, int n, sim::Color color) override;
  void FillFan(const ImVec2* pts, int n, sim::Color color, const std::string& cls) override;
  void BeginGroup(const std::string& id, const std::string& cls) override;
  void EndGroup() override;
  void FillCircle(ImVec2 center, float radius, sim::Color color) override;
  void StrokeCircle(ImVec2 center, float radius, sim::Color color, float width) override;
  void Text(ImVec2 pos, FontRole font, sim::Color color, const std::string& text) override;
  ImVec2 TextSize(FontRole font, const std::string& text) const override;
  void Label(ImVec2 pos, FontRole font, sim::Color color, const std::string& markup) override;
  ImVec2 LabelSize(FontRole font, const std::string& markup) const override;
  void PushClip(ImVec2 min, ImVec2 max) override;
  void PopClip() override;
  void Clip(ImVec2& min, ImVec2& max) const override;

  const VectorFigure& figure() const { return fig_; }
  VectorFigure Take() { return std::move(fig_); }

 private:
  VectorOp& Add(VectorOp::Kind kind, sim::Color color);
  /// A text op rotated 90° counter-clockwise about `center`, `ext` its measured size.
  void DrawVertical(ImVec2 center, FontRole font, sim::Color color, const std::string& text,
                    ImVec2 ext, bool markup) override;
  VectorFigure fig_;
  /// The figure's rectangle, then each pushed clip intersected with the one before.
  std::vector<ImVec4> clips_;
};

}  // namespace formsim::app
