#include "app/render/world_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/render/canvas_draw_sink.hpp"
#include "app/render/faded_draw_sink.hpp"
#include "app/render/plot.hpp"

namespace formsim::app {
namespace {

void Label(Canvas& cv, const Theme& th, FontRole f, ImVec2 pos, sim::Color col,
           const std::string& s) {
  const ImVec2 ext = cv.TextSize(f, s);
  pos = ImVec2(std::round(pos.x), std::round(pos.y));
  cv.FillRect(ImVec2(pos.x - 4, pos.y - 2), ImVec2(pos.x + ext.x + 4, pos.y + ext.y + 2),
              th.backdrop.WithAlpha(0.84f), 3.0f);
  cv.Text(pos, f, col, s);
}

std::string MetreText(double v, double step) {
  return FormatTick(v, step, 0);
}

}  // namespace

std::set<std::string> DefaultSceneOverlays() {
  std::set<std::string> out;
  for (const sim::OverlayInfo& o : sim::Overlays())
    if (o.on_by_default) out.insert(o.name);
  return out;
}

std::string ParseSceneOverlays(const std::string& text, std::set<std::string>* out) {
  std::set<std::string> next = *out;
  std::string item;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && text[i] != ',') {
      if (text[i] != ' ') item += text[i];
      continue;
    }
    if (item.empty()) continue;
    const bool remove = item[0] == '-';
    const std::string name = remove ? item.substr(1) : item;
    item.clear();
    if (name == "all") {
      for (const sim::OverlayInfo& o : sim::Overlays()) next.insert(o.name);
    } else if (name == "none") {
      next.clear();
    } else if (name == "default") {
      next = DefaultSceneOverlays();
    } else {
      bool known = false;
      for (const sim::OverlayInfo& o : sim::Overlays()) known = known || o.name == name;
      if (!known) {
        std::string names;
        for (const sim::OverlayInfo& o : sim::Overlays()) names += (names.empty() ? "" : ", ") + o.name;
        return "unknown overlay '" + name + "' (known: " + names + ", all, none, default, -NAME)";
      }
      if (remove)
        next.erase(name);
      else
        next.insert(name);
    }
  }
  *out = std::move(next);
  return "";
}

// The legend of the marks the scene drew: a sample of each and its label, bottom left.
static void DrawLegend(Canvas& cv, const View& view, const Theme& th,
                const std::vector<CanvasDrawSink::LegendEntry>& entries) {
  if (entries.empty()) return;
  const FontRole f = FontRole::kSmall;
  const float row = cv.FontSize(f) + 6, sample = 26;
  float w = 0;
  for (const auto& e : entries) w = std::max(w, cv.TextSize(f, e.label).x);
  const float h = row * static_cast<float>(entries.size()) + 8;
  const ImVec2 lo(view.min.x + 10, std::max(view.min.y + 60, view.max.y - 56 - h));
  const ImVec2 hi(lo.x + w + sample + 24, lo.y + h);
  cv.FillRect(lo, hi, th.backdrop.WithAlpha(0.9f), 3.0f);
  cv.StrokeRect(lo, hi, th.legend_border, 1.0f, 3.0f);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto& e = entries[i];
    const sim::Color c = th.Ink(e.color);
    const float y = lo.y + 4 + row * static_cast<float>(i), cy = y + row / 2;
    const float x0 = lo.x + 7, x1 = x0 + sample, cx = 0.5f * (x0 + x1);
    const float lw = 2.0f * th.line_scale;
    switch (e.mark) {
      case sim::LegendMark::kBody: {
        cv.FillRect(ImVec2(cx - 9, cy - 6), ImVec2(cx + 9, cy + 6), c, 1.0f);
        const ImVec2 wedge[3] = {ImVec2(cx + 6, cy), ImVec2(cx - 3, cy - 4), ImVec2(cx - 3, cy + 4)};
        cv.FillPolygon(wedge, 3, sim::Color{1, 1, 1, 0.9f});
        break;
      }
      case sim::LegendMark::kLine:
      case sim::LegendMark::kTrail:
        cv.Line(ImVec2(x0, cy), ImVec2(x1, cy), {c, lw});
        break;
      case sim::LegendMark::kDashedLine:
        cv.Line(ImVec2(x0, cy), ImVec2(x1, cy), {c, lw, LineDash::Dashes(5, 3)});
        break;
      case sim::LegendMark::kGhost:
        cv.StrokeRect(ImVec2(cx - 8, cy - 5), ImVec2(cx + 8, cy + 5), c.WithAlpha(0.6f), 1.5f, 2.0f);
        break;
      case sim::LegendMark::kDot:
        cv.FillCircle(ImVec2(cx, cy), 4.0f, c);
        cv.StrokeCircle(ImVec2(cx, cy), 4.0f, th.text, 1.0f);
        break;
      case sim::LegendMark::kCross:
        cv.Line(ImVec2(cx - 5, cy - 5), ImVec2(cx + 5, cy + 5), {c, lw});
        cv.Line(ImVec2(cx - 5, cy + 5), ImVec2(cx + 5, cy - 5), {c, lw});
        break;
      case sim::LegendMark::kEllipse: {
        std::vector<ImVec2> pts;
        for (int k = 0; k < 24; ++k)
          pts.push_back(ImVec2(cx + 11 * std::cos(k * 0.2618f), cy + 5 * std::sin(k * 0.2618f)));
        cv.Polyline(pts.data(), static_cast<int>(pts.size()), {c, 1.5f}, true);
        break;
      }
      case sim::LegendMark::kRing:
        cv.StrokeCircle(ImVec2(cx, cy), 6.0f, c, lw);
        break;
      case sim::LegendMark::kArrow:
        cv.Line(ImVec2(x0, cy), ImVec2(x1, cy), {c, lw});
        cv.Line(ImVec2(x1, cy), ImVec2(x1 - 6, cy - 4), {c, lw});
        cv.Line(ImVec2(x1, cy), ImVec2(x1 - 6, cy + 4), {c, lw});
        break;
      case sim::LegendMark::kArc: {
        std::vector<ImVec2> pts;
        for (int k = 0; k <= 8; ++k)
          pts.push_back(ImVec2(x0 + 2 + 22 * std::cos(-k * 0.12f), cy + 6 + 22 * std::sin(-k * 0.12f) * 0.6f));
        cv.Polyline(pts.data(), static_cast<int>(pts.size()), {c, 1.5f});
        break;
      }
    }
    cv.Text(ImVec2(lo.x + 14 + sample, y + 2), f, th.text, e.label);
  }
}

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

