#include "sim/inspection/inspection_config.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "control/inspection/fuzzy_controller.hpp"
#include "control/inspection/paper_frame.hpp"
#include "sim/core/bounded_file.hpp"
#include "sim/core/multirate.hpp"
#include "sim/core/number_format.hpp"

namespace fs = std::filesystem;

namespace formsim::sim::inspection {

using control::inspection::AzimuthDirection;
using control::inspection::Rad;

const std::vector<std::string>& PairChoiceNames() {
  static const std::vector<std::string> names = {"best_angle", "nearest"};
  return names;
}

const std::vector<std::string>& NavSourceNames() {
  static const std::vector<std::string> names = {"kalman", "classical", "raw", "dead_reckoning",
                                                 "truth"};
  return names;
}

control::inspection::TrilaterationDef InspectionConfig::Trilateration() const {
  control::inspection::TrilaterationDef def;
  def.range_tolerance = range_tolerance;
  def.pair = static_cast<control::inspection::PairChoice>(pair_choice);
  def.min_subtended = Rad(min_subtended_deg);
  def.angle_tolerance = Rad(angle_tolerance_deg);
  def.max_range = max_range;
  return def;
}

control::inspection::HeadingFilterDef InspectionConfig::Heading() const {
  control::inspection::HeadingFilterDef def;
  def.limit = Rad(heading_limit_deg);
  def.window = heading_window;
  def.reacquire_after = heading_reacquire;
  return def;
}

control::inspection::Route InspectionConfig::MakeRoute() const {
  return control::inspection::Route::UShape(route_start, straight_length, turn_radius, turn_right);
}

control::inspection::PostMap InspectionConfig::SurveyedMap() const {
  control::inspection::PostMap map;
  map.radius = post_radius;
  for (const auto& p : posts) map.posts.push_back(p.surveyed);
  return map;
}

namespace {

// Bounds on the generated posts: each is a Box2D body and a candidate of every identification.
constexpr int kMaxTurnPosts = 1000;
constexpr double kMaxPosts = 10000;

// Lengths and coordinates of the route and posts (the core bounds bodies and obstacles).
const Tune kLength = Tune().In(1e-3, 1e3);
const Tune kCoordinate = Tune().In(-1e3, 1e3);

void Check(YamlReader& r, const std::string& key, const Tune& valid, double v) {
  if (const std::string why = valid.Check(v); !why.empty()) r.Fail(key, why);
}

// Posts along both sides of both straights and around the turn, in driving order.
std::vector<Vec2> GeneratePosts(const InspectionConfig& c) {
  std::vector<Vec2> out;
  const double side = c.turn_right ? 1.0 : -1.0;
  const double x1 = c.route_start.x, x2 = c.route_start.x + 2.0 * side * c.turn_radius;
  const double y0 = c.route_start.y, y1 = c.route_start.y + c.straight_length;
  const int n = static_cast<int>(std::floor(c.straight_length / c.post_spacing + 1e-9));
  const double shift = c.post_stagger ? 0.5 * c.post_spacing : 0.0;
  for (int k = 0; k <= n; ++k) {
    out.push_back({x1 - side * c.post_side_offset, y0 + k * c.post_spacing});
    if (y0 + k * c.post_spacing + shift <= y1 + 1e-9)
      out.push_back({x1 + side * c.post_side_offset, y0 + k * c.post_spacing + shift});
  }
  const Vec2 centre{x1 + side * c.turn_radius, y1};
  for (int k = 0; k < c.turn_outer; ++k) {
    const double a = -side * control::kPi / 2.0 + side * control::kPi * (k + 0.5) / c.turn_outer;
    out.push_back(centre + AzimuthDirection(a) * (c.turn_radius + c.post_side_offset));
  }
  const double inner_r = c.turn_radius - c.post_side_offset;
  if (c.turn_inner > 0 && inner_r < 0.3) {
    out.push_back(centre);
  } else {
    for (int k = 0; k < c.turn_inner; ++k) {
      const double a = -side * control::kPi / 2.0 + side * control::kPi * (k + 0.5) / c.turn_inner;
      out.push_back(centre + AzimuthDirection(a) * inner_r);
    }
  }
  for (int k = n; k >= 0; --k) {
    out.push_back({x2 + side * c.post_side_offset, y0 + k * c.post_spacing});
    if (y0 + k * c.post_spacing + shift <= y1 + 1e-9)
      out.push_back({x2 - side * c.post_side_offset, y0 + k * c.post_spacing + shift});
  }
  return out;
}

// route: the U the robot drives (Fig. 7).
void ReadInspectionRoute(YamlReader& root, InspectionConfig& c) {
  YamlReader r = root.Map("route");
  const auto s = r.Doubles("start", {c.route_start.x, c.route_start.y}, 2);
  for (double v : s) Check(r, "start", kCoordinate, v);
  c.route_start = {s[0], s[1]};
  c.straight_length = r.Double("straight_length", c.straight_length, kLength);
  c.turn_radius = r.Double("turn_radius", c.turn_radius, kLength);
  c.turn_right = r.Choice("turn", {"left", "right"}, 1) == 1;
  r.Finish();
}

// The layout keys of posts (the posts themselves are generated from them afterwards).
void ReadInspectionPostLayout(YamlReader& p, InspectionConfig& c) {
  c.post_radius = p.Double("radius", c.post_radius, Tune().In(1e-3, 1.0));
  // The layout applies on reset: the posts are bodies of the world built then.
  const std::string gp = "Localisation/posts";
  c.post_spacing = p.Real("spacing", c.post_spacing,
                          Tune("post spacing", "m")
                              .In(1e-3, 1e3)
                              .Slider(1.0, 18.0)
                              .Group(gp)
                              .OnReset()
                              .Help("Distance between two posts along each side of the route"));
  c.post_side_offset = p.Real("side_offset", c.post_side_offset,
                              Tune("post side offset", "m")
                                  .In(1e-3, 1e3)
                                  .Slider(0.5, 6.0)
                                  .Group(gp)
                                  .OnReset()
                                  .Help("Distance of the post rows from the route's centre line"));
  c.post_stagger = p.Bool("stagger", c.post_stagger);
  c.turn_outer = p.Int("turn_outer", c.turn_outer, Tune().In(0, kMaxTurnPosts));
  c.turn_inner = p.Int("turn_inner", c.turn_inner, Tune().In(0, kMaxTurnPosts));
  c.survey_sigma = p.Real("survey_sigma", c.survey_sigma,
                          Tune("post survey error σ", "m")
                              .AtLeast(0)
                              .AtMost(10)
                              .Slider(0.0, 0.2)
                              .Group("Noise/survey")
                              .OnReset());
}

// posts: the layout, its bounds, then the generated posts with their survey errors, less the
// omitted ones.
void ReadInspectionPosts(YamlReader& root, Rng& survey, InspectionConfig& c) {
  YamlReader p = root.Map("posts");
  ReadInspectionPostLayout(p, c);
  const std::vector<std::string> omit = p.Strings("omit", {});
  if (c.post_spacing < 4.0 * c.post_radius)
    p.Fail("spacing", "must be at least two post diameters");
  if (c.post_side_offset <= c.post_radius) p.Fail("side_offset", "must exceed the post radius");
  const double per_side = std::floor(c.straight_length / c.post_spacing + 1e-9) + 1.0;
  if (4.0 * per_side > kMaxPosts)
    p.Fail("spacing", "gives " + FormatDouble(4.0 * per_side) +
                          " posts along the straights (at most " + FormatDouble(kMaxPosts) +
                          "): increase the spacing");
  const std::vector<Vec2> pos = GeneratePosts(c);
  std::set<std::string> names;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    InspectionPost post;
    post.name = "P" + std::to_string(i + 1);
    post.position = pos[i];
    // Survey errors are drawn for every generated post, omitted or not, so omitting a post
    // does not change the others.
    post.surveyed = {pos[i].x + survey.Normal(0.0, c.survey_sigma),
                     pos[i].y + survey.Normal(0.0, c.survey_sigma)};
    names.insert(post.name);
    if (std::find(omit.begin(), omit.end(), post.name) == omit.end()) c.posts.push_back(post);
  }
  for (const auto& name : omit)
    if (!names.count(name))
      p.Fail("omit",
             "no post named '" + name + "' (posts are P1..P" + std::to_string(pos.size()) + ")");
  p.Finish();
}

// obstacles: the shared block, whose names must not take a reference post's.
void ReadInspectionObstacles(YamlReader& root, InspectionConfig& c) {
  c.obstacles = ReadObstacles(root);
  for (const ObstacleDef& o : c.obstacles)
    for (const InspectionPost& p : c.posts)
      if (o.name == p.name)
        root.Fail("obstacles", "obstacle name '" + o.name + "' is taken by a reference post");
}

// robot: its name, where it starts relative to the route, its body and its drive.
void ReadInspectionRobot(YamlReader& root, InspectionConfig& c) {
  YamlReader r = root.Map("robot");
  c.body = DefaultRobotDef();
  c.body.name = r.String("name", "R1");
  c.body.half_length = 0.45;
  c.body.half_width = 0.3;
  c.body.mass = 40.0;
  YamlReader start = r.Map("start");
  c.start_lateral = start.Double("lateral", c.start_lateral);
  c.start_along = start.Double("along", c.start_along);
  c.start_heading_deg = start.Double("heading_deg", c.start_heading_deg);
  if (std::abs(c.start_lateral) > 1.5)
    start.Fail("lateral", "must be within the fuzzy input range [-1.5, 1.5] m");
  if (c.start_along < 0 || c.start_along >= c.straight_length)
    start.Fail("along", "must lie on the first straight");
  if (std::abs(c.start_heading_deg) > 45) start.Fail("heading_deg", "must be within ±45°");
  start.Finish();
  YamlReader body = r.Map("body");
  ReadRobotBody(body, c.body);
  YamlReader drive = r.Map("drive");
  c.drive = ReadSteeredDrive(drive);
  r.Finish();
}

// localisation: the post detector's gates and the trilateration's choices.
void ReadInspectionLocalisation(YamlReader& root, InspectionConfig& c) {
  YamlReader l = root.Map("localisation");
  const std::string g = "Localisation/laser";
  auto& d = c.detector;
  d.gate = l.Real("gate", d.gate,
                  Tune("identification gate", "m").Above(0).AtMost(1e3).Slider(0.05, 1.4).Group(g));
  if (d.gate >= 0.5 * c.post_spacing)
    l.Fail("gate", "must be below half the post spacing, else neighbouring posts are confused");
  d.fit_tolerance =
      l.Real("fit_tolerance", d.fit_tolerance,
             Tune("circle fit tolerance", "m").Above(0).AtMost(10).Slider(0.005, 0.2).Group(g));
  d.min_beams =
      l.Integer("min_beams", d.min_beams,
                Tune("min beams per post").AtLeast(1).AtMost(10000).Slider(1, 10).Group(g));
  c.max_range = l.Real("max_range", c.max_range,
                       Tune("max post range", "m").Above(0).AtMost(1e3).Slider(1.0, 30.0).Group(g));
  c.pair_choice =
      l.Pick("pair", PairChoiceNames(), c.pair_choice,
             Tune("fix from the pair")
                 .Group(g)
                 .Help("best_angle: the two posts whose rays cross closest to 90° (the "
                       "smallest dilution of precision); nearest: the two nearest posts"));
  c.min_subtended_deg =
      l.Real("min_subtended_deg", c.min_subtended_deg,
             Tune("min angle between posts", "deg").Above(0).Below(90).Slider(1.0, 89.0).Group(g));
  c.angle_tolerance_deg =
      l.Real("angle_tolerance_deg", c.angle_tolerance_deg,
             Tune("angle consistency", "deg").Above(0).AtMost(180).Slider(0.1, 20.0).Group(g));
  c.range_tolerance =
      l.Real("range_tolerance", c.range_tolerance,
             Tune("circle miss tolerance", "m").AtLeast(0).AtMost(10).Slider(0.0, 0.5).Group(g));
  d.cluster_jump = l.Double("cluster_jump", d.cluster_jump, Tune().Above(0).AtMost(1e3));
  d.span_tolerance = l.Double("span_tolerance", d.span_tolerance, Tune().AtLeast(0).AtMost(1e3));
  l.Finish();
}

// estimation.kalman: the per-axis Kalman filter.
void ReadInspectionKalman(YamlReader& e, InspectionConfig& c) {
  YamlReader k = e.Map("kalman");
  const std::string gk = "Estimation/Kalman";
  auto& kf = c.kalman;
  kf.q_per_m =
      k.Real("q_per_m", kf.q_per_m,
             Tune("Q per metre", "m²/m").AtLeast(0).AtMost(100).Slider(1e-7, 1e-1, kLog).Group(gk));
  kf.q_per_s = k.Real(
      "q_per_s", kf.q_per_s,
      Tune("Q per second", "m²/s").AtLeast(0).AtMost(100).Slider(1e-8, 1e-1, kLog).Group(gk));
  kf.r = k.Real("r", kf.r,
                Tune("R (fix variance)", "m²").In(1e-10, 100).Slider(1e-6, 1.0, kLog).Group(gk));
  kf.nis_gate = k.Real("nis_gate", kf.nis_gate,
                       Tune("innovation gate (≤0 off)").In(-1e6, 1e6).Slider(0.0, 100.0).Group(gk));
  kf.reacquire_after =
      k.Integer("reacquire_after", kf.reacquire_after,
                Tune("re-init after gated").AtLeast(1).AtMost(1000000).Slider(1, 200).Group(gk));
  kf.p0 = k.Double("p0", kf.p0, Tune().In(1e-10, 1e6));
  k.Finish();
}

// estimation.classical and estimation.heading: the paper's limiting and averaging filters.
void ReadInspectionClassicFilters(YamlReader& e, InspectionConfig& c) {
  YamlReader cl = e.Map("classical");
  const std::string gc = "Estimation/classical";
  c.limit.max_step =
      cl.Real("limit_step", c.limit.max_step,
              Tune("limit step", "m").Above(0).AtMost(1e3).Slider(0.01, 2.0).Group(gc));
  c.limit.max_rate =
      cl.Real("limit_rate", c.limit.max_rate,
              Tune("limit rate", "m/s").AtLeast(0).AtMost(1e3).Slider(0.0, 5.0).Group(gc));
  c.mean_window = cl.Integer("mean_window", c.mean_window,
                             Tune("mean window").In(1, 100).Slider(1, 50).Group(gc));
  c.limit.reacquire_after =
      cl.Int("reacquire_after", c.limit.reacquire_after, Tune().AtLeast(1).AtMost(1000000));
  cl.Finish();
  YamlReader h = e.Map("heading");
  const std::string gh = "Estimation/heading";
  c.heading_limit_deg =
      h.Real("limit_deg", c.heading_limit_deg,
             Tune("heading limit", "deg").Above(0).AtMost(180).Slider(0.5, 45.0).Group(gh));
  c.heading_window = h.Integer("mean_window", c.heading_window,
                               Tune("heading mean window").In(1, 100).Slider(1, 50).Group(gh));
  c.heading_reacquire =
      h.Int("reacquire_after", c.heading_reacquire, Tune().AtLeast(1).AtMost(1000000));
  h.Finish();
}

// estimation: which estimate steers the robot, and the filters that make each.
void ReadInspectionEstimation(YamlReader& root, InspectionConfig& c) {
  YamlReader e = root.Map("estimation");
  c.source = e.Pick("controller_source", NavSourceNames(), c.source,
                    Tune("controller uses").Group("Estimation/source"));
  ReadInspectionKalman(e, c);
  ReadInspectionClassicFilters(e, c);
  e.Finish();
}

// control: the rate of the fuzzy controller and its turn feed-forward.
void ReadInspectionControl(YamlReader& root, const ExperimentSetup& setup, InspectionConfig& c) {
  YamlReader r = root.Map("control");
  const std::string g = "Gains/fuzzy";
  c.feedforward = r.Flag("feedforward", c.feedforward, Tune("turn feed-forward").Group(g));
  c.control_rate_hz =
      r.Real("rate_hz", c.control_rate_hz,
             Tune("control rate", "Hz").Above(0).AtMost(1e6).Slider(1.0, 50.0).Group(g));
  c.control_every = RateSteps(r, "rate_hz", c.control_rate_hz, setup.dt);
  r.Finish();
}

// fuzzy.file: the rule base, read and loaded once here so that a broken one is a scenario error
// at this key.
void ReadInspectionRuleBase(YamlReader& f, InspectionConfig& c) {
  c.fuzzy_file =
      fs::path(f.FilePath("file", "../fuzzy/inspection.fll")).lexically_normal().string();
  std::error_code ec;
  if (!fs::is_regular_file(c.fuzzy_file, ec))
    f.Fail("file", "cannot open the rule base '" + c.fuzzy_file +
                       "' (relative paths start at the scenario's folder)");
  try {
    c.fuzzy_text = ReadBoundedFile(c.fuzzy_file);
  } catch (const FileReadError& e) {
    f.Fail("file", "the rule base " + std::string(e.what()));
  }
  // Checked here, so that a broken rule base is a scenario error at this key (also on reset).
  try {
    control::inspection::FuzzyController check;
    check.LoadText(c.fuzzy_text, c.fuzzy_file);
  } catch (const std::exception& e) {
    f.Fail("file", e.what());
  }
}

// fuzzy: the rule base and the scales of its inputs.
void ReadInspectionFuzzy(YamlReader& root, InspectionConfig& c) {
  YamlReader f = root.Map("fuzzy");
  ReadInspectionRuleBase(f, c);
  const std::string gf = "Gains/fuzzy";
  c.fuzzy_s_scale =
      f.Real("s_scale", c.fuzzy_s_scale,
             Tune("offset term scale")
                 .In(1e-3, 1e3)
                 .Slider(0.1, 10.0, kLog)
                 .Group(gf)
                 .Help("Stretches the universe and every term of the input s: 2 doubles "
                       "the width of every offset term (1 = the rule base as written)"));
  c.fuzzy_dphi_scale = f.Real("dphi_scale", c.fuzzy_dphi_scale,
                              Tune("heading term scale")
                                  .In(1e-3, 1e3)
                                  .Slider(0.1, 10.0, kLog)
                                  .Group(gf)
                                  .Help("Stretches the universe and every term of the input dphi "
                                        "(1 = the rule base as written)"));
  f.Finish();
}

// metrics: the bounds the run is scored against.
void ReadInspectionMetrics(YamlReader& root, InspectionConfig& c) {
  YamlReader m = root.Map("metrics");
  c.lateral_bound = m.Double("lateral_bound", c.lateral_bound, Tune().Above(0).AtMost(1e3));
  c.transient_m = m.Double("transient_m", c.transient_m, Tune().AtLeast(0).AtMost(1e4));
  m.Finish();
}

}  // namespace

// The sections are read in the scenario's order, which is also the order of the first error
// reported and of the tunables declared.
InspectionConfig ReadInspectionConfig(YamlReader& root, const ExperimentSetup& setup, Rng survey) {
  InspectionConfig c;
  {
    YamlReader w = root.Map("world");
    c.world = ReadWorldDef(w);
  }
  c.patches = ReadPatches(root);
  ReadInspectionRoute(root, c);
  ReadInspectionPosts(root, survey, c);
  ReadInspectionObstacles(root, c);
  ReadInspectionRobot(root, c);
  {
    YamlReader l = root.Map("laser");
    c.laser = ReadLaserScanner(l, setup.dt, &c.laser_every);
  }
  {
    YamlReader o = root.Map("odometry");
    c.odometry = ReadWheelOdometry(o);
  }
  ReadInspectionLocalisation(root, c);
  ReadInspectionEstimation(root, c);
  ReadInspectionControl(root, setup, c);
  ReadInspectionFuzzy(root, c);
  ReadInspectionMetrics(root, c);
  return c;
}

}  // namespace formsim::sim::inspection
