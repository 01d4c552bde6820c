// Labels placed without collisions (names first, then links, then values; moved with a leader
// or dropped), and the world legend: compact, at most 15% of the view, in the corner with the
// fewest robots, kept for a second, collapsible. The same code draws window and headless frames.
#include <gtest/gtest.h>

#include "app/render/canvas_draw_sink.hpp"
#include "app/render/vector_canvas.hpp"
#include "app/render/world_legend.hpp"
#include "app/render/world_view.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

View Screen(float w, float h) {
  View v;
  v.min = ImVec2(0, 0);
  v.max = ImVec2(w, h);
  v.center = {0, 0};
  v.scale = 100;
  return v;
}

bool Overlap(const ImVec4& a, const ImVec4& b) {
  return a.x < b.z && b.x < a.z && a.y < b.w && b.y < a.w;
}

TEST(LabelPlacement, NoPlacedLabelsOverlapAndNamesComeFirst) {
  VectorCanvas cv(800, 600);
  const View view = Screen(800, 600);
  const Theme& th = GetTheme(ThemeId::kLight);
  CanvasDrawSink sink(cv, view, th);
  // A value first, then a link label and a name at the very same spot.
  sink.Text({0, 0}, "l est 0.512 m", {0.85f, 0.4f, 0, 1}, 0, 0);
  sink.Label({0, 0}, "0.500 m, 90.0°", {0.25f, 0.25f, 0.25f, 1}, sim::LabelRole::kLink, 0, 0);
  sink.Label({0, 0}, "R2", {0.1f, 0.1f, 0.1f, 1}, sim::LabelRole::kName, 0, 0);
  sink.FlushLabels();
  const auto& placed = sink.placed_labels();
  ASSERT_EQ(placed.size(), 3u);
  for (std::size_t i = 0; i < placed.size(); ++i)
    for (std::size_t j = i + 1; j < placed.size(); ++j)
      EXPECT_FALSE(Overlap(placed[i], placed[j])) << i << " overlaps " << j;
  // The name kept the asked-for spot (its box starts 2 px left of the anchor on screen).
  const ImVec2 anchor = view.ToScreen({0, 0});
  EXPECT_NEAR(placed[0].x, anchor.x - 2, 0.5);
  EXPECT_NEAR(placed[0].y, anchor.y - 1, 0.5);
}

TEST(LabelPlacement, LabelsKeepOffRobotBodiesOrAreDropped) {
  VectorCanvas cv(400, 300);
  const View view = Screen(400, 300);
  CanvasDrawSink sink(cv, view, GetTheme(ThemeId::kDark));
  const ImVec2 c = view.ToScreen({0, 0});
  const ImVec4 body(c.x - 30, c.y - 30, c.x + 30, c.y + 30);
  sink.SetKeepClear({body});
  sink.Label({0, 0}, "R3", {0.1f, 0.1f, 0.1f, 1}, sim::LabelRole::kName, 0, 0);
  for (int k = 0; k < 60; ++k) sink.Text({0, 0}, "value " + std::to_string(k), {0, 0, 0, 1}, 0, 0);
  sink.FlushLabels();
  for (const ImVec4& b : sink.placed_labels()) EXPECT_FALSE(Overlap(b, body));
  EXPECT_GT(sink.placed_labels().size(), 1u) << "labels move to free spots";
  EXPECT_GT(sink.dropped_labels(), 0) << "those without a free spot are left out";
  EXPECT_EQ(static_cast<int>(sink.placed_labels().size()) + sink.dropped_labels(), 61);
}

std::vector<CanvasDrawSink::LegendEntry> Entries(int n) {
  std::vector<CanvasDrawSink::LegendEntry> e;
  for (int i = 0; i < n; ++i)
    e.push_back({sim::LegendMark::kLine, sim::PaletteColor(i),
                 "mark number " + std::to_string(i) + " of the scene"});
  return e;
}

// Where a legend of `n` entries goes in each corner of `view`, with nothing to avoid: drawn once
// per corner with that corner kept (a choice made half a second before). `last` gets the state
// of the last one drawn.
std::vector<ImVec4> CornerBoxes(Canvas& cv, const View& view, int n, LegendState* last = nullptr) {
  std::vector<ImVec4> boxes(4);
  for (int c = 0; c < 4; ++c) {
    LegendState st;
    st.corner = c;
    st.chosen_at = 0.0;
    DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(n), LegendAvoid(), &st, 0.5, 60,
                    56);
    boxes[c] = ImVec4(st.box_min.x, st.box_min.y, st.box_max.x, st.box_max.y);
    if (last != nullptr) *last = st;
  }
  return boxes;
}

