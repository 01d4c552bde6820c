// Readers for the scenario blocks every experiment kind shares: world, obstacles, patches,
// robot bodies.
#include <set>
#include <string>

#include "sim/core/world.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

WorldDef ReadWorldDef(YamlReader& m, bool friction_live) {
  WorldDef def;
  Tune mu = Tune("floor μ").In(0, world_limits::kMaxFriction).Slider(0.0, 1.5).Group("Floor");
  if (!friction_live) mu.OnReset();
  def.floor_friction = m.Real("floor_friction", def.floor_friction, mu);
  def.velocity_iterations = m.Int("velocity_iterations", def.velocity_iterations);
  if (def.velocity_iterations < 1 || def.velocity_iterations > 100)
    m.Fail("velocity_iterations", "must be in [1, 100] (Box2D's default is 8)");
  def.position_iterations = m.Int("position_iterations", def.position_iterations);
  if (def.position_iterations < 1 || def.position_iterations > 100)
    m.Fail("position_iterations", "must be in [1, 100] (Box2D's default is 3)");
  m.Finish();
  return def;
}

std::vector<ObstacleDef> ReadObstacles(YamlReader& root) {
  std::vector<ObstacleDef> out;
  int index = 0;
  for (YamlReader& o : root.MapList("obstacles")) {
    ObstacleDef def = DefaultObstacleDef();
    def.name = o.String("name", "obstacle" + std::to_string(index++));
    const int shape = o.Choice("shape", {"box", "circle", "polygon", "wall"}, 0);
    def.shape = static_cast<ObstacleDef::Shape>(shape);
    def.friction = o.Double("friction", def.friction);
    if (!(def.friction >= 0 && def.friction <= world_limits::kMaxFriction))
      o.Fail("friction", "must be in [0, 10]");
    switch (def.shape) {
      case ObstacleDef::Shape::kBox: {
        const auto c = o.Doubles("center", {0, 0}, 2);
        const auto size = o.Doubles("size", {1, 1}, 2);
        if (size[0] <= 0 || size[1] <= 0) o.Fail("size", "must be positive");
        def.pose = {c[0], c[1], o.Double("angle", 0.0)};
        def.half_x = size[0] / 2;
        def.half_y = size[1] / 2;
        break;
      }
      case ObstacleDef::Shape::kCircle: {
        const auto c = o.Doubles("center", {0, 0}, 2);
        def.pose = {c[0], c[1], 0.0};
        def.radius = o.RequiredDouble("radius");
        if (def.radius <= 0) o.Fail("radius", "must be positive");
        break;
      }
      case ObstacleDef::Shape::kPolygon: {
        const auto c = o.Doubles("center", {0, 0}, 2);
        def.pose = {c[0], c[1], o.Double("angle", 0.0)};
        def.vertices = o.Points("vertices", 3);
        if (def.vertices.size() > 8) o.Fail("vertices", "at most 8 vertices (convex polygon)");
        break;
      }
      case ObstacleDef::Shape::kWall:
        def.vertices = o.Points("points", 2);
        break;
    }
    o.Finish();
    // Sizes, positions and polygon shape as Box2D needs them, reported at the obstacle.
    if (const std::string e = CheckObstacleDef(def); !e.empty()) {
      const char* key = def.shape == ObstacleDef::Shape::kBox      ? "size"
                        : def.shape == ObstacleDef::Shape::kCircle ? "radius"
                        : def.shape == ObstacleDef::Shape::kWall   ? "points"
                                                                   : "vertices";
      if (e.rfind("centre", 0) == 0 || e.rfind("angle", 0) == 0) key = "center";
      if (e.rfind("friction", 0) == 0) key = "friction";
      o.Fail(key, e);
    }
    out.push_back(def);
  }
  return out;
}

std::vector<PatchDef> ReadPatches(YamlReader& root) {
  std::vector<PatchDef> out;
  int index = 0;
  std::set<std::string> names;
  for (YamlReader& p : root.MapList("patches")) {
    PatchDef def;
    def.name = p.String("name", "patch" + std::to_string(index++));
    if (def.name.empty() || def.name.find_first_of(".,") != std::string::npos)
      p.Fail("name", "a patch name must be non-empty, without '.' or ',' (names address keys and metrics)");
    if (def.name == "floor") p.Fail("name", "'floor' names the ground outside every patch");
    if (!names.insert(def.name).second) p.Fail("name", "duplicate patch name '" + def.name + "'");
    if (!p.Has("friction")) p.Fail("friction", "required number is missing");
    def.friction = p.Real("friction", 0.8,
                          Tune("μ").In(0, world_limits::kMaxFriction).Slider(0.0, 1.5)
                              .Group("Floor/" + def.name).OnReset());
    if (p.Has("polygon")) {
      def.polygon = p.Points("polygon", 3);
    } else {
      const auto c = p.Doubles("center", {0, 0}, Tune().In(-world_limits::kExtent, world_limits::kExtent));
      if (!p.Has("size")) p.Fail("size", "a patch needs either polygon: [[x, y], ...] or center + size");
      const auto s = p.Doubles("size", {1, 1}, Tune().In(world_limits::kMinSize, 2 * world_limits::kExtent));
      def.polygon = {{c[0] - s[0] / 2, c[1] - s[1] / 2}, {c[0] + s[0] / 2, c[1] - s[1] / 2},
                     {c[0] + s[0] / 2, c[1] + s[1] / 2}, {c[0] - s[0] / 2, c[1] + s[1] / 2}};
    }
    p.Finish();
    out.push_back(def);
  }
  return out;
}

void ReadRobotBody(YamlReader& b, RobotDef& def) {
  def.shape = static_cast<RobotDef::Shape>(b.Choice("shape", {"box", "circle"}, static_cast<int>(def.shape)));
  if (def.shape == RobotDef::Shape::kBox) {
    const auto size = b.Doubles("size", {2 * def.half_length, 2 * def.half_width}, 2);
    if (size[0] <= 0 || size[1] <= 0) b.Fail("size", "must be positive");
    def.half_length = size[0] / 2;
    def.half_width = size[1] / 2;
  } else {
    def.radius = b.Double("radius", def.radius);
    if (def.radius <= 0) b.Fail("radius", "must be positive");
  }
  def.mass = b.Double("mass", def.mass);
  if (!(def.mass >= world_limits::kMinMass && def.mass <= world_limits::kMaxMass))
    b.Fail("mass", "must be in [0.001, 1e6] kg");
  def.collide_with_robots = b.Bool("collide_with_robots", def.collide_with_robots);
  b.Finish();
  // Sizes as Box2D needs them (pose is checked where it is read).
  RobotDef at_origin = def;
  at_origin.pose = {};
  if (const std::string e = CheckRobotDef(at_origin); !e.empty())
    b.Fail(def.shape == RobotDef::Shape::kCircle ? "radius" : "size", e);
}

}  // namespace formsim::sim
