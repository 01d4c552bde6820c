#include "app/export/app_icon.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "app/export/pdf_writer.hpp"
#include "app/export/png_writer.hpp"
#include "app/export/svg_writer.hpp"

namespace formsim::app {
namespace {

constexpr sim::Color kBackground{0.11f, 0.19f, 0.31f, 1.0f};
constexpr sim::Color kWhite{1.0f, 1.0f, 1.0f, 1.0f};

// A robot: a disc in its colour with a white rim and a long, narrow heading arrow, so the
// direction cannot be read three ways (unlike an equilateral wedge).
void Robot(Canvas& cv, ImVec2 c, float r, float heading, sim::Color color) {
  cv.FillCircle(c, r, color);
  cv.StrokeCircle(c, r, kWhite, r * 0.14f);
  const float ux = std::cos(heading), uy = -std::sin(heading);  // screen y points down
  const float vx = -uy, vy = ux;
  const ImVec2 tip(c.x + ux * r * 0.78f, c.y + uy * r * 0.78f);
  const ImVec2 back(c.x - ux * r * 0.42f, c.y - uy * r * 0.42f);
  const ImVec2 arrow[4] = {tip,
                           ImVec2(back.x + vx * r * 0.42f, back.y + vy * r * 0.42f),
                           ImVec2(c.x - ux * r * 0.12f, c.y - uy * r * 0.12f),
                           ImVec2(back.x - vx * r * 0.42f, back.y - vy * r * 0.42f)};
  cv.FillPolygon(arrow, 4, kWhite);
}

}  // namespace

VectorFigure RecordAppIcon(float size) {
  VectorCanvas vector(size, size);
  Canvas& cv = vector;  // the base's default arguments and helpers (Line)
  const float s = size / 256.0f;
  auto at = [s](float x, float y) { return ImVec2(x * s, y * s); };
  cv.FillRect(at(8, 8), at(248, 248), kBackground, 44 * s);
  // The leader's path: a gentle S from the lower left to the leader.
  std::vector<ImVec2> trail;
  for (int i = 0; i <= 48; ++i) {
    const float t = i / 48.0f;
    trail.push_back(at(34 + 142 * t, 214 - 128 * t + 26 * std::sin(6.2832f * t)));
  }
  cv.Polyline(trail.data(), static_cast<int>(trail.size()),
              Stroke(kWhite.WithAlpha(0.35f), 7 * s, LineDash::Dashes(14 * s, 10 * s)));
  // A cascade: R2 follows R1 (distance and bearing), R3 follows R1 and R2 (two distances).
  const ImVec2 r1 = at(176, 86), r2 = at(96, 102), r3 = at(160, 166);
  const Stroke link(kWhite.WithAlpha(0.85f), 5 * s);
  cv.Line(r1, r2, link);
  cv.Line(r1, r3, link);
  cv.Line(r2, r3, link);
  const float heading = 0.62f;  // radians, counter-clockwise from +x
  Robot(cv, r2, 30 * s, heading, sim::PaletteColor(5));
  Robot(cv, r3, 30 * s, heading, sim::PaletteColor(2));
  Robot(cv, r1, 34 * s, heading, sim::PaletteColor(4));
  return vector.Take();
}

void WriteAppIcon(const std::string& svg_path, const std::string& png_path, int png_px) {
  if (!svg_path.empty()) {
    const VectorFigure fig = RecordAppIcon(256.0f);
    FigureSize size;
    size.width = {256, "px"};
    size.height = {256, "px"};
    WriteSvg(fig, size, "formsim", svg_path);
  }
  if (!png_path.empty()) {
    if (png_px < 16 || png_px > 1024)
      throw std::runtime_error("--png-size " + std::to_string(png_px) + ": expected 16 ... 1024");
    const VectorFigure fig = RecordAppIcon(static_cast<float>(png_px));
    const std::vector<std::uint8_t> rgba = RasterRgba(fig, png_px, png_px);
    WritePng(png_path, png_px, png_px, rgba.data());
  }
}

}  // namespace formsim::app
