// The robot glyph cannot be misread (issue 46 item 1): every robot of every shipped scenario is
// drawn with its body centred on its pose and a slender notched heading arrow whose tip (the
// point farthest from the arrow's centroid) lies on its heading, read from the draw list; SVG
// snapshots group each robot as <g id="robot-NAME" class="robot"> with one class="heading" path
// pointing along the robot's final heading in timeseries.csv; the legend's body mark shows the
// arrow in the colour the world view draws it, in every theme.
#include <gtest/gtest.h>

#include <chrono>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "app/export/svg_writer.hpp"
#include "app/render/contrast.hpp"
#include "app/render/theme.hpp"
#include "sim/core/draw.hpp"
#include "sim/core/world.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::Scenario;
using testing::TempDir;

constexpr double kPi = 3.14159265358979323846;

double AngleDiff(double a, double b) {
  return std::abs(std::remainder(a - b, 2.0 * kPi));
}

// The area centroid of a simple polygon.
Vec2 Centroid(const std::vector<Vec2>& p) {
  double a = 0, cx = 0, cy = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 &u = p[i], &v = p[(i + 1) % p.size()];
    const double c = u.x * v.y - v.x * u.y;
    a += c, cx += (u.x + v.x) * c, cy += (u.y + v.y) * c;
  }
  return {cx / (3 * a), cy / (3 * a)};
}

// The point of `p` farthest from its centroid: the arrow's tip.
Vec2 Tip(const std::vector<Vec2>& p) {
  const Vec2 c = Centroid(p);
  Vec2 best = p[0];
  double d = -1;
  for (const Vec2& q : p)
    if ((q - c).Norm() > d) d = (q - c).Norm(), best = q;
  return best;
}

// A draw list: each robot group with the polygons and heading arrows drawn inside it.
class RecordingSink : public sim::DrawSink {
 public:
  struct Group {
    std::string id, cls;
    std::vector<std::vector<Vec2>> polygons;
    std::vector<sim::Color> polygon_fills;
    std::vector<std::vector<Vec2>> headings;
    std::vector<sim::Color> heading_fills, heading_bodies;
    int circles = 0;
  };
  std::vector<Group> groups;
  int open = 0, headings_outside = 0;

  void BeginGroup(const std::string& id, const std::string& cls) override {
    EXPECT_EQ(open, 0) << "robot groups do not nest: " << id;
    groups.push_back({id, cls, {}, {}, {}, {}, {}, 0});
    ++open;
  }
  void EndGroup() override {
    EXPECT_GT(open, 0);
    --open;
  }
  void Heading(const std::vector<Vec2>& pts, sim::Color fill, sim::Color body) override {
    if (open == 0) {
      ++headings_outside;
      return;
    }
    groups.back().headings.push_back(pts);
    groups.back().heading_fills.push_back(fill);
    groups.back().heading_bodies.push_back(body);
  }
  void Polygon(const std::vector<Vec2>& pts, sim::Color fill, sim::Color) override {
    if (open == 0) return;
    groups.back().polygons.push_back(pts);
    groups.back().polygon_fills.push_back(fill);
  }
  void Circle(Vec2, double, sim::Color, sim::Color) override {
    if (open > 0) ++groups.back().circles;
  }
  void Segment(Vec2, Vec2, sim::Color, float) override {}
  void Polyline(const std::vector<Vec2>&, sim::Color, float, bool) override {}
  void CovarianceEllipse(Vec2, double, double, double, double, sim::Color) override {}
  void Cross(Vec2, double, sim::Color) override {}
  void Text(Vec2, const std::string&, sim::Color, float, float) override {}
  void Flash(Vec2, double, sim::Color, float) override {}
};

