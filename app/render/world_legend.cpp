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

using LegendEntries = std::vector<CanvasDrawSink::LegendEntry>;

// Where in the view a legend may go, and what it would cover there.
class LegendSpace {
 public:
  LegendSpace(Canvas& cv, const View& view, const LegendEntries& entries, const LegendAvoid& avoid,
              bool collapsed, float title_w, float top_reserved, float bottom_reserved)
      : cv_(cv),
        view_(view),
        entries_(entries),
        avoid_(avoid),
        collapsed_(collapsed),
        title_w_(title_w),
        top_reserved_(top_reserved),
        bottom_reserved_(bottom_reserved),
        max_area_(kLegendMaxShare * view.width() * view.height()) {}

  // The largest area the legend takes (kLegendMaxShare of the view's).
  float MaxArea() const { return max_area_; }

  // The layout of the first `shown` entries in `columns` (0 entries or `collapsed`: the tab).
  Layout Measure(int shown, int columns, bool collapsed) const {
    return app::Measure(cv_, entries_, shown, columns, collapsed, title_w_);
  }

  // Within the largest share of the view, its width (two columns in 60% of it) and the height
  // left between the reserved bands.
  bool Fits(const Layout& l) const {
    return l.w * l.h <= max_area_ &&
           l.w <= std::min(view_.width() - 50, l.columns == 2 ? 0.6f * view_.width() : 1e9f) &&
           l.h <= view_.height() - top_reserved_ - bottom_reserved_;
  }

  // The layouts that fit, fullest first: every entry in two columns where that fits in 60% of
  // the view's width, else in one; then fewer entries, the rest counted in a last line. Folded
  // (by a click): the title tab alone. Nothing fits: none.
  std::vector<Layout> Candidates() const {
    std::vector<Layout> layouts;
    const int n = static_cast<int>(entries_.size());
    for (int shown = n; shown >= 1; --shown)
      for (int columns : {2, 1}) {
        if (columns == 2 && shown < 4) continue;
        const Layout l = Measure(shown, columns, collapsed_);
        if (!Fits(l)) continue;
        layouts.push_back(l);
        if (collapsed_) return layouts;  // folded: every layout is the same title tab
      }
    // Last, the title tab alone: where every fuller layout would cover a robot in every corner,
    // the legend folds rather than hide one.
    const Layout tab = Measure(0, 1, true);
    if (!layouts.empty() && Fits(tab)) layouts.push_back(tab);
    return layouts;
  }

  // The top left of `l` in corner `c` (0 top left, 1 top right, 2 bottom left, 3 bottom right).
  ImVec2 CornerMin(const Layout& l, int c) const {
    return ImVec2((c % 2 == 0) ? view_.min.x + 40 : view_.max.x - 10 - l.w,
                  c < 2 ? view_.min.y + top_reserved_ : view_.max.y - bottom_reserved_ - l.h);
  }

  // Robots whose bodies reach under the box [lo, hi].
  long long RobotsUnder(ImVec2 lo, ImVec2 hi) const {
    long long count = 0;
    for (std::size_t i = 0; i < avoid_.bodies.size(); ++i) {
      const ImVec2 p = avoid_.bodies[i];
      const float r = i < avoid_.body_radii.size() ? avoid_.body_radii[i] : 0.0f;
      count += p.x + r >= lo.x && p.x - r <= hi.x && p.y + r >= lo.y && p.y - r <= hi.y;
    }
    return count;
  }

  // Robots under `l` placed in corner `c`.
  long long RobotsUnder(const Layout& l, int c) const {
    const ImVec2 lo = CornerMin(l, c);
    return RobotsUnder(lo, ImVec2(lo.x + l.w, lo.y + l.h));
  }

  // Trail points inside the box [lo, hi].
  long long TrailPointsIn(ImVec2 lo, ImVec2 hi) const {
    long long count = 0;
    for (const ImVec2& p : avoid_.trails)
      count += p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    return count;
  }

 private:
  Canvas& cv_;
  const View& view_;
  const LegendEntries& entries_;
  const LegendAvoid& avoid_;
  bool collapsed_;
  float title_w_, top_reserved_, bottom_reserved_;
  float max_area_;
};

// Between choices, the layout chosen with the corner while the entries, the fold and the fit
// stay as they were: true and `*l` when there is one. A robot driven under it makes the corner
// `*due` now, not a second later.
bool KeptLegendLayout(const LegendSpace& space, const LegendState* state, int n, bool collapsed,
                      bool* due, Layout* l) {
  if (*due || state->entries != n || state->chosen_collapsed != collapsed || state->shown < 0 ||
      state->shown > n)
    return false;
  *l = space.Measure(state->shown, state->columns, collapsed || state->shown == 0);
  if (!space.Fits(*l) && state->shown != 0) return false;
  if (space.RobotsUnder(*l, state->corner) > 0) {
    *due = true;
    return false;
  }
  return true;
}

// The corner of `order` for `l` under the fewest robots, then the fewest trail points (a robot
// outweighs any number of them: a thousand robots' trails put tens of thousands in a corner);
// on a tie the earlier in `order`. `current` when `order` names none.
int QuietestLegendCorner(const LegendSpace& space, const Layout& l, const std::vector<int>& order,
                         int current) {
  int corner = current;
  long long best_robots = -1, best_trails = -1;
  for (int c : order) {
    if (c < 0) continue;
    const ImVec2 lo = space.CornerMin(l, c), hi(lo.x + l.w, lo.y + l.h);
    const long long r = space.RobotsUnder(lo, hi);
    if (best_robots >= 0 && r > best_robots) continue;
    const long long t = space.TrailPointsIn(lo, hi);
    if (best_robots < 0 || r < best_robots || t < best_trails)
      best_robots = r, best_trails = t, corner = c;
  }
  return corner;
}

