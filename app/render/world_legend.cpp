#include "app/render/world_legend.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace formsim::app {
namespace {

// A sample of a mark, centred in [x0, x1] at height cy.
void DrawSample(Canvas& cv, const Theme& th, sim::LegendMark mark, sim::Color color, float x0,
                float x1, float cy) {
  const sim::Color c = mark == sim::LegendMark::kBody ? th.Fill(color) : th.Ink(color);
  const float cx = 0.5f * (x0 + x1);
  const float lw = 2.0f * th.line_scale;
  switch (mark) {
    case sim::LegendMark::kBody: {
      // The robot as the world view draws it (sim::DrawRobotBody): its fill, dark outline and
      // heading arrow, in the theme's inks for that body.
      const sim::Color body = color.WithAlpha(sim::kBodyAlpha);
      const ImVec2 box[4] = {ImVec2(cx + 9, cy - 6), ImVec2(cx - 9, cy - 6), ImVec2(cx - 9, cy + 6),
                             ImVec2(cx + 9, cy + 6)};
      cv.FillPolygon(box, 4, th.Fill(body));
      cv.Polyline(box, 4, {th.Ink(sim::Color{0.1f, 0.1f, 0.1f, 1.0f}), 1.5f * th.line_scale}, true);
      ImVec2 arrow[4];
      int k = 0;
      for (const Vec2& p : sim::HeadingArrow(-9, 9, 6))
        arrow[k++] = ImVec2(cx + static_cast<float>(p.x), cy - static_cast<float>(p.y));
      cv.FillFan(arrow, 4, th.HeadingInk(body), "heading-legend");
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
        pts.push_back(
            ImVec2(x0 + 2 + 22 * std::cos(-k * 0.12f), cy + 6 + 22 * std::sin(-k * 0.12f) * 0.6f));
      cv.Polyline(pts.data(), static_cast<int>(pts.size()), {c, 1.5f});
      break;
    }
  }
}

struct Layout {
  int columns = 1, rows = 0, shown = 0;
  float col_w = 0, row_h = 0, w = 0, h = 0;
};

constexpr float kSample = 24, kPad = 6, kTitleGap = 2;

// The last line of a legend that leaves out `hidden` entries.
std::string MoreText(int hidden) {
  return "+ " + std::to_string(hidden) + " more (larger view shows them)";
}

Layout Measure(Canvas& cv, const std::vector<CanvasDrawSink::LegendEntry>& entries, int shown,
               int columns, bool collapsed, float title_w) {
  const FontRole f = FontRole::kSmall;
  Layout l;
  l.row_h = cv.FontSize(f) + 4;
  l.columns = columns;
  l.shown = shown;
  float label_w = 0;
  for (int i = 0; i < shown; ++i)
    label_w = std::max(label_w, cv.TextSize(f, entries[static_cast<std::size_t>(i)].label).x);
  l.col_w = kSample + 8 + label_w + 10;
  const int hidden = static_cast<int>(entries.size()) - shown;
  l.rows = collapsed ? 0 : (shown + columns - 1) / columns + (hidden > 0 ? 1 : 0);
  l.w = std::max(title_w + 2 * kPad, collapsed ? 0.0f : columns * l.col_w + 2 * kPad);
  if (!collapsed && hidden > 0) l.w = std::max(l.w, cv.TextSize(f, MoreText(hidden)).x + 2 * kPad);
  l.h = l.row_h + kTitleGap + l.rows * l.row_h + kPad;
  return l;
}

}  // namespace