void FrameWorldView(const sim::Experiment& exp, float width, float height, View& view, AutoFit& fit,
                    bool jump) {
  view.min = ImVec2(0, 0);
  view.max = ImVec2(width, height);
  Vec2 lo, hi;
  exp.Bounds(lo, hi);
  fit.Update(view, lo, hi, jump ? 1.0 : 0.15);
}

void DrawWorldView(Canvas& cv, const View& view, const sim::Experiment& exp, const Theme& th,
                   const WorldViewOptions& opt) {
  cv.PushClip(view.min, view.max);
  cv.FillRect(view.min, view.max, th.background);
  const Vec2 wlo = view.ToWorld(ImVec2(view.min.x, view.max.y));
  const Vec2 whi = view.ToWorld(ImVec2(view.max.x, view.min.y));
  const double major = GridStep(view.scale, 70.0);

  // Grid: minor lines (a fifth of the major step when far enough apart), major lines, axes.
  if (opt.grid) {
    const double minor = major / 5.0 * view.scale >= 12.0 ? major / 5.0 : major / 2.0;
    // Grid lines are pixel-aligned 1-px rectangles, not anti-aliased lines: crisper, and far
    // cheaper for the software rasteriser (long thin AA quads cost it ~8 ms per frame).
    auto vline = [&](float sx, sim::Color col) {
      const float x = std::floor(sx);
      cv.FillRect(ImVec2(x, view.min.y), ImVec2(x + 1, view.max.y), col);
    };
    auto hline = [&](float sy, sim::Color col) {
      const float y = std::floor(sy);
      cv.FillRect(ImVec2(view.min.x, y), ImVec2(view.max.x, y + 1), col);
    };
    auto lines = [&](double step, sim::Color col) {
      for (double x = std::ceil(wlo.x / step) * step; x <= whi.x; x += step)
        vline(view.ToScreen({x, 0}).x, col);
      for (double y = std::ceil(wlo.y / step) * step; y <= whi.y; y += step)
        hline(view.ToScreen({0, y}).y, col);
    };
    if (minor * view.scale >= 10.0) lines(minor, th.world_minor);
    lines(major, th.world_major);
    const ImVec2 o = view.ToScreen({0, 0});
    vline(o.x, th.world_axis);
    hline(o.y, th.world_axis);
  }

  CanvasDrawSink sink(cv, view, th, FontRole::kSmall);
  sink.SetOverlays(opt.scene_overlays);
  sink.SetAnglesInDegrees(opt.degrees);
  exp.Draw(sink);
  for (const WorldOverlay& o : opt.overlays) {
    FadedDrawSink faded(sink, 0.4f);
    o.exp->DrawOverlay(faded);
  }

  // Coordinates of the major grid lines along the bottom and left edges, in metres.
  if (opt.grid && opt.coordinates) {
    const float fs = cv.FontSize(FontRole::kSmall);
    for (double x = std::ceil(wlo.x / major) * major; x <= whi.x; x += major) {
      const float sx = view.ToScreen({x, 0}).x;
      if (sx < view.min.x + 40 || sx > view.max.x - 30) continue;
      const std::string s = MetreText(x, major);
      const float w = cv.TextSize(FontRole::kSmall, s).x;
      cv.Text(ImVec2(std::round(sx - w / 2), view.max.y - fs - 3), FontRole::kSmall, th.coordinates,
              s);
    }
    for (double y = std::ceil(wlo.y / major) * major; y <= whi.y; y += major) {
      const float sy = view.ToScreen({0, y}).y;
      if (sy < view.min.y + 60 || sy > view.max.y - 40) continue;
      cv.Text(ImVec2(view.min.x + 4, std::round(sy - fs / 2)), FontRole::kSmall, th.coordinates,
              MetreText(y, major));
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
    const ImVec2 ext = cv.TextSize(FontRole::kLabel, buf);
    cv.FillRect(ImVec2(p0.x - 8, p0.y - ext.y - 10), ImVec2(p1.x + 8, p1.y + 10),
                th.backdrop.WithAlpha(0.84f), 3.0f);
    const sim::Color ink = th.axis;
    cv.Line(p0, p1, {ink, 3.0f});
    cv.Line(ImVec2(p0.x, p0.y - 6), ImVec2(p0.x, p0.y + 6), {ink, 2.0f});
    cv.Line(ImVec2(p1.x, p1.y - 6), ImVec2(p1.x, p1.y + 6), {ink, 2.0f});
    cv.Text(ImVec2(std::round(0.5f * (p0.x + p1.x) - ext.x / 2), p0.y - ext.y - 6),
            FontRole::kLabel, ink, buf);
  }

  if (opt.time_label) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "t = %.2f s", exp.time());
    Label(cv, th, FontRole::kTitle, ImVec2(view.min.x + 12, view.min.y + 10), th.text,
          buf + (opt.time_note.empty() ? std::string() : "  " + opt.time_note));
    if (!opt.caption.empty())
      Label(cv, th, FontRole::kSmall, ImVec2(view.min.x + 12, view.min.y + 36), th.axis,
            opt.caption);
  }
  if (opt.legend) DrawLegend(cv, view, th, sink.legend());
  // Legend of the overlays, top right: a dashed sample in the entry's colour and its label.
  if (!opt.overlays.empty()) {
    const float row = cv.FontSize(FontRole::kSmall) + 6, sample = 26;
    float w = 0;
    for (const WorldOverlay& o : opt.overlays)
      w = std::max(w, cv.TextSize(FontRole::kSmall, o.label).x);
    const ImVec2 hi(view.max.x - 10, view.min.y + 10 + row * opt.overlays.size() + 8);
    const ImVec2 lo(std::max(view.min.x + 10, hi.x - w - sample - 22), view.min.y + 10);
    cv.FillRect(lo, hi, th.backdrop.WithAlpha(0.88f), 3.0f);
    cv.StrokeRect(lo, hi, th.legend_border, 1.0f, 3.0f);
    for (std::size_t i = 0; i < opt.overlays.size(); ++i) {
      const float y = lo.y + 4 + row * static_cast<float>(i);
      const sim::Color c = th.Ink(opt.overlays[i].color);
      cv.Line(ImVec2(lo.x + 7, y + row / 2), ImVec2(lo.x + 7 + sample, y + row / 2),
              {c.WithAlpha(0.7f), 2.0f, LineDash::Dashes(5, 3)});
      cv.Text(ImVec2(lo.x + 14 + sample, y + 2), FontRole::kSmall, th.text, opt.overlays[i].label);
    }
  }
  cv.PopClip();
}

}  // namespace formsim::app