// Chooses the layout into `*l` and, when `due`, its corner into `*corner`; false when not even
// the title tab fits. The fullest layout with a corner that covers no robot; else the one
// covering the fewest (the fuller on a tie). Between choices the corner stays and only the
// layout is chosen so. A corner is chosen among the current one, then bottom left, bottom
// right, top right, top left.
bool ChooseLegendLayout(const LegendSpace& space, bool due, int* corner, Layout* l) {
  std::vector<Layout> layouts = space.Candidates();
  if (layouts.empty()) {
    const Layout tab = space.Measure(0, 1, true);  // the title tab alone
    if (tab.w * tab.h > space.MaxArea()) return false;
    layouts.push_back(tab);
  }
  const std::vector<int> order =
      due ? std::vector<int>{*corner, 2, 3, 1, 0} : std::vector<int>{*corner};
  std::size_t pick = 0;
  long long fewest = -1;
  for (std::size_t k = 0; k < layouts.size() && fewest != 0; ++k) {
    long long least = -1;
    for (int c : order) {
      if (c < 0) continue;
      const long long r = space.RobotsUnder(layouts[k], c);
      if (least < 0 || r < least) least = r;
    }
    if (fewest < 0 || least < fewest) fewest = least, pick = k;
  }
  *l = layouts[pick];
  if (due) *corner = QuietestLegendCorner(space, *l, order, *corner);
  return true;
}

// The box at `lo` with its title tab, then the entries (a sample and a label each) column by
// column and the count of those left out. `state` (may be null) learns where the box and its
// tab are.
void DrawLegendBox(Canvas& cv, const Theme& th, const LegendEntries& entries, const Layout& l,
                   ImVec2 lo, const std::string& title, LegendState* state) {
  const FontRole f = FontRole::kSmall;
  const int n = static_cast<int>(entries.size());
  const ImVec2 hi(lo.x + l.w, lo.y + l.h);
  cv.FillRect(lo, hi, th.backdrop.WithAlpha(0.88f), 3.0f);
  cv.StrokeRect(lo, hi, th.legend_border, 1.0f, 3.0f);
  cv.Text(ImVec2(lo.x + kPad, lo.y + 2), f, th.text, title);
  if (state != nullptr) {
    state->toggle_min = lo;
    state->toggle_max = ImVec2(hi.x, lo.y + l.row_h);
    state->box_min = lo, state->box_max = hi;
  }
  if (l.rows == 0) return;  // the title tab alone
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

}  // namespace

WorldLegendPlan PlanWorldLegend(Canvas& cv, const View& view, const LegendEntries& entries,
                                const LegendAvoid& avoid, LegendState* state, double clock,
                                float top_reserved, float bottom_reserved) {
  WorldLegendPlan plan;
  if (entries.empty()) return plan;
  const bool collapsed = state != nullptr && state->collapsed;
  plan.title = collapsed ? "legend  +" : "legend  -";
  const LegendSpace space(cv, view, entries, avoid, collapsed,
                          cv.TextSize(FontRole::kSmall, plan.title).x, top_reserved,
                          bottom_reserved);
  const int n = static_cast<int>(entries.size());
  int corner = state != nullptr ? state->corner : -1;
  bool due = LegendCornerDue(state, clock);
  Layout l;
  if (!KeptLegendLayout(space, state, n, collapsed, &due, &l)) {
    if (!ChooseLegendLayout(space, due, &corner, &l)) return plan;
    if (state != nullptr) {
      if (due) state->corner = corner, state->chosen_at = clock;
      state->shown = l.rows == 0 ? 0 : l.shown, state->columns = l.columns;
      state->chosen_collapsed = collapsed, state->entries = n;
    }
  }
  plan.drawn = true;
  plan.lo = space.CornerMin(l, corner);
  plan.hi = ImVec2(plan.lo.x + l.w, plan.lo.y + l.h);
  plan.columns = l.columns, plan.rows = l.rows, plan.shown = l.shown;
  plan.col_w = l.col_w, plan.row_h = l.row_h, plan.w = l.w, plan.h = l.h;
  return plan;
}

void DrawPlannedWorldLegend(Canvas& cv, const Theme& th, const LegendEntries& entries,
                            const WorldLegendPlan& plan, LegendState* state) {
  if (!plan.drawn) return;
  Layout l;
  l.columns = plan.columns, l.rows = plan.rows, l.shown = plan.shown;
  l.col_w = plan.col_w, l.row_h = plan.row_h;
  l.w = plan.w, l.h = plan.h;
  DrawLegendBox(cv, th, entries, l, plan.lo, plan.title, state);
}

void DrawWorldLegend(Canvas& cv, const View& view, const Theme& th, const LegendEntries& entries,
                     const LegendAvoid& avoid, LegendState* state, double clock, float top_reserved,
                     float bottom_reserved) {
  DrawPlannedWorldLegend(
      cv, th, entries,
      PlanWorldLegend(cv, view, entries, avoid, state, clock, top_reserved, bottom_reserved),
      state);
}

}  // namespace formsim::app