void DrawWorldLegend(Canvas& cv, const View& view, const Theme& th,
                     const std::vector<CanvasDrawSink::LegendEntry>& entries,
                     const LegendAvoid& avoid, LegendState* state, double clock, float top_reserved,
                     float bottom_reserved) {
  if (entries.empty()) return;
  const FontRole f = FontRole::kSmall;
  const bool collapsed = state != nullptr && state->collapsed;
  const std::string title = collapsed ? "legend  +" : "legend  -";
  const float title_w = cv.TextSize(f, title).x;
  const float max_area = kLegendMaxShare * view.width() * view.height();
  const int n = static_cast<int>(entries.size());
  auto fits = [&](const Layout& l) {
    return l.w * l.h <= max_area &&
           l.w <= std::min(view.width() - 50, l.columns == 2 ? 0.6f * view.width() : 1e9f) &&
           l.h <= view.height() - top_reserved - bottom_reserved;
  };
  // The layouts that fit, fullest first: every entry in two columns where that fits in 60% of
  // the view's width, else in one; then fewer entries, the rest counted in a last line. Folded
  // (by a click): the title tab alone. Nothing fits: the title tab alone.
  std::vector<Layout> layouts;
  auto add_layouts = [&] {
    for (int shown = n; shown >= 1; --shown)
      for (int columns : {2, 1}) {
        if (columns == 2 && shown < 4) continue;
        const Layout l = Measure(cv, entries, shown, columns, collapsed, title_w);
        if (!fits(l)) continue;
        layouts.push_back(l);
        if (collapsed) return;  // folded: every layout is the same title tab
      }
    // Last, the title tab alone: where every fuller layout would cover a robot in every corner,
    // the legend folds rather than hide one.
    const Layout tab = Measure(cv, entries, 0, 1, true, title_w);
    if (!layouts.empty() && fits(tab)) layouts.push_back(tab);
  };
  const float x_left = view.min.x + 40;
  const float y_top = view.min.y + top_reserved;
  auto corner_min = [&](const Layout& l, int c) {
    return ImVec2((c % 2 == 0) ? x_left : view.max.x - 10 - l.w,
                  c < 2 ? y_top : view.max.y - bottom_reserved - l.h);
  };
  // Robots whose bodies reach under the box, and trail points inside it.
  auto robots_under = [&](ImVec2 lo, ImVec2 hi) {
    long long count = 0;
    for (std::size_t i = 0; i < avoid.bodies.size(); ++i) {
      const ImVec2 p = avoid.bodies[i];
      const float r = i < avoid.body_radii.size() ? avoid.body_radii[i] : 0.0f;
      count += p.x + r >= lo.x && p.x - r <= hi.x && p.y + r >= lo.y && p.y - r <= hi.y;
    }
    return count;
  };
  auto trail_points_in = [&](ImVec2 lo, ImVec2 hi) {
    long long count = 0;
    for (const ImVec2& p : avoid.trails)
      count += p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    return count;
  };
  int corner = state != nullptr ? state->corner : -1;
  bool due = LegendCornerDue(state, clock);
  Layout l;
  bool have = false;
  // Between choices, the layout chosen with the corner while the entries, the fold and the fit
  // stay as they were.
  if (!due && state->entries == n && state->chosen_collapsed == collapsed && state->shown >= 0 &&
      state->shown <= n) {
    l = Measure(cv, entries, state->shown, state->columns, collapsed || state->shown == 0, title_w);
    have = fits(l) || state->shown == 0;
    // A robot driven under the kept legend: the corner is chosen anew now, not a second later.
    const ImVec2 lo = corner_min(l, corner);
    if (have && robots_under(lo, ImVec2(lo.x + l.w, lo.y + l.h)) > 0) due = true, have = false;
  }
  if (!have) {
    add_layouts();
    if (layouts.empty()) {
      l = Measure(cv, entries, 0, 1, true, title_w);  // the title tab alone
      if (l.w * l.h > max_area) return;
      layouts.push_back(l);
    }
    // The fullest layout with a corner that covers no robot; else the one covering the fewest
    // (the fuller on a tie). Between choices the corner stays and only the layout is chosen so.
    // Its corner: the fewest robots, then the fewest trail points (a robot outweighs any number
    // of them: a thousand robots' trails put tens of thousands in a corner); on a tie the
    // current one, then bottom left, bottom right, top right, top left.
    const std::vector<int> order =
        due ? std::vector<int>{corner, 2, 3, 1, 0} : std::vector<int>{corner};
    std::size_t pick = 0;
    long long fewest = -1;
    for (std::size_t k = 0; k < layouts.size() && fewest != 0; ++k) {
      long long least = -1;
      for (int c : order) {
        if (c < 0) continue;
        const ImVec2 lo = corner_min(layouts[k], c);
        const long long r = robots_under(lo, ImVec2(lo.x + layouts[k].w, lo.y + layouts[k].h));
        if (least < 0 || r < least) least = r;
      }
      if (fewest < 0 || least < fewest) fewest = least, pick = k;
    }
    l = layouts[pick];
    if (due) {
      long long best_robots = -1, best_trails = -1;
      for (int c : order) {
        if (c < 0) continue;
        const ImVec2 lo = corner_min(l, c), hi(lo.x + l.w, lo.y + l.h);
        const long long r = robots_under(lo, hi);
        if (best_robots >= 0 && r > best_robots) continue;
        const long long t = trail_points_in(lo, hi);
        if (best_robots < 0 || r < best_robots || t < best_trails)
          best_robots = r, best_trails = t, corner = c;
      }
    }
    if (state != nullptr) {
      if (due) state->corner = corner, state->chosen_at = clock;
      state->shown = l.rows == 0 ? 0 : l.shown, state->columns = l.columns;
      state->chosen_collapsed = collapsed, state->entries = n;
    }
  }
  const bool title_only = l.rows == 0;
  const ImVec2 lo = corner_min(l, corner), hi(lo.x + l.w, lo.y + l.h);
  cv.FillRect(lo, hi, th.backdrop.WithAlpha(0.88f), 3.0f);
  cv.StrokeRect(lo, hi, th.legend_border, 1.0f, 3.0f);
  cv.Text(ImVec2(lo.x + kPad, lo.y + 2), f, th.text, title);
  if (state != nullptr) {
    state->toggle_min = lo;
    state->toggle_max = ImVec2(hi.x, lo.y + l.row_h);
    state->box_min = lo, state->box_max = hi;
  }
  if (title_only) return;
  const int rows_per_col = (l.shown + l.columns - 1) / l.columns;
  for (int i = 0; i < l.shown; ++i) {
    const auto& e = entries[static_cast<std::size_t>(i)];
    const int col = i / rows_per_col, row = i % rows_per_col;
    const float x0 = lo.x + kPad + col * l.col_w;
    const float y = lo.y + l.row_h + kTitleGap + row * l.row_h;
    DrawSample(cv, th, e.mark, e.color, x0, x0 + kSample, y + l.row_h / 2);
    cv.Text(ImVec2(x0 + kSample + 8, y + 1), f, th.text, e.label);
  }
  if (l.shown < n) {
    const float y = lo.y + l.row_h + kTitleGap + rows_per_col * l.row_h;
    cv.Text(ImVec2(lo.x + kPad, y + 1), f, th.coordinates, MoreText(n - l.shown));
  }
}

}  // namespace formsim::app