// Checks the draw list of `exp` now against its robots' true poses. Returns the robots checked.
int CheckDrawList(const sim::Experiment& exp, const std::string& where) {
  RecordingSink sink;
  exp.Draw(sink);
  EXPECT_EQ(sink.open, 0) << where << ": a group left open";
  EXPECT_EQ(sink.headings_outside, 0) << where << ": a heading arrow outside a robot group";
  std::map<std::string, const RecordingSink::Group*> by_name;
  for (const RecordingSink::Group& g : sink.groups) {
    EXPECT_EQ(g.cls, "robot") << where << " " << g.id;
    EXPECT_EQ(g.id.rfind("robot-", 0), 0u) << where << " " << g.id;
    EXPECT_EQ(by_name.count(g.id.substr(6)), 0u) << where << ": two groups " << g.id;
    by_name[g.id.substr(6)] = &g;
  }
  int checked = 0;
  for (const auto& robot : exp.world().robots()) {
    const std::string at = where + " " + robot->name();
    const auto it = by_name.find(robot->name());
    if (it == by_name.end()) {
      ADD_FAILURE() << at << ": no robot-" << robot->name() << " group in the draw list";
      continue;
    }
    const RecordingSink::Group& g = *it->second;
    const Pose2 pose = robot->pose();
    // The body: one polygon centred on the pose (a sink without a scale draws every detail).
    if (g.polygons.size() != 1u || g.headings.size() != 1u) {
      ADD_FAILURE() << at << ": " << g.polygons.size() << " bodies, " << g.headings.size()
                    << " heading arrows (want one of each)";
      continue;
    }
    const Vec2 centre = Centroid(g.polygons[0]);
    EXPECT_LT((centre - pose.p()).Norm(), 1e-3) << at << ": body centre off its pose";
    // The arrow: its tip ahead of its centroid along the heading, on the heading axis.
    const std::vector<Vec2>& arrow = g.headings[0];
    const Vec2 c = Centroid(arrow), tip = Tip(arrow);
    EXPECT_EQ(tip.x, arrow[0].x) << at << ": the tip is not the arrow's first point";
    const double dir = std::atan2(tip.y - c.y, tip.x - c.x);
    EXPECT_LT(AngleDiff(dir, pose.theta) * 180.0 / kPi, 1.0) << at << ": arrow direction";
    const Vec2 u{std::cos(pose.theta), std::sin(pose.theta)};
    const Vec2 d = tip - pose.p();
    EXPECT_LT(std::abs(u.x * d.y - u.y * d.x), 1e-3) << at << ": tip off the heading axis";
    EXPECT_GT(u.x * d.x + u.y * d.y, 0.0) << at << ": tip behind the centre";
    // Slender: 2.5 times as long as wide (tip to barbs : barb to barb).
    const double length = (arrow[0] - (arrow[1] + arrow[3]) * 0.5).Norm();
    const double width = (arrow[1] - arrow[3]).Norm();
    EXPECT_NEAR(length / width, 2.5, 1e-6) << at;
    // Its ink contrasts with the body under it.
    EXPECT_GE(ContrastRatio(g.heading_fills[0], g.heading_bodies[0]), 4.0) << at;
    ++checked;
  }
  return checked;
}

// Every robot of every shipped scenario, at the start, after a few steps and in the middle of
// the run, at most 5 s in (half a second for the swarms of over 20 robots), which keeps the test
// to a second or two.
TEST(RobotGlyph, DrawListArrowFollowsEveryRobotsPoseInEveryShippedScenario) {
  const auto start = std::chrono::steady_clock::now();
  int scenarios = 0, robots = 0;
  for (const std::string& file : sim::ShippedScenarios()) {
    const std::string stem = std::filesystem::path(file).stem().string();
    sim::Session s(file, {}, -1);
    const double dt = s.exp().dt(), duration = s.exp().setup().duration;
    const bool large = s.exp().world().robots().size() > 20;
    const double later = std::min(0.5 * duration, large ? 0.5 : 5.0);
    robots += CheckDrawList(s.exp(), stem + " t=0");
    for (int k = 0; k < 5; ++k) s.Step();
    robots += CheckDrawList(s.exp(), stem + " 5 steps");
    while (s.exp().time() < later - 0.5 * dt && !s.exp().finished()) s.Step();
    robots += CheckDrawList(s.exp(), stem + " t=" + std::to_string(s.exp().time()));
    ++scenarios;
  }
  EXPECT_GE(scenarios, 27);
  EXPECT_GT(robots, 3 * 1100);
  std::cout << scenarios << " scenarios, " << robots << " robot glyphs checked in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
            << " s\n";
}

