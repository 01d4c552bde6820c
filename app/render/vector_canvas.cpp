#include "app/render/vector_canvas.hpp"

#include <algorithm>
#include <stdexcept>

#include "app/render/vector_fonts.hpp"

namespace formsim::app {

VectorCanvas::VectorCanvas(float width, float height) {
  VectorFonts::Get();  // fail now, before anything is drawn, when the fonts are missing
  fig_.width = width;
  fig_.height = height;
  clips_.emplace_back(0.0f, 0.0f, width, height);
}

VectorOp& VectorCanvas::Add(VectorOp::Kind kind, sim::Color color) {
  VectorOp op;
  op.kind = kind;
  op.color = color;
  fig_.ops.push_back(std::move(op));
  return fig_.ops.back();
}

void VectorCanvas::FillRect(ImVec2 min, ImVec2 max, sim::Color color, float rounding) {
  if (color.a <= 0 || !(max.x > min.x) || !(max.y > min.y)) return;
  VectorOp& op = Add(VectorOp::Kind::kFillRect, color);
  op.pts = {min, max};
  op.size = rounding;
}

void VectorCanvas::StrokeRect(ImVec2 min, ImVec2 max, sim::Color color, float width,
                              float rounding) {
  if (color.a <= 0) return;
  VectorOp& op = Add(VectorOp::Kind::kStrokeRect, color);
  op.pts = {min, max};
  op.width = width;
  op.size = rounding;
}

void VectorCanvas::Polyline(const ImVec2* pts, int n, const Stroke& stroke, bool closed) {
  if (n < 2 || stroke.color.a <= 0) return;
  VectorOp& op = Add(VectorOp::Kind::kPath, stroke.color);
  op.pts.assign(pts, pts + n);
  op.width = stroke.width;
  op.dash = stroke.dash;
  op.closed = closed;
}

void VectorCanvas::FillPolygon(const ImVec2* pts, int n, sim::Color color) {
  if (n < 3 || color.a <= 0) return;
  VectorOp& op = Add(VectorOp::Kind::kFillPath, color);
  op.pts.assign(pts, pts + n);
  op.closed = true;
}

void VectorCanvas::FillFan(const ImVec2* pts, int n, sim::Color color, const std::string& cls) {
  if (n < 3 || color.a <= 0) return;
  FillPolygon(pts, n, color);
  fig_.ops.back().cls = cls;
}

void VectorCanvas::BeginGroup(const std::string& id, const std::string& cls) {
  VectorOp& op = Add(VectorOp::Kind::kBeginGroup, {});
  op.text = id;
  op.cls = cls;
}

void VectorCanvas::EndGroup() {
  Add(VectorOp::Kind::kEndGroup, {});
}

void VectorCanvas::FillCircle(ImVec2 center, float radius, sim::Color color) {
  if (color.a <= 0 || !(radius > 0)) return;
  VectorOp& op = Add(VectorOp::Kind::kFillCircle, color);
  op.pts = {center};
  op.size = radius;
}

void VectorCanvas::StrokeCircle(ImVec2 center, float radius, sim::Color color, float width) {
  if (color.a <= 0 || !(radius > 0)) return;
  VectorOp& op = Add(VectorOp::Kind::kStrokeCircle, color);
  op.pts = {center};
  op.size = radius;
  op.width = width;
}

void VectorCanvas::Text(ImVec2 pos, FontRole font, sim::Color color, const std::string& text) {
  if (text.empty() || color.a <= 0) return;
  VectorOp& op = Add(VectorOp::Kind::kText, color);
  op.pts = {ImVec2(pos.x, pos.y + VectorFonts::Get().Baseline(font))};
  op.font = font;
  op.text = text;
}

void VectorCanvas::DrawVertical(ImVec2 center, FontRole font, sim::Color color,
                                const std::string& text, ImVec2 ext, bool markup) {
  if (text.empty() || color.a <= 0) return;
  VectorOp& op = Add(VectorOp::Kind::kText, color);
  // The baseline start before rotating, then the rotation about the centre.
  op.pts = {ImVec2(center.x - ext.x / 2, center.y - ext.y / 2 + VectorFonts::Get().Baseline(font)),
            center};
  op.font = font;
  op.text = text;
  op.vertical = true;
  op.markup = markup;
}

void VectorCanvas::Label(ImVec2 pos, FontRole font, sim::Color color, const std::string& markup) {
  if (markup.empty() || color.a <= 0) return;
  Text(pos, font, color, markup);
  fig_.ops.back().markup = true;
}

ImVec2 VectorCanvas::LabelSize(FontRole font, const std::string& markup) const {
  float w = 0;
  for (const MarkupRun& run : ParseMarkup(markup).runs)
    w += PlacementOf(run.kind).scale * VectorFonts::Get().Width(font, run.text);
  return ImVec2(w, FontSize(font));
}

ImVec2 VectorCanvas::TextSize(FontRole font, const std::string& text) const {
  return ImVec2(VectorFonts::Get().Width(font, text), FontSize(font));
}

void VectorCanvas::PushClip(ImVec2 min, ImVec2 max) {
  VectorOp& op = Add(VectorOp::Kind::kPushClip, {});
  op.pts = {min, max};
  const ImVec4& c = clips_.back();
  clips_.emplace_back(std::max(c.x, min.x), std::max(c.y, min.y), std::min(c.z, max.x),
                      std::min(c.w, max.y));
}

void VectorCanvas::Clip(ImVec2& min, ImVec2& max) const {
  min = ImVec2(clips_.back().x, clips_.back().y);
  max = ImVec2(clips_.back().z, clips_.back().w);
}

void VectorCanvas::PopClip() {
  if (clips_.size() <= 1) throw std::logic_error("VectorCanvas::PopClip without PushClip");
  clips_.pop_back();
  Add(VectorOp::Kind::kPopClip, {});
}

}  // namespace formsim::app
