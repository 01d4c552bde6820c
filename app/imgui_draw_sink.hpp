#pragma once
/// \file sim::DrawSink implemented over an ImGui draw list through a View: the one drawing path
/// of the world view, in the GUI window and in headless frames alike.

#include <imgui.h>

#include "app/view.hpp"
#include "sim/core/draw.hpp"

namespace formsim::app {

inline ImU32 ToImColor(sim::Color c) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a));
}

class ImDrawSink : public sim::DrawSink {
 public:
  /// `label_font` draws Text() labels; `line_scale` multiplies every line thickness.
  ImDrawSink(ImDrawList* list, const View& view, ImFont* label_font, float line_scale = 1.0f)
      : dl_(list), view_(view), font_(label_font), line_scale_(line_scale) {}

  void Polygon(const std::vector<Vec2>& pts, sim::Color fill, sim::Color outline) override;
  void Circle(Vec2 center, double radius, sim::Color fill, sim::Color outline) override;
  void Segment(Vec2 a, Vec2 b, sim::Color color, float thickness_px) override;
  void Polyline(const std::vector<Vec2>& pts, sim::Color color, float thickness_px,
                bool fade) override;
  void CovarianceEllipse(Vec2 center, double sxx, double sxy, double syy, double n_sigma,
                         sim::Color color) override;
  void Cross(Vec2 p, double size, sim::Color color) override;
  void Text(Vec2 p, const std::string& text, sim::Color color, float dx_px, float dy_px) override;
  void Flash(Vec2 p, double radius, sim::Color color, float age) override;
  double PixelsPerMetre() const override { return view_.scale; }
  void ViewBox(Vec2& lo, Vec2& hi) const override;

 private:
  void FillSimplePolygon(const std::vector<ImVec2>& pts, ImU32 col);
  /// Labels already drawn this frame: a label that would overlap one is skipped (zoomed-out
  /// views of many robots stay readable instead of turning into a smudge of text).
  std::vector<ImVec4> labels_;
  ImDrawList* dl_;
  const View& view_;
  ImFont* font_;
  float line_scale_;
};

}  // namespace formsim::app