// The arrow's ink contrasts with the body in every theme and palette colour (as shown over the
// background), and the shape's tip is the point farthest from its centroid.
TEST(RobotGlyph, ArrowContrastsWithTheBodyInEveryTheme) {
  for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint, ThemeId::kHighContrast}) {
    const Theme& th = GetTheme(id);
    for (int i = 0; i < kPaletteSize; ++i) {
      const sim::Color body = sim::PaletteColor(i).WithAlpha(sim::kBodyAlpha);
      const sim::Color shown = Over(th.Fill(body), th.background);
      EXPECT_GE(ContrastRatio(th.HeadingInk(body), shown), 4.0) << th.name << " colour " << i;
    }
  }
  for (const auto& box : {std::array<double, 3>{-0.15, 0.15, 0.1}, {-0.1, 0.1, 0.1},
                          {-0.3, 0.3, 0.25}, {-9, 9, 6}}) {
    const auto a = sim::HeadingArrow(box[0], box[1], box[2]);
    const std::vector<Vec2> pts(a.begin(), a.end());
    EXPECT_EQ(Tip(pts).x, a[0].x);
    EXPECT_EQ(a[0].y, 0.0);
    EXPECT_LE(a[0].x, box[1]);
    EXPECT_GE(a[1].x, box[0]);
    EXPECT_LE(a[1].y, 0.6 * box[2] + 1e-12);
  }
}

// ---- SVG snapshots ----

struct SvgRobot {
  std::vector<Vec2> heading;  ///< SVG pixels, y down
  std::string body_fill, heading_fill;
  int headings = 0;
};
struct SvgScene {
  std::map<std::string, SvgRobot> robots;  ///< by group id
  std::string legend_body_fill, legend_heading_fill;
};

std::string Attr(const std::string& el, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = el.find(key);
  if (at == std::string::npos) return "";
  const std::size_t b = at + key.size();
  return el.substr(b, el.find('"', b) - b);
}

// A fill with its opacity, as written ("#rrggbb" or "#rrggbb@0.85").
std::string Fill(const std::string& el) {
  const std::string o = Attr(el, "fill-opacity");
  return Attr(el, "fill") + (o.empty() ? "" : "@" + o);
}

std::vector<Vec2> PathPoints(const std::string& d) {
  std::vector<Vec2> pts;
  std::istringstream in(d);
  std::string tok;
  while (in >> tok) {
    if (tok == "Z") break;
    const double x = std::stod(tok[0] == 'M' || tok[0] == 'L' ? tok.substr(1) : tok);
    double y = 0;
    in >> y;
    pts.push_back({x, y});
  }
  return pts;
}

// The robot groups of an SVG written by SvgDocument (one element a line) and the legend's body
// mark (its box, then its outline, then its arrow of class "heading-legend").
SvgScene ParseSvg(const std::string& svg) {
  SvgScene out;
  std::istringstream in(svg);
  std::string line, group, last_fill;
  int depth = 0;  // <g> depth inside the current robot group
  while (std::getline(in, line)) {
    if (line.rfind("<g ", 0) == 0 && Attr(line, "class") == "robot") {
      EXPECT_TRUE(group.empty()) << "robot groups nest: " << line;
      group = Attr(line, "id");
      EXPECT_EQ(out.robots.count(group), 0u) << "two groups " << group;
      out.robots[group];
      depth = 1;
      continue;
    }
    if (!group.empty()) {
      if (line.rfind("<g", 0) == 0) ++depth;
      if (line.rfind("</g>", 0) == 0 && --depth == 0) {
        group.clear();
        continue;
      }
      SvgRobot& r = out.robots[group];
      if (line.rfind("<path", 0) == 0 && Attr(line, "class") == "heading") {
        ++r.headings;
        r.heading = PathPoints(Attr(line, "d"));
        r.heading_fill = Fill(line);
      } else if (line.rfind("<path", 0) == 0 && r.body_fill.empty() &&
                 Attr(line, "fill") != "none") {
        r.body_fill = Fill(line);
      }
      continue;
    }
    if (line.rfind("<path", 0) == 0 && Attr(line, "class") == "heading-legend") {
      out.legend_body_fill = last_fill;
      out.legend_heading_fill = Fill(line);
    } else if (line.rfind("<path", 0) == 0 && Attr(line, "fill") != "none" &&
               Attr(line, "class").empty()) {
      last_fill = Fill(line);
    }
  }
  return out;
}

