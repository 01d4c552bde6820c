#include "app/render/world_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/render/camera.hpp"
#include "app/render/canvas_draw_sink.hpp"
#include "app/render/faded_draw_sink.hpp"
#include "app/render/plot.hpp"

namespace formsim::app {
namespace {

// A grid value at `at`, on a backdrop: a trail or robot passing under it leaves it readable.
void CoordinateText(Canvas& cv, const Theme& th, ImVec2 at, const std::string& s) {
  const ImVec2 ext = cv.TextSize(FontRole::kSmall, s);
  cv.FillRect(ImVec2(at.x - 2, at.y), ImVec2(at.x + ext.x + 2, at.y + ext.y),
              th.backdrop, 2.0f);
  cv.Text(at, FontRole::kSmall, th.coordinates, s);
}

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
        for (const sim::OverlayInfo& o : sim::Overlays())
          names += (names.empty() ? "" : ", ") + o.name;
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
  cv.FillBackground(view.min, view.max, th.background);
  const Vec2 wlo = view.ToWorld(ImVec2(view.min.x, view.max.y));
  const Vec2 whi = view.ToWorld(ImVec2(view.max.x, view.min.y));
  const double major = GridStep(view.scale, 70.0);

  // Grid: minor lines (a fifth of the major step when far enough apart), major lines, axes.
  if (opt.grid) {
    const double minor =
        major / 5.0 * view.scale >= 12.0 && !opt.level_of_detail ? major / 5.0 : major / 2.0;
    // Grid lines are pixel-aligned 1-px rectangles, not anti-aliased lines: crisper, and far
    // cheaper for the software rasteriser (long thin AA quads cost it ~8 ms per frame). They are
    // cleared, not drawn, where the canvas can (opaque, on whole pixels: ImGuiCanvas's
    // FillBackground): the same pixels without the fragment shader on every 4x4 block a 1-px
    // line touches (a 1280x720 export: 6-16 % less CPU; a vector canvas draws rectangles).
    auto vline = [&](float sx, sim::Color col) {
      const float x = std::floor(sx);
      cv.FillBackground(ImVec2(x, view.min.y), ImVec2(x + 1, view.max.y), col);
    };
    auto hline = [&](float sy, sim::Color col) {
      const float y = std::floor(sy);
      cv.FillBackground(ImVec2(view.min.x, y), ImVec2(view.max.x, y + 1), col);
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

  // The robots and their recent trails on screen: labels keep off the bodies, the legend off
  // both.
  FocusSet own;
  if (!opt.focus) FocusOf(exp, kFocusTrailSeconds, &own);
  const FocusSet& focus = opt.focus ? *opt.focus : own;
  LegendAvoid avoid;
  std::vector<ImVec4> bodies;
  for (std::size_t i = 0; i < focus.bodies.size(); ++i) {
    const ImVec2 c = view.ToScreen(focus.bodies[i]);
    const float r = static_cast<float>(focus.radii[i] * view.scale);
    avoid.bodies.push_back(c);
    avoid.body_radii.push_back(r);
    if (r >= 3.0f) bodies.push_back(ImVec4(c.x - r, c.y - r, c.x + r, c.y + r));
  }
  avoid.trails.reserve(focus.trails.size());
  for (const Vec2& p : focus.trails) avoid.trails.push_back(view.ToScreen(p));
  const std::size_t robot_boxes = bodies.size();  // the entries after them are not robots
  // Scene labels also keep off what the view draws over them: the time and caption (top left),
  // the scale bar (bottom right) and the grid's coordinates (bottom and left edges).
  {
    const float fs = cv.FontSize(FontRole::kSmall);
    if (opt.time_label)
      bodies.push_back(ImVec4(
          view.min.x, view.min.y,
          view.min.x + 16 + cv.TextSize(FontRole::kTitle, "t = 000.00 s  " + opt.time_note).x,
          view.min.y + 40 + (opt.caption.empty() ? 0 : fs + 6)));
    if (opt.scale_bar)
      bodies.push_back(ImVec4(view.max.x - 40 - static_cast<float>(major * view.scale),
                              view.max.y - 50 - cv.FontSize(FontRole::kLabel), view.max.x,
                              view.max.y));
    if (opt.grid && opt.coordinates) {
      bodies.push_back(ImVec4(view.min.x, view.max.y - fs - 6, view.max.x, view.max.y));
      bodies.push_back(ImVec4(view.min.x, view.min.y,
                              view.min.x + 4 + cv.TextSize(FontRole::kSmall, "-00.0").x,
                              view.max.y));
    }
  }

  CanvasDrawSink sink(cv, view, th, FontRole::kSmall);
  sink.SetOverlays(opt.scene_overlays);
  sink.SetAnglesInDegrees(opt.degrees);
  sink.SetLevelOfDetail(opt.level_of_detail);
  // The legend as last drawn (it moves at most once a second): labels keep off it too.
  const bool has_legend_box =
      opt.legend && opt.legend_state && opt.legend_state->box_max.x > opt.legend_state->box_min.x;
  for (const ImVec4& b : opt.keep_clear) bodies.push_back(b);
  if (has_legend_box) {  // last: the report below counts labels over it
    const LegendState& ls = *opt.legend_state;
    bodies.push_back(ImVec4(ls.box_min.x, ls.box_min.y, ls.box_max.x, ls.box_max.y));
  }
  const std::vector<ImVec4> keep_clear = bodies;
  sink.SetKeepClear(std::move(bodies));
  exp.Draw(sink);
  for (const WorldOverlay& o : opt.overlays) {
    FadedDrawSink faded(sink, 0.4f);
    o.exp->DrawOverlay(faded);
  }
  sink.FlushLabels();
  if (opt.report) {
    opt.report->scale_bar_box = ImVec4();
    // Counted from the boxes as drawn, not from what the placement meant to do.
    auto overlap = [](const ImVec4& a, const ImVec4& b) {
      return a.x < b.z && b.x < a.z && a.y < b.w && b.y < a.w;
    };
    const auto& placed = sink.placed_labels();
    int n = 0;
    for (std::size_t i = 0; i < placed.size(); ++i) {
      bool hit = false;
      for (std::size_t j = 0; j < placed.size() && !hit; ++j)
        hit = j != i && overlap(placed[i], placed[j]);
      for (std::size_t k = 0; k < robot_boxes && !hit; ++k) hit = overlap(placed[i], keep_clear[k]);
      if (has_legend_box && !hit) hit = overlap(placed[i], keep_clear.back());
      n += hit;
    }
    opt.report->robots.clear();
    const auto& robots = exp.world().robots();
    for (std::size_t i = 0; i < focus.bodies.size(); ++i)
      opt.report->robots.push_back({i < robots.size() ? robots[i]->name() : "#" + std::to_string(i + 1),
                                    view.ToScreen(focus.bodies[i]),
                                    static_cast<float>(focus.radii[i] * view.scale)});
    opt.report->labels = static_cast<int>(placed.size());
    opt.report->overlapping_labels = n;
    opt.report->formation_fraction = FormationFraction(view, focus);
  }

  // Coordinates of the major grid lines along the bottom and left edges, in metres.
  if (opt.grid && opt.coordinates) {
    const float fs = cv.FontSize(FontRole::kSmall);
    for (double x = std::ceil(wlo.x / major) * major; x <= whi.x; x += major) {
      const float sx = view.ToScreen({x, 0}).x;
      if (sx < view.min.x + 40 || sx > view.max.x - 30) continue;
      const std::string s = MetreText(x, major);
      CoordinateText(cv, th, ImVec2(std::round(sx - cv.TextSize(FontRole::kSmall, s).x / 2),
                                    view.max.y - fs - 3), s);
    }
    for (double y = std::ceil(wlo.y / major) * major; y <= whi.y; y += major) {
      const float sy = view.ToScreen({0, y}).y;
      if (sy < view.min.y + 60 || sy > view.max.y - 40) continue;
      CoordinateText(cv, th, ImVec2(view.min.x + 4, std::round(sy - fs / 2)), MetreText(y, major));
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
    if (opt.report)
      opt.report->scale_bar_box = ImVec4(p0.x - 8, p0.y - ext.y - 10, p1.x + 8, p1.y + 10);
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
    const std::string time = buf + (opt.time_note.empty() ? std::string() : "  " + opt.time_note);
    // Below a box drawn over the view's top left (presentation mode's bar in a narrow window).
    float top = view.min.y;
    const float right = view.min.x + 12 + std::max(cv.TextSize(FontRole::kTitle, time).x,
                                                   cv.TextSize(FontRole::kSmall, opt.caption).x);
    for (const ImVec4& b : opt.keep_clear)
      if (b.x < right && b.y < top + 40 + cv.FontSize(FontRole::kSmall)) top = std::max(top, b.w);
    Label(cv, th, FontRole::kTitle, ImVec2(view.min.x + 12, top + 10), th.text, time);
    if (!opt.caption.empty())
      Label(cv, th, FontRole::kSmall, ImVec2(view.min.x + 12, top + 36), th.axis, opt.caption);
  }
  if (opt.legend) {
    const float pins = opt.overlays.empty()
                           ? 0.0f
                           : (cv.FontSize(FontRole::kSmall) + 6) * opt.overlays.size() + 14;
    DrawWorldLegend(cv, view, th, sink.legend(), avoid, opt.legend_state, opt.clock, 60.0f + pins,
                    56.0f);
    if (opt.report && opt.legend_state)
      opt.report->legend_box = ImVec4(opt.legend_state->box_min.x, opt.legend_state->box_min.y,
                                      opt.legend_state->box_max.x, opt.legend_state->box_max.y);
  } else if (opt.report) {
    opt.report->legend_box = ImVec4();
  }
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

ImVec2 CoordinateReadoutPos(const View& view, ImVec2 ext, const ImVec4& bar, const ImVec4& legend) {
  ImVec2 at(view.min.x + 44, view.max.y - 42);
  constexpr float kGap = 6;
  auto hits = [&](const ImVec4& b) {
    return b.z > b.x && at.x + ext.x + kGap > b.x && at.x - kGap < b.z && at.y + ext.y + kGap > b.y &&
           at.y - kGap < b.w;
  };
  if (hits(bar)) at.y = bar.y - ext.y - 4;
  // Above the legend when it holds the bottom left corner (a readout over it reads as neither).
  if (hits(legend)) at.y = legend.y - ext.y - kGap;
  return at;
}

}  // namespace formsim::app