TEST(WorldLegend, TakesAtMostFifteenPercentAndAvoidsTheRobots) {
  for (auto [w, h] :
       std::vector<std::pair<float, float>>{{1920.f, 1080.f}, {900.f, 600.f}, {480.f, 320.f}}) {
    VectorCanvas cv(w, h);
    const View view = Screen(w, h);
    LegendAvoid avoid;
    // Robots in the bottom-left corner, where the legend goes by default.
    for (int k = 0; k < 5; ++k) avoid.bodies.push_back(ImVec2(60.f + 10 * k, h - 90.f));
    LegendState st;
    DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(14), avoid, &st, 0.0, 60, 56);
    const float area = (st.box_max.x - st.box_min.x) * (st.box_max.y - st.box_min.y);
    EXPECT_GT(area, 0.0f) << w;
    EXPECT_LE(area, kLegendMaxShare * w * h + 1) << w << "x" << h;
    EXPECT_NE(st.corner, 2) << "the robots are bottom left";
    for (const ImVec2& p : avoid.bodies)
      EXPECT_FALSE(p.x >= st.box_min.x && p.x <= st.box_max.x && p.y >= st.box_min.y &&
                   p.y <= st.box_max.y);
  }
}

// A robot whose centre lies just outside the legend's corner but whose body reaches under it
// counts as covered (presentation mode at UI scale 2 put the legend over R6 so).
TEST(WorldLegend, AvoidsARobotWhoseBodyReachesUnderIt) {
  VectorCanvas cv(1280, 800);
  const View view = Screen(1280, 800);
  LegendState free_st;
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(6), LegendAvoid(), &free_st, 0.0, 60,
                  56);
  const int preferred = free_st.corner;
  LegendAvoid avoid;
  avoid.bodies.push_back(
      ImVec2(0.5f * (free_st.box_min.x + free_st.box_max.x), free_st.box_min.y - 10.0f));
  avoid.body_radii.push_back(30.0f);
  LegendState st;
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(6), avoid, &st, 0.0, 60, 56);
  EXPECT_NE(st.corner, preferred) << "the body reaches 20 px under the legend there";
  const ImVec2 p = avoid.bodies[0];
  const float r = avoid.body_radii[0];
  EXPECT_FALSE(p.x + r >= st.box_min.x && p.x - r <= st.box_max.x && p.y + r >= st.box_min.y &&
               p.y - r <= st.box_max.y);
}

// Covering a robot is worse than covering any number of trail points: dense trails (a point a
// step, a thousand robots) must not push the legend over a robot.
TEST(WorldLegend, ARobotOutweighsAnyNumberOfTrailPoints) {
  VectorCanvas cv(1280, 800);
  const View view = Screen(1280, 800);
  const std::vector<ImVec4> boxes = CornerBoxes(cv, view, 6);
  LegendAvoid avoid;
  const ImVec4 b = boxes[2];  // bottom left, the first choice on a tie: one robot there
  avoid.bodies.push_back(ImVec2(0.5f * (b.x + b.z), 0.5f * (b.y + b.w)));
  for (int c : {0, 1, 3})  // 200 trail points in each other corner
    for (int k = 0; k < 200; ++k)
      avoid.trails.push_back(
          ImVec2(boxes[c].x + 2 + (k % 20) * (boxes[c].z - boxes[c].x - 4) / 20,
                 boxes[c].y + 2 + (k / 20) * (boxes[c].w - boxes[c].y - 4) / 10));
  LegendState st;
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(6), avoid, &st, 0.0, 60, 56);
  EXPECT_NE(st.corner, 2) << "the legend went over the robot to spare trail points";
}

