#include "app/render/world_view.hpp"

#include <algorithm>
#include <cmath>

#include "app/render/camera.hpp"
#include "app/render/canvas_draw_sink.hpp"
#include "app/render/faded_draw_sink.hpp"
#include "app/render/plot.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

// A grid value at `at`, on a backdrop: a trail or robot passing under it leaves it readable.
void CoordinateText(Canvas& cv, const Theme& th, ImVec2 at, const std::string& s) {
  const ImVec2 ext = cv.TextSize(FontRole::kSmall, s);
  cv.FillRect(ImVec2(at.x - 2, at.y), ImVec2(at.x + ext.x + 2, at.y + ext.y), th.backdrop, 2.0f);
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

// The part of the world in a view and its major grid step (metres).
struct VisibleWorld {
  Vec2 lo, hi;
  double major = 1;
};

// Minor lines (a fifth of the major step when far enough apart), major lines, then the axes.
void DrawWorldGrid(Canvas& cv, const View& view, const Theme& th, const VisibleWorld& w,
                   bool level_of_detail) {
  const double major = w.major;
  const double minor =
      major / 5.0 * view.scale >= 12.0 && !level_of_detail ? major / 5.0 : major / 2.0;
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
    for (double x = std::ceil(w.lo.x / step) * step; x <= w.hi.x; x += step)
      vline(view.ToScreen({x, 0}).x, col);
    for (double y = std::ceil(w.lo.y / step) * step; y <= w.hi.y; y += step)
      hline(view.ToScreen({0, y}).y, col);
  };
  if (minor * view.scale >= 10.0) lines(minor, th.world_minor);
  lines(major, th.world_major);
  const ImVec2 o = view.ToScreen({0, 0});
  vline(o.x, th.world_axis);
  hline(o.y, th.world_axis);
}

// The robots and their recent trails on screen, for the legend to keep off (`avoid`); returns
// the boxes of the robots at least 3 px across, which scene labels keep off.
std::vector<ImVec4> ScreenRobots(const View& view, const FocusSet& focus, LegendAvoid* avoid) {
  std::vector<ImVec4> boxes;
  for (std::size_t i = 0; i < focus.bodies.size(); ++i) {
    const ImVec2 c = view.ToScreen(focus.bodies[i]);
    const float r = static_cast<float>(focus.radii[i] * view.scale);
    avoid->bodies.push_back(c);
    avoid->body_radii.push_back(r);
    if (r >= 3.0f) boxes.push_back(ImVec4(c.x - r, c.y - r, c.x + r, c.y + r));
  }
  avoid->trails.reserve(focus.trails.size());
  for (const Vec2& p : focus.trails) avoid->trails.push_back(view.ToScreen(p));
  return boxes;
}

// Adds the boxes of what the view writes over the scene, which its labels keep off: the time
// and caption (top left), the scale bar (bottom right) and the grid's coordinates (bottom and
// left edges).
void AddViewTextBoxes(Canvas& cv, const View& view, const WorldViewOptions& opt, double major,
                      std::vector<ImVec4>* boxes) {
  const float fs = cv.FontSize(FontRole::kSmall);
  if (opt.time_label)
    boxes->push_back(
        ImVec4(view.min.x, view.min.y,
               view.min.x + 16 + cv.TextSize(FontRole::kTitle, "t = 000.00 s  " + opt.time_note).x,
               view.min.y + 40 + (opt.caption.empty() ? 0 : fs + 6)));
  if (opt.scale_bar)
    boxes->push_back(ImVec4(view.max.x - 40 - static_cast<float>(major * view.scale),
                            view.max.y - 50 - cv.FontSize(FontRole::kLabel), view.max.x,
                            view.max.y));
  if (opt.grid && opt.coordinates) {
    boxes->push_back(ImVec4(view.min.x, view.max.y - fs - 6, view.max.x, view.max.y));
    boxes->push_back(ImVec4(view.min.x, view.min.y,
                            view.min.x + 4 + cv.TextSize(FontRole::kSmall, "-00.0").x, view.max.y));
  }
}

