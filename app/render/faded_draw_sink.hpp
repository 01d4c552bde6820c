#pragma once
/// \file A sim::DrawSink that draws through another one with every colour faded: a pinned run
/// drawn over the live one in the world view. Labels and event flashes are left out (the live
/// run has them), so the overlay is the robots, trails and estimates only.

#include "sim/core/draw.hpp"

namespace formsim::app {

class FadedDrawSink : public sim::DrawSink {
 public:
  /// Every alpha is multiplied by `alpha` (0..1).
  FadedDrawSink(sim::DrawSink& inner, float alpha) : in_(inner), a_(alpha) {}

  void Polygon(const std::vector<Vec2>& pts, sim::Color fill, sim::Color outline) override {
    in_.Polygon(pts, Fade(fill), Fade(outline));
  }
  void Circle(Vec2 center, double radius, sim::Color fill, sim::Color outline) override {
    in_.Circle(center, radius, Fade(fill), Fade(outline));
  }
  void Segment(Vec2 a, Vec2 b, sim::Color color, float thickness_px) override {
    in_.Segment(a, b, Fade(color), thickness_px);
  }
  void Polyline(const std::vector<Vec2>& pts, sim::Color color, float thickness_px,
                bool fade) override {
    in_.Polyline(pts, Fade(color), thickness_px, fade);
  }
  void CovarianceEllipse(Vec2 center, double sxx, double sxy, double syy, double n_sigma,
                         sim::Color color) override {
    in_.CovarianceEllipse(center, sxx, sxy, syy, n_sigma, Fade(color));
  }
  void Cross(Vec2 p, double size, sim::Color color) override { in_.Cross(p, size, Fade(color)); }
  void Heading(const std::vector<Vec2>& pts, sim::Color fill, sim::Color body) override {
    in_.Heading(pts, Fade(fill), Fade(body));
  }
  void Text(Vec2, const std::string&, sim::Color, float, float) override {}
  void Flash(Vec2, double, sim::Color, float) override {}
  bool Shows(const std::string& name) const override { return in_.Shows(name); }
  bool AnglesInDegrees() const override { return in_.AnglesInDegrees(); }

 private:
  sim::Color Fade(sim::Color c) const { return c.WithAlpha(c.a * a_); }
  sim::DrawSink& in_;
  float a_;
};

}  // namespace formsim::app