// Where the full legend would cover a robot in every corner, it takes a smaller layout (one
// column, or fewer entries) that covers none, rather than hide a robot (presentation mode at UI
// scale 2, where two columns of eight entries span 60% of the view, hid R6 so).
TEST(WorldLegend, ShrinksRatherThanCoverARobot) {
  VectorCanvas cv(1280, 800);
  const View view = Screen(1280, 800);
  // The full legend's box in each corner.
  LegendState full;
  const std::vector<ImVec4> boxes = CornerBoxes(cv, view, 8, &full);
  ASSERT_EQ(full.shown, 8);
  ASSERT_EQ(full.columns, 2) << "eight entries fit in two columns at 1280x800";
  // A robot under each box, at the box's side away from the view's edges.
  LegendAvoid avoid;
  for (int c = 0; c < 4; ++c) {
    const ImVec4 b = boxes[c];
    avoid.bodies.push_back(ImVec2(c % 2 == 0 ? b.z - 8 : b.x + 8, c < 2 ? b.w - 8 : b.y + 8));
    avoid.body_radii.push_back(4.0f);
  }
  LegendState st;
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(8), avoid, &st, 0.0, 60, 56);
  for (std::size_t i = 0; i < avoid.bodies.size(); ++i) {
    const ImVec2 p = avoid.bodies[i];
    const float r = avoid.body_radii[i];
    EXPECT_FALSE(p.x + r >= st.box_min.x && p.x - r <= st.box_max.x && p.y + r >= st.box_min.y &&
                 p.y - r <= st.box_max.y)
        << "robot " << i << " is under the legend";
  }
  EXPECT_TRUE(st.columns == 1 || st.shown < 8) << "a smaller layout than the full one";
  EXPECT_GT(st.shown, 0) << "one column of all eight fits beside the robots";
  // Kept for the rest of the second, with the same layout.
  const ImVec2 lo = st.box_min, hi = st.box_max;
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(8), avoid, &st, 0.5, 60, 56);
  EXPECT_EQ(st.box_min.x, lo.x);
  EXPECT_EQ(st.box_max.y, hi.y);
}

TEST(WorldLegend, CornerIsReChosenOnceASecondAtOnceForARobotAndCollapses) {
  VectorCanvas cv(1280, 800);
  const View view = Screen(1280, 800);
  LegendState st;
  LegendAvoid avoid;
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(6), avoid, &st, 10.0, 60, 56);
  const int first = st.corner;
  const float open_h = st.box_max.y - st.box_min.y;
  // Trail points arriving in its corner wait for the next choice, a second later.
  for (int k = 0; k < 20; ++k)
    avoid.trails.push_back(ImVec2(0.5f * (st.box_min.x + st.box_max.x), st.box_min.y + 3.0f * k));
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(6), avoid, &st, 10.5, 60, 56);
  EXPECT_EQ(st.corner, first);
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(6), avoid, &st, 11.1, 60, 56);
  EXPECT_NE(st.corner, first);
  // A robot driven under it moves it at once (issue 46: the legend never hides a robot).
  const int second = st.corner;
  avoid.bodies.push_back(ImVec2(0.5f * (st.box_min.x + st.box_max.x), 0.5f * (st.box_min.y + st.box_max.y)));
  avoid.body_radii.push_back(10.0f);
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(6), avoid, &st, 11.2, 60, 56);
  EXPECT_NE(st.corner, second);
  st.collapsed = true;
  DrawWorldLegend(cv, view, GetTheme(ThemeId::kLight), Entries(6), avoid, &st, 11.3, 60, 56);
  EXPECT_LT(st.box_max.y - st.box_min.y, 0.5f * open_h) << "collapsed: a title tab";
}

// The pointer's coordinates, bottom left, never run under the scale bar, bottom right: in a narrow
// view (a UI scale of 2 at 1920x1080 gives one about 500 logical pixels wide) they go above it.
TEST(CoordinateReadout, KeepsOffTheScaleBarInNarrowViews) {
  sim::Session s(testing::Scenario("formation_cascade7"), {}, -1);
  const Theme& th = GetTheme(ThemeId::kLight);
  int moved = 0;
  for (const float w : {1200.0f, 800.0f, 500.0f, 380.0f, 300.0f}) {
    VectorCanvas cv(static_cast<int>(w), 600);
    View view;
    AutoFit fit;
    FrameWorldView(s.exp(), w, 600, view, fit, true);
    WorldViewReport report;
    WorldViewOptions opt;
    opt.report = &report;
    DrawWorldView(cv, view, s.exp(), th, opt);
    const ImVec4 bar = report.scale_bar_box;
    ASSERT_GT(bar.z, bar.x) << "a scale bar at width " << w;
    for (const float text_w : {150.0f, 230.0f, 320.0f}) {
      const ImVec2 ext(text_w, 15);
      const ImVec2 at = CoordinateReadoutPos(view, ext, bar);
      const ImVec4 box(at.x, at.y, at.x + ext.x, at.y + ext.y);
      EXPECT_FALSE(Overlap(box, bar)) << "width " << w << ", text " << text_w;
      EXPECT_GE(at.y, view.min.y) << "width " << w;
      moved += at.y != view.max.y - 42;
    }
  }
  EXPECT_GT(moved, 0) << "some narrow view needs the readout moved";
  EXPECT_LT(moved, 15) << "a wide view keeps it at its place";
}

}  // namespace
}  // namespace formsim::app