// Scene labels that overlap another label, a robot's box (the first `robot_boxes` of
// `keep_clear`) or the legend's (`legend`, when drawn): counted from the boxes as drawn, not
// from what the placement meant to do.
int OverlappingLabels(const std::vector<ImVec4>& placed, const std::vector<ImVec4>& keep_clear,
                      std::size_t robot_boxes, const WorldLegendPlan& legend) {
  auto overlap = [](const ImVec4& a, const ImVec4& b) {
    return a.x < b.z && b.x < a.z && a.y < b.w && b.y < a.w;
  };
  int n = 0;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    bool hit = false;
    for (std::size_t j = 0; j < placed.size() && !hit; ++j)
      hit = j != i && overlap(placed[i], placed[j]);
    for (std::size_t k = 0; k < robot_boxes && !hit; ++k) hit = overlap(placed[i], keep_clear[k]);
    if (legend.drawn && !hit)
      hit = overlap(placed[i], ImVec4(legend.lo.x, legend.lo.y, legend.hi.x, legend.hi.y));
    n += hit;
  }
  return n;
}

// The robots as drawn (name, screen centre, radius) for the layout report.
std::vector<WorldViewReport::Robot> ReportedRobots(const View& view, const sim::Experiment& exp,
                                                   const FocusSet& focus) {
  std::vector<WorldViewReport::Robot> out;
  const auto& robots = exp.world().robots();
  for (std::size_t i = 0; i < focus.bodies.size(); ++i)
    out.push_back({i < robots.size() ? robots[i]->name() : "#" + std::to_string(i + 1),
                   view.ToScreen(focus.bodies[i]),
                   static_cast<float>(focus.radii[i] * view.scale)});
  return out;
}

// Coordinates of the major grid lines along the bottom and left edges, in metres.
void DrawGridCoordinates(Canvas& cv, const View& view, const Theme& th, const VisibleWorld& w) {
  const double major = w.major;
  const float fs = cv.FontSize(FontRole::kSmall);
  for (double x = std::ceil(w.lo.x / major) * major; x <= w.hi.x; x += major) {
    const float sx = view.ToScreen({x, 0}).x;
    if (sx < view.min.x + 40 || sx > view.max.x - 30) continue;
    const std::string s = MetreText(x, major);
    CoordinateText(
        cv, th,
        ImVec2(std::round(sx - cv.TextSize(FontRole::kSmall, s).x / 2), view.max.y - fs - 3), s);
  }
  for (double y = std::ceil(w.lo.y / major) * major; y <= w.hi.y; y += major) {
    const float sy = view.ToScreen({0, y}).y;
    if (sy < view.min.y + 60 || sy > view.max.y - 40) continue;
    CoordinateText(cv, th, ImVec2(view.min.x + 4, std::round(sy - fs / 2)), MetreText(y, major));
  }
}

// The scale bar, bottom right: one major grid step. `report` (may be null) learns its box.
void DrawScaleBar(Canvas& cv, const View& view, const Theme& th, double major,
                  WorldViewReport* report) {
  const float len = static_cast<float>(major * view.scale);
  const ImVec2 p1(view.max.x - 24, view.max.y - 34), p0(p1.x - len, p1.y);
  const std::string text =
      major >= 1.0 ? sim::Sprintf("%g m", major) : sim::Sprintf("%g cm", major * 100.0);
  const ImVec2 ext = cv.TextSize(FontRole::kLabel, text);
  cv.FillRect(ImVec2(p0.x - 8, p0.y - ext.y - 10), ImVec2(p1.x + 8, p1.y + 10),
              th.backdrop.WithAlpha(0.84f), 3.0f);
  if (report) report->scale_bar_box = ImVec4(p0.x - 8, p0.y - ext.y - 10, p1.x + 8, p1.y + 10);
  const sim::Color ink = th.axis;
  cv.Line(p0, p1, {ink, 3.0f});
  cv.Line(ImVec2(p0.x, p0.y - 6), ImVec2(p0.x, p0.y + 6), {ink, 2.0f});
  cv.Line(ImVec2(p1.x, p1.y - 6), ImVec2(p1.x, p1.y + 6), {ink, 2.0f});
  cv.Text(ImVec2(std::round(0.5f * (p0.x + p1.x) - ext.x / 2), p0.y - ext.y - 6), FontRole::kLabel,
          ink, text);
}