// The last row of a run's timeseries.csv: column name -> value.
std::map<std::string, double> LastRow(const std::string& csv_path) {
  std::istringstream in(ReadText(csv_path));
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::map<std::string, double> row;
  std::istringstream h(header), v(last);
  std::string name, value;
  while (std::getline(h, name, ',') && std::getline(v, value, ','))
    row[name] = value.empty() ? std::nan("") : std::stod(value);
  return row;
}

// Runs `stem` with an SVG snapshot (and `extra` flags) in a folder of its own, `tag` (tests run
// in parallel); the SVG's text and the last CSV row.
std::pair<std::string, std::map<std::string, double>> SnapshotRun(const std::string& stem,
                                                                  const std::string& extra,
                                                                  const std::string& tag) {
  const std::string dir = TempDir("robot_glyph_" + tag + "_" + stem);
  const std::string cmd = Binary() + " run " + Scenario(stem) + " --out " + dir +
                          "/run --snapshot " + dir + "/snap.svg -q " + extra;
  EXPECT_EQ(RunShell(cmd, dir + "/log.txt"), 0) << ReadText(dir + "/log.txt");
  return {ReadText(dir + "/snap.svg"), LastRow(dir + "/run/timeseries.csv")};
}

TEST(RobotGlyph, SvgSnapshotArrowsPointAlongTheFinalHeadings) {
  for (const char* stem : {"formation_cascade7", "formation_switching"}) {
    const auto [svg, row] = SnapshotRun(stem, "", "final");
    const SvgScene scene = ParseSvg(svg);
    int robots = 0;
    for (const auto& [column, value] : row) {
      const std::size_t dot = column.rfind(".theta");
      if (dot == std::string::npos || dot + 6 != column.size()) continue;
      const std::string name = column.substr(0, dot);
      const std::string id = XmlId("robot-" + name);
      const auto it = scene.robots.find(id);
      ASSERT_NE(it, scene.robots.end()) << stem << ": no <g id=\"" << id << "\" class=\"robot\">";
      const SvgRobot& r = it->second;
      ASSERT_EQ(r.headings, 1) << stem << " " << id << ": one class=\"heading\" path";
      ASSERT_EQ(r.heading.size(), 4u) << stem << " " << id;
      // Screen y points down: the world angle is atan2(-dy, dx).
      const Vec2 c = Centroid(r.heading), tip = Tip(r.heading);
      const double dir = std::atan2(-(tip.y - c.y), tip.x - c.x);
      EXPECT_LT(AngleDiff(dir, value) * 180.0 / kPi, 2.0)
          << stem << " " << name << ": arrow " << dir << " rad, final heading " << value;
      ++robots;
    }
    EXPECT_EQ(robots, static_cast<int>(scene.robots.size())) << stem;
    EXPECT_GE(robots, 5) << stem;
  }
}

TEST(RobotGlyph, XmlIdsAreSanitised) {
  EXPECT_EQ(XmlId("robot-R1"), "robot-R1");
  EXPECT_EQ(XmlId("robot-my robot <1>&\"x\""), "robot-my_robot__1___x_");
  EXPECT_EQ(XmlId("1abc"), "_1abc");
  EXPECT_EQ(XmlId(""), "_");
}

// The legend's body mark shows the arrow in the colour the world view draws it on a body of the
// legend's colour, in every theme (high-contrast drew black arrows while its legend showed white).
TEST(RobotGlyph, LegendBodyMarkUsesTheDrawnArrowColourInEveryTheme) {
  for (const char* theme : {"high-contrast", "light", "dark", "print"}) {
    const auto [svg, row] = SnapshotRun("formation_cascade7",
                                        std::string("--legend --theme ") + theme,
                                        std::string("legend_") + theme);
    const SvgScene scene = ParseSvg(svg);
    ASSERT_FALSE(scene.legend_heading_fill.empty()) << theme << ": no legend body mark";
    int same_body = 0;
    for (const auto& [id, r] : scene.robots) {
      if (r.body_fill != scene.legend_body_fill) continue;
      EXPECT_EQ(r.heading_fill, scene.legend_heading_fill) << theme << " " << id;
      ++same_body;
    }
    EXPECT_GE(same_body, 1) << theme << ": no robot with the legend's body colour "
                            << scene.legend_body_fill;
  }
}

}  // namespace
}  // namespace formsim::app
