#include "app/render/plot_marker.hpp"

namespace formsim::app {

void DrawMarker(Canvas& cv, ImVec2 c, float r, MarkerShape shape, sim::Color color, bool hollow) {
  auto polygon = [&](const ImVec2* p, int n) {
    if (hollow)
      cv.Polyline(p, n, Stroke{color, 1.2f}, true);
    else
      cv.FillPolygon(p, n, color);
  };
  switch (shape) {
    case MarkerShape::kNone:
      return;
    case MarkerShape::kCircle:
      if (hollow)
        cv.StrokeCircle(c, r, color, 1.2f);
      else
        cv.FillCircle(c, r, color);
      return;
    case MarkerShape::kSquare: {
      const float h = 0.85f * r;  // the same ink as the circle, about
      // Clockwise on screen (top-left first), as ImGui's anti-aliased fill wants.
      const ImVec2 p[4] = {ImVec2(c.x - h, c.y - h), ImVec2(c.x + h, c.y - h),
                           ImVec2(c.x + h, c.y + h), ImVec2(c.x - h, c.y + h)};
      polygon(p, 4);
      return;
    }
    case MarkerShape::kTriangle: {
      const ImVec2 p[3] = {ImVec2(c.x, c.y - 1.15f * r), ImVec2(c.x + r, c.y + 0.75f * r),
                           ImVec2(c.x - r, c.y + 0.75f * r)};
      polygon(p, 3);
      return;
    }
    case MarkerShape::kTriangleDown: {
      const ImVec2 p[3] = {ImVec2(c.x - r, c.y - 0.75f * r), ImVec2(c.x + r, c.y - 0.75f * r),
                           ImVec2(c.x, c.y + 1.15f * r)};
      polygon(p, 3);
      return;
    }
    case MarkerShape::kDiamond: {
      const float h = 1.2f * r;
      const ImVec2 p[4] = {ImVec2(c.x, c.y - h), ImVec2(c.x + h, c.y), ImVec2(c.x, c.y + h),
                           ImVec2(c.x - h, c.y)};
      polygon(p, 4);
      return;
    }
    case MarkerShape::kPlus: {
      const float h = 1.2f * r;
      cv.Line(ImVec2(c.x - h, c.y), ImVec2(c.x + h, c.y), Stroke{color, 1.6f});
      cv.Line(ImVec2(c.x, c.y - h), ImVec2(c.x, c.y + h), Stroke{color, 1.6f});
      return;
    }
    case MarkerShape::kCross: {
      const float h = 0.9f * r;
      cv.Line(ImVec2(c.x - h, c.y - h), ImVec2(c.x + h, c.y + h), Stroke{color, 1.6f});
      cv.Line(ImVec2(c.x - h, c.y + h), ImVec2(c.x + h, c.y - h), Stroke{color, 1.6f});
      return;
    }
  }
}

}  // namespace formsim::app