// The simulated time (with the options' note), and the caption under it, top left.
void DrawTimeLabel(Canvas& cv, const View& view, const Theme& th, double t,
                   const WorldViewOptions& opt) {
  std::string time = sim::FormatSimTime(t);
  if (!opt.time_note.empty()) time.append("  ").append(opt.time_note);
  // Below a box drawn over the view's top left (presentation mode's bar in a narrow window).
  float top = view.min.y;
  const float right =
      view.min.x + 12 +
      std::max(cv.TextSize(FontRole::kTitle, time).x, cv.TextSize(FontRole::kSmall, opt.caption).x);
  for (const ImVec4& b : opt.keep_clear)
    if (b.x < right && b.y < top + 40 + cv.FontSize(FontRole::kSmall)) top = std::max(top, b.w);
  Label(cv, th, FontRole::kTitle, ImVec2(view.min.x + 12, top + 10), th.text, time);
  if (!opt.caption.empty())
    Label(cv, th, FontRole::kSmall, ImVec2(view.min.x + 12, top + 36), th.axis, opt.caption);
}

// Where the legend of the marks drawn goes (below the pinned runs' legend when there is one).
WorldLegendPlan PlanMarksLegend(Canvas& cv, const View& view, const WorldViewOptions& opt,
                                const std::vector<CanvasDrawSink::LegendEntry>& entries,
                                const LegendAvoid& avoid) {
  const float pins =
      opt.overlays.empty() ? 0.0f : (cv.FontSize(FontRole::kSmall) + 6) * opt.overlays.size() + 14;
  return PlanWorldLegend(cv, view, entries, avoid, opt.legend_state, opt.clock, 60.0f + pins,
                         56.0f);
}

