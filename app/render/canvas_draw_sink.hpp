#pragma once
/// \file sim::DrawSink implemented on a Canvas through a View: the one drawing path of the world
/// view, in the GUI window, headless frames, and SVG / PDF snapshots alike. The theme decides
/// how the experiment's colours are shown.

#include <set>
#include <string>
#include <vector>

#include "app/render/canvas.hpp"
#include "app/render/theme.hpp"
#include "app/render/view.hpp"
#include "sim/core/draw.hpp"

namespace formsim::app {

class CanvasDrawSink : public sim::DrawSink {
 public:
  /// Text() labels use `label_font`; every line thickness is multiplied by the theme's scale.
  CanvasDrawSink(Canvas& canvas, const View& view, const Theme& theme,
                 FontRole label_font = FontRole::kSmall)
      : cv_(canvas), view_(view), theme_(theme), font_(label_font) {}

  void Polygon(const std::vector<Vec2>& pts, sim::Color fill, sim::Color outline) override;
  void Circle(Vec2 center, double radius, sim::Color fill, sim::Color outline) override;
  void Segment(Vec2 a, Vec2 b, sim::Color color, float thickness_px) override;
  void Polyline(const std::vector<Vec2>& pts, sim::Color color, float thickness_px,
                bool fade) override;
  void CovarianceEllipse(Vec2 center, double sxx, double sxy, double syy, double n_sigma,
                         sim::Color color) override;
  void Cross(Vec2 p, double size, sim::Color color) override;
  /// Labels are queued and drawn by FlushLabels(), names first, then links, then values.
  void Text(Vec2 p, const std::string& text, sim::Color color, float dx_px, float dy_px) override;
  void Label(Vec2 p, const std::string& text, sim::Color color, sim::LabelRole role, float dx_px,
             float dy_px) override;
  void Flash(Vec2 p, double radius, sim::Color color, float age) override;
  /// The theme's HeadingInk() of `body` (its alpha `fill`'s), a fan from the tip of class
  /// "heading" (Canvas::FillFan).
  void Heading(const std::vector<Vec2>& pts, sim::Color fill, sim::Color body) override;
  void BeginGroup(const std::string& id, const std::string& cls) override {
    cv_.BeginGroup(id, cls);
  }
  void EndGroup() override { cv_.EndGroup(); }
  bool Shows(const std::string& name) const override {
    return overlays_ == nullptr ? sim::OverlayOnByDefault(name) : overlays_->count(name) > 0;
  }
  void Legend(sim::LegendMark mark, sim::Color color, const std::string& label) override;
  /// The overlays to draw (nullptr: the defaults); the set must outlive the sink.
  void SetOverlays(const std::set<std::string>* overlays) { overlays_ = overlays; }
  bool AnglesInDegrees() const override { return degrees_; }
  void SetAnglesInDegrees(bool degrees) { degrees_ = degrees; }
  /// On: a polygon under 12 px across is filled without anti-aliasing fringes; with an outline,
  /// as the outline's colour half a pixel beyond its edge under its fill, made opaque over the
  /// background, half a pixel inside (four triangles for a rectangle, none thin; its colour stays
  /// readable), else with a 1 px outline (the window's frame rate with a thousand robots). Off
  /// (the default): the pictures of files stay as they are.
  void SetLevelOfDetail(bool on) { level_of_detail_ = on; }
  /// One entry per label the scene named, in the order first named.
  struct LegendEntry {
    sim::LegendMark mark;
    sim::Color color;
    std::string label;
  };
  const std::vector<LegendEntry>& legend() const { return legend_; }
  double PixelsPerMetre() const override { return view_.scale; }
  void ViewBox(Vec2& lo, Vec2& hi) const override;

  /// Screen boxes (x0, y0, x1, y1) no label may cover: the robots' bodies.
  void SetKeepClear(std::vector<ImVec4> boxes) { keep_clear_ = std::move(boxes); }
  /// One more box the labels keep off (before FlushLabels).
  void KeepClear(const ImVec4& box) { keep_clear_.push_back(box); }
  /// Places and draws the queued labels: by role (names, links, values), each at its own spot
  /// when that is free, else at the first free spot around its anchor with a thin leader line,
  /// else not at all (at this zoom). Free: covering no placed label and no keep-clear box.
  void FlushLabels();
  /// Screen boxes of the labels drawn by FlushLabels() (none overlaps another).
  const std::vector<ImVec4>& placed_labels() const { return placed_; }
  /// Labels queued but left out for want of a free spot.
  int dropped_labels() const { return dropped_; }

 private:
  float Width(float px) const { return px * theme_.line_scale; }
  struct Queued {
    ImVec2 anchor;  ///< the world point on screen
    ImVec2 pos;     ///< where the scene asked for the text's top-left corner
    std::string text;
    sim::Color color;
    sim::LabelRole role;
  };
  std::vector<Queued> queued_;
  std::vector<ImVec4> placed_, keep_clear_;
  int dropped_ = 0;
  const std::set<std::string>* overlays_ = nullptr;
  bool degrees_ = true;
  bool level_of_detail_ = false;
  std::vector<LegendEntry> legend_;
  std::vector<ImVec2> screen_, outer_, inner_, normals_;  ///< Polygon's scratch
  Canvas& cv_;
  const View& view_;
  const Theme& theme_;
  FontRole font_;
};

}  // namespace formsim::app
