#include "sim/inspection/inspection_config.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "control/inspection/paper_frame.hpp"

namespace formsim::sim {

using control::inspection::AzimuthDirection;
using control::inspection::Rad;

const std::vector<std::string>& NavSourceNames() {
  static const std::vector<std::string> names = {"kalman", "classical", "raw", "dead_reckoning",
                                                 "truth"};
  return names;
}

control::inspection::TrilaterationDef InspectionConfig::Trilateration() const {
  control::inspection::TrilaterationDef def;
  def.range_tolerance = range_tolerance;
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

}  // namespace

InspectionConfig ReadInspectionConfig(YamlReader& root, const ExperimentSetup& setup, Rng survey) {
  InspectionConfig c;
  {
    YamlReader r = root.Map("route");
    const auto s = r.Doubles("start", {c.route_start.x, c.route_start.y}, 2);
    c.route_start = {s[0], s[1]};
    c.straight_length = r.Double("straight_length", c.straight_length);
    c.turn_radius = r.Double("turn_radius", c.turn_radius);
    c.turn_right = r.Choice("turn", {"left", "right"}, 1) == 1;
    if (c.straight_length <= 0) r.Fail("straight_length", "must be positive");
    if (c.turn_radius <= 0) r.Fail("turn_radius", "must be positive");
    r.Finish();
  }
  std::vector<std::string> omit;
  {
    YamlReader p = root.Map("posts");
    c.post_radius = p.Double("radius", c.post_radius);
    c.post_spacing = p.Double("spacing", c.post_spacing);
    c.post_side_offset = p.Double("side_offset", c.post_side_offset);
    c.post_stagger = p.Bool("stagger", c.post_stagger);
    c.turn_outer = p.Int("turn_outer", c.turn_outer);
    c.turn_inner = p.Int("turn_inner", c.turn_inner);
    c.survey_sigma = p.Double("survey_sigma", c.survey_sigma);
    omit = p.Strings("omit", {});
    if (c.post_radius <= 0 || c.post_radius > 1.0) p.Fail("radius", "must be in (0, 1] m");
    if (c.post_spacing < 4.0 * c.post_radius)
      p.Fail("spacing", "must be at least two post diameters");
    if (c.post_side_offset <= c.post_radius) p.Fail("side_offset", "must exceed the post radius");
    if (c.turn_outer < 0) p.Fail("turn_outer", "must be >= 0");
    if (c.turn_inner < 0) p.Fail("turn_inner", "must be >= 0");
    if (c.survey_sigma < 0) p.Fail("survey_sigma", "must be >= 0");
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
  {
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
  {
    YamlReader l = root.Map("laser");
    c.laser = ReadLaserScanner(l);
  }
  {
    YamlReader o = root.Map("odometry");
    c.odometry = ReadWheelOdometry(o);
  }
  {
    YamlReader l = root.Map("localisation");
    auto& d = c.detector;
    d.min_beams = l.Int("min_beams", d.min_beams);
    d.cluster_jump = l.Double("cluster_jump", d.cluster_jump);
    d.span_tolerance = l.Double("span_tolerance", d.span_tolerance);
    d.fit_tolerance = l.Double("fit_tolerance", d.fit_tolerance);
    d.gate = l.Double("gate", d.gate);
    c.range_tolerance = l.Double("range_tolerance", c.range_tolerance);
    c.min_subtended_deg = l.Double("min_subtended_deg", c.min_subtended_deg);
    c.angle_tolerance_deg = l.Double("angle_tolerance_deg", c.angle_tolerance_deg);
    c.max_range = l.Double("max_range", c.max_range);
    if (d.min_beams < 1) l.Fail("min_beams", "must be >= 1");
    if (d.cluster_jump <= 0) l.Fail("cluster_jump", "must be positive");
    if (d.span_tolerance < 0) l.Fail("span_tolerance", "must be >= 0");
    if (d.fit_tolerance <= 0) l.Fail("fit_tolerance", "must be positive");
    if (d.gate <= 0) l.Fail("gate", "must be positive");
    if (d.gate >= 0.5 * c.post_spacing)
      l.Fail("gate", "must be below half the post spacing, else neighbouring posts are confused");
    if (c.range_tolerance < 0) l.Fail("range_tolerance", "must be >= 0");
    if (c.min_subtended_deg <= 0 || c.min_subtended_deg >= 90)
      l.Fail("min_subtended_deg", "must be in (0, 90)");
    if (c.angle_tolerance_deg <= 0) l.Fail("angle_tolerance_deg", "must be positive");
    if (c.max_range <= 0) l.Fail("max_range", "must be positive");
    l.Finish();
  }
  {
    YamlReader e = root.Map("estimation");
    c.source = e.Choice("controller_source", NavSourceNames(), c.source);
    YamlReader k = e.Map("kalman");
    auto& kf = c.kalman;
    kf.q_per_m = k.Double("q_per_m", kf.q_per_m);
    kf.q_per_s = k.Double("q_per_s", kf.q_per_s);
    kf.r = k.Double("r", kf.r);
    kf.p0 = k.Double("p0", kf.p0);
    kf.nis_gate = k.Double("nis_gate", kf.nis_gate);
    kf.reacquire_after = k.Int("reacquire_after", kf.reacquire_after);
    if (kf.q_per_m < 0) k.Fail("q_per_m", "must be >= 0");
    if (kf.q_per_s < 0) k.Fail("q_per_s", "must be >= 0");
    if (kf.r <= 0) k.Fail("r", "must be positive (a variance)");
    if (kf.p0 <= 0) k.Fail("p0", "must be positive (a variance)");
    if (kf.reacquire_after < 1) k.Fail("reacquire_after", "must be >= 1");
    k.Finish();
    YamlReader cl = e.Map("classical");
    c.limit.max_step = cl.Double("limit_step", c.limit.max_step);
    c.limit.max_rate = cl.Double("limit_rate", c.limit.max_rate);
    c.limit.reacquire_after = cl.Int("reacquire_after", c.limit.reacquire_after);
    c.mean_window = cl.Int("mean_window", c.mean_window);
    if (c.limit.max_step <= 0) cl.Fail("limit_step", "must be positive");
    if (c.limit.max_rate < 0) cl.Fail("limit_rate", "must be >= 0");
    if (c.limit.reacquire_after < 1) cl.Fail("reacquire_after", "must be >= 1");
    if (c.mean_window < 1 || c.mean_window > 100) cl.Fail("mean_window", "must be in [1, 100]");
    cl.Finish();
    YamlReader h = e.Map("heading");
    c.heading_limit_deg = h.Double("limit_deg", c.heading_limit_deg);
    c.heading_window = h.Int("mean_window", c.heading_window);
    c.heading_reacquire = h.Int("reacquire_after", c.heading_reacquire);
    if (c.heading_limit_deg <= 0) h.Fail("limit_deg", "must be positive");
    if (c.heading_window < 1 || c.heading_window > 100)
      h.Fail("mean_window", "must be in [1, 100]");
    if (c.heading_reacquire < 1) h.Fail("reacquire_after", "must be >= 1");
    h.Finish();
    e.Finish();
  }
  {
    YamlReader r = root.Map("control");
    c.control_rate_hz = r.Double("rate_hz", c.control_rate_hz);
    c.feedforward = r.Bool("feedforward", c.feedforward);
    if (c.control_rate_hz <= 0) r.Fail("rate_hz", "must be positive");
    if (c.control_rate_hz > 1.0 / setup.dt + 1e-9)
      r.Fail("rate_hz", "cannot exceed the world step rate 1/dt");
    if (c.laser.rate_hz > 1.0 / setup.dt + 1e-9)
      root.Map("laser").Fail("rate_hz", "cannot exceed the world step rate 1/dt");
    r.Finish();
  }
  {
    YamlReader f = root.Map("fuzzy");
    const std::string file = f.String("file", "../fuzzy/inspection.fll");
    c.fuzzy_reload = f.Bool("reload", false);
    std::filesystem::path p(file);
    if (p.is_relative()) p = std::filesystem::path(setup.file).parent_path() / p;
    if (!std::filesystem::is_regular_file(p))
      f.Fail("file", "cannot open the rule base '" + p.string() +
                         "' (relative paths start at the scenario's folder)");
    c.fuzzy_file = p.lexically_normal().string();
    f.Finish();
  }
  {
    YamlReader m = root.Map("metrics");
    c.lateral_bound = m.Double("lateral_bound", c.lateral_bound);
    c.transient_m = m.Double("transient_m", c.transient_m);
    if (c.lateral_bound <= 0) m.Fail("lateral_bound", "must be positive");
    if (c.transient_m < 0) m.Fail("transient_m", "must be >= 0");
    m.Finish();
  }
  return c;
}

}  // namespace formsim::sim