// Legend of the pinned runs drawn over the view, top right: a dashed sample in the entry's
// colour and its label.
void DrawOverlayLegend(Canvas& cv, const View& view, const Theme& th,
                       const std::vector<WorldOverlay>& overlays) {
  const float row = cv.FontSize(FontRole::kSmall) + 6, sample = 26;
  float w = 0;
  for (const WorldOverlay& o : overlays) w = std::max(w, cv.TextSize(FontRole::kSmall, o.label).x);
  const ImVec2 hi(view.max.x - 10, view.min.y + 10 + row * overlays.size() + 8);
  const ImVec2 lo(std::max(view.min.x + 10, hi.x - w - sample - 22), view.min.y + 10);
  cv.FillRect(lo, hi, th.backdrop.WithAlpha(0.88f), 3.0f);
  cv.StrokeRect(lo, hi, th.legend_border, 1.0f, 3.0f);
  for (std::size_t i = 0; i < overlays.size(); ++i) {
    const float y = lo.y + 4 + row * static_cast<float>(i);
    const sim::Color c = th.Ink(overlays[i].color);
    cv.Line(ImVec2(lo.x + 7, y + row / 2), ImVec2(lo.x + 7 + sample, y + row / 2),
            {c.WithAlpha(0.7f), 2.0f, LineDash::Dashes(5, 3)});
    cv.Text(ImVec2(lo.x + 14 + sample, y + 2), FontRole::kSmall, th.text, overlays[i].label);
  }
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
  VisibleWorld world;
  world.lo = view.ToWorld(ImVec2(view.min.x, view.max.y));
  world.hi = view.ToWorld(ImVec2(view.max.x, view.min.y));
  world.major = GridStep(view.scale, 70.0);
  if (opt.grid) DrawWorldGrid(cv, view, th, world, opt.level_of_detail);

  // The robots and their recent trails on screen: labels keep off the bodies, the legend off
  // both. Labels also keep off what the view writes over the scene, what others draw over it
  // (opt.keep_clear) and the legend (below).
  FocusSet own;
  if (!opt.focus) FocusOf(exp, kFocusTrailSeconds, &own);
  const FocusSet& focus = opt.focus ? *opt.focus : own;
  LegendAvoid avoid;
  std::vector<ImVec4> boxes = ScreenRobots(view, focus, &avoid);
  const std::size_t robot_boxes = boxes.size();  // the entries after them are not robots
  AddViewTextBoxes(cv, view, opt, world.major, &boxes);
  for (const ImVec4& b : opt.keep_clear) boxes.push_back(b);

  CanvasDrawSink sink(cv, view, th, FontRole::kSmall);
  sink.SetOverlays(opt.scene_overlays);
  sink.SetAnglesInDegrees(opt.degrees);
  sink.SetLevelOfDetail(opt.level_of_detail);
  const std::vector<ImVec4> keep_clear = opt.report ? boxes : std::vector<ImVec4>();
  sink.SetKeepClear(std::move(boxes));
  exp.Draw(sink);
  for (const WorldOverlay& o : opt.overlays) {
    FadedDrawSink faded(sink, 0.4f);
    o.exp->DrawOverlay(faded);
  }
  // The legend's place is chosen now, from the marks drawn, so that the labels keep off the box
  // it is drawn in this frame (not last frame's, which it may have just left).
  WorldLegendPlan legend;
  if (opt.legend) {
    legend = PlanMarksLegend(cv, view, opt, sink.legend(), avoid);
    if (legend.drawn) sink.KeepClear(ImVec4(legend.lo.x, legend.lo.y, legend.hi.x, legend.hi.y));
  }
  sink.FlushLabels();
  if (opt.report) {
    WorldViewReport& report = *opt.report;
    report.scale_bar_box = ImVec4();
    const std::vector<ImVec4>& placed = sink.placed_labels();
    report.robots = ReportedRobots(view, exp, focus);
    report.labels = static_cast<int>(placed.size());
    report.overlapping_labels = OverlappingLabels(placed, keep_clear, robot_boxes, legend);
    report.formation_fraction = FormationFraction(view, focus);
  }

  if (opt.grid && opt.coordinates) DrawGridCoordinates(cv, view, th, world);
  if (opt.scale_bar) DrawScaleBar(cv, view, th, world.major, opt.report);
  if (opt.time_label) DrawTimeLabel(cv, view, th, exp.time(), opt);
  DrawPlannedWorldLegend(cv, th, sink.legend(), legend, opt.legend_state);
  if (opt.report)
    opt.report->legend_box =
        legend.drawn ? ImVec4(legend.lo.x, legend.lo.y, legend.hi.x, legend.hi.y) : ImVec4();
  if (!opt.overlays.empty()) DrawOverlayLegend(cv, view, th, opt.overlays);
  cv.PopClip();
}

ImVec2 CoordinateReadoutPos(const View& view, ImVec2 ext, const ImVec4& bar, const ImVec4& legend) {
  ImVec2 at(view.min.x + 44, view.max.y - 42);
  constexpr float kGap = 6;
  auto hits = [&](const ImVec4& b) {
    return b.z > b.x && at.x + ext.x + kGap > b.x && at.x - kGap < b.z &&
           at.y + ext.y + kGap > b.y && at.y - kGap < b.w;
  };
  if (hits(bar)) at.y = bar.y - ext.y - 4;
  // Above the legend when it holds the bottom left corner (a readout over it reads as neither).
  if (hits(legend)) at.y = legend.y - ext.y - kGap;
  return at;
}

}  // namespace formsim::app
