#include "app/world_view.hpp"

#include <cmath>
#include <cstdio>

#include "app/imgui_draw_sink.hpp"
#include "app/plot.hpp"

namespace formsim::app {
namespace {

void Label(ImDrawList* dl, ImFont* f, ImVec2 pos, ImU32 col, const std::string& s,
           bool backdrop = true) {
  const ImVec2 ext = f->CalcTextSizeA(f->FontSize, 1e9f, 0.0f, s.c_str());
  pos = ImVec2(std::round(pos.x), std::round(pos.y));
  if (backdrop)
    dl->AddRectFilled(ImVec2(pos.x - 4, pos.y - 2), ImVec2(pos.x + ext.x + 4, pos.y + ext.y + 2),
                      IM_COL32(255, 255, 255, 215), 3.0f);
  dl->AddText(f, f->FontSize, pos, col, s.c_str());
}

std::string MetreText(double v, double step) {
  return FormatTick(v, step, 0);
}

}  // namespace

double GridStep(double ppm, double min_px) {
  double step = 1e-3;
  static const double kMult[] = {1, 2, 5};
  for (int e = -3; e <= 6; ++e)
    for (double m : kMult) {
      step = m * std::pow(10.0, e);
      if (step * ppm >= min_px) return step;
    }
  return step;
}

void DrawWorldView(ImDrawList* dl, const View& view, const sim::Experiment& exp, const Fonts& fonts,
                   const WorldViewOptions& opt) {
  dl->PushClipRect(view.min, view.max, true);
  dl->AddRectFilled(view.min, view.max, kWorldBackground);
  const Vec2 wlo = view.ToWorld(ImVec2(view.min.x, view.max.y));
  const Vec2 whi = view.ToWorld(ImVec2(view.max.x, view.min.y));
  const double major = GridStep(view.scale, 70.0);

  // Grid: minor lines (a fifth of the major step when far enough apart), major lines, axes.
  if (opt.grid) {
    const double minor = major / 5.0 * view.scale >= 12.0 ? major / 5.0 : major / 2.0;
    // Grid lines are pixel-aligned 1-px rectangles, not anti-aliased lines: crisper, and far
    // cheaper for the software rasteriser (long thin AA quads cost it ~8 ms per frame).
    auto vline = [&](float sx, ImU32 col, float th) {
      const float x = std::floor(sx);
      dl->AddRectFilled(ImVec2(x, view.min.y), ImVec2(x + th, view.max.y), col);
    };
    auto hline = [&](float sy, ImU32 col, float th) {
      const float y = std::floor(sy);
      dl->AddRectFilled(ImVec2(view.min.x, y), ImVec2(view.max.x, y + th), col);
    };
    auto lines = [&](double step, ImU32 col, float th) {
      for (double x = std::ceil(wlo.x / step) * step; x <= whi.x; x += step)
        vline(view.ToScreen({x, 0}).x, col, th);
      for (double y = std::ceil(wlo.y / step) * step; y <= whi.y; y += step)
        hline(view.ToScreen({0, y}).y, col, th);
    };
    if (minor * view.scale >= 10.0) lines(minor, IM_COL32(236, 236, 232, 255), 1.0f);
    lines(major, IM_COL32(212, 212, 206, 255), 1.0f);
    const ImVec2 o = view.ToScreen({0, 0});
    vline(o.x, IM_COL32(170, 170, 165, 255), 1.0f);
    hline(o.y, IM_COL32(170, 170, 165, 255), 1.0f);
  }

  ImDrawSink sink(dl, view, fonts.small);
  exp.Draw(sink);

  // Coordinates of the major grid lines along the bottom and left edges, in metres.
  const ImU32 ink = IM_COL32(70, 70, 70, 255);
  if (opt.grid && opt.coordinates) {
    for (double x = std::ceil(wlo.x / major) * major; x <= whi.x; x += major) {
      const float sx = view.ToScreen({x, 0}).x;
      if (sx < view.min.x + 40 || sx > view.max.x - 30) continue;
      const std::string s = MetreText(x, major);
      const float w = fonts.small->CalcTextSizeA(fonts.small->FontSize, 1e9f, 0, s.c_str()).x;
      dl->AddText(fonts.small, fonts.small->FontSize,
                  ImVec2(std::round(sx - w / 2), view.max.y - fonts.small->FontSize - 3),
                  IM_COL32(120, 120, 120, 255), s.c_str());
    }
    for (double y = std::ceil(wlo.y / major) * major; y <= whi.y; y += major) {
      const float sy = view.ToScreen({0, y}).y;
      if (sy < view.min.y + 60 || sy > view.max.y - 40) continue;
      const std::string s = MetreText(y, major);
      dl->AddText(fonts.small, fonts.small->FontSize,
                  ImVec2(view.min.x + 4, std::round(sy - fonts.small->FontSize / 2)),
                  IM_COL32(120, 120, 120, 255), s.c_str());
    }
  }

  // Scale bar, bottom right: one major grid step.
  if (opt.scale_bar) {
    const float len = static_cast<float>(major * view.scale);
    const ImVec2 p1(view.max.x - 24, view.max.y - 34), p0(p1.x - len, p1.y);
    char buf[32];
    if (major >= 1.0)
      std::snprintf(buf, sizeof(buf), "%g m", major);
    else
      std::snprintf(buf, sizeof(buf), "%g cm", major * 100.0);
    const ImVec2 ext = fonts.label->CalcTextSizeA(fonts.label->FontSize, 1e9f, 0, buf);
    dl->AddRectFilled(ImVec2(p0.x - 8, p0.y - ext.y - 10), ImVec2(p1.x + 8, p1.y + 10),
                      IM_COL32(255, 255, 255, 215), 3.0f);
    dl->AddLine(p0, p1, ink, 3.0f);
    dl->AddLine(ImVec2(p0.x, p0.y - 6), ImVec2(p0.x, p0.y + 6), ink, 2.0f);
    dl->AddLine(ImVec2(p1.x, p1.y - 6), ImVec2(p1.x, p1.y + 6), ink, 2.0f);
    dl->AddText(fonts.label, fonts.label->FontSize,
                ImVec2(std::round(0.5f * (p0.x + p1.x) - ext.x / 2), p0.y - ext.y - 6), ink, buf);
  }

  if (opt.time_label) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "t = %.2f s", exp.time());
    Label(dl, fonts.title, ImVec2(view.min.x + 12, view.min.y + 10), IM_COL32(20, 20, 20, 255),
          buf);
    if (!opt.caption.empty())
      Label(dl, fonts.small, ImVec2(view.min.x + 12, view.min.y + 36), ink, opt.caption);
  }
  dl->PopClipRect();
}

}  // namespace formsim::app
