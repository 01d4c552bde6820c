#pragma once
/// \file The Box2D world, top-down (no gravity), with robots, static obstacles and ground
/// patches of their own friction. Definition structs with defaults, Box2D style:
///   RobotDef def = DefaultRobotDef(); def.name = "R1"; def.pose = {0, 0, 0};
///   world.CreateRobot(def);

#include <box2d/box2d.h>

#include <memory>
#include <string>
#include <vector>

#include "control/common/geometry.hpp"
#include "sim/core/draw.hpp"

namespace formsim::sim {

class World;
class Robot;

constexpr double kGravity = 9.81;  ///< m/s², for friction limits (the world itself has none)

/// Box2D collision categories of the world's fixtures (ray casts that skip robots test them).
inline constexpr uint16 kObstacleCategory = 0x0001;
inline constexpr uint16 kRobotCategory = 0x0002;

/// What the world accepts. Box2D computes in float and asserts on degenerate shapes (Debian's
/// build keeps its assertions), so everything handed to it is checked against these first.
namespace world_limits {
inline constexpr double kExtent = 1e4;      ///< |x|, |y| of any point, m (float keeps ~1 mm)
inline constexpr double kMaxAngle = 1e3;    ///< |θ| of a pose, rad
inline constexpr double kMinSize = 0.01;    ///< smallest side or diameter of a body, m
inline constexpr double kMaxSize = 1e3;     ///< largest side or diameter, m
inline constexpr double kMinArea = 1e-4;    ///< smallest polygon area, m²
inline constexpr double kMinMass = 1e-3;    ///< kg
inline constexpr double kMaxMass = 1e6;     ///< kg
inline constexpr double kMaxFriction = 10;  ///< Coulomb μ
}  // namespace world_limits

/// How a robot turns commands into motion. Each robot kind supplies one (unicycle, Mecanum,
/// differential drive with motors, steered vehicle). Apply() runs before every world step.
class DriveModel {
 public:
  virtual ~DriveModel() = default;
  virtual void Apply(Robot& robot, World& world, double dt) = 0;
  /// True when the last Apply had to limit the command (speed limits, traction).
  virtual bool saturated() const { return false; }
};

/// A robot's body: a box (half extents) or a circle, and its mass properties.
struct RobotDef {
  std::string name = "robot";
  Pose2 pose;
  enum class Shape { kBox, kCircle } shape = Shape::kBox;
  double half_length = 0.08;  ///< along the heading, m
  double half_width = 0.06;   ///< m
  double radius = 0.07;       ///< for circles, m
  double mass = 2.0;          ///< kg
  int color_index = 0;        ///< palette entry
  bool collide_with_robots = true;
};
inline RobotDef DefaultRobotDef() {
  return RobotDef{};
}

/// A static obstacle.
struct ObstacleDef {
  std::string name = "obstacle";
  enum class Shape { kBox, kCircle, kPolygon, kWall } shape = Shape::kBox;
  Pose2 pose;  ///< centre and rotation (box, polygon), centre (circle)
  double half_x = 0.5, half_y = 0.5;
  double radius = 0.5;
  std::vector<Vec2> vertices;  ///< polygon (local frame, convex, <= 8) or wall polyline (world)
  double friction = 0.6;
};
inline ObstacleDef DefaultObstacleDef() {
  return ObstacleDef{};
}

/// A region of floor with its own friction coefficient (slippery zones, gravel, ...).
struct PatchDef {
  std::string name = "patch";
  std::vector<Vec2> polygon;  ///< world frame, any simple polygon
  double friction = 0.8;
};

/// "" when the robot body can be handed to Box2D (finite, inside the world, sizes and mass
/// within world_limits), else the reason.
std::string CheckRobotDef(const RobotDef& def);
/// Same for an obstacle: also a convex polygon of 3 to 8 vertices with sides of at least
/// kMinSize and area of at least kMinArea, and wall segments of at least kMinSize.
std::string CheckObstacleDef(const ObstacleDef& def);

/// A collision between two named bodies (robots or obstacles), logged when contact begins.
struct CollisionEvent {
  double time = 0.0;
  std::string a, b;
  Vec2 point;
};

struct WorldDef {
  double floor_friction = 0.8;  ///< μ where no patch lies
  int velocity_iterations = 8;
  int position_iterations = 3;
};

/// Result of a ray cast against obstacles (and optionally robots).
struct RayHit {
  bool hit = false;
  double distance = 0.0;
  Vec2 point;
  std::string body_name;
};

class Robot {
 public:
  const std::string& name() const { return def_.name; }
  const RobotDef& def() const { return def_; }
  /// True pose from the physics body (inline: read many times a step).
  Pose2 pose() const {
    const b2Vec2 p = body_->GetPosition();
    return {p.x, p.y, body_->GetAngle()};
  }
  /// Velocity in the body frame: forward, lateral (left), yaw rate.
  double forward_speed() const;
  double lateral_speed() const;
  double yaw_rate() const { return body_->GetAngularVelocity(); }
  Vec2 world_velocity() const {
    const b2Vec2 v = body_->GetLinearVelocity();
    return {v.x, v.y};
  }
  b2Body* body() { return body_; }
  const b2Body* body() const { return body_; }
  double mass() const { return body_->GetMass(); }
  double inertia() const { return body_->GetInertia(); }
  /// Body outline in the body frame (for drawing).
  std::vector<Vec2> outline() const;

  void SetDrive(std::unique_ptr<DriveModel> drive) { drive_ = std::move(drive); }
  DriveModel* drive() { return drive_.get(); }
  const DriveModel* drive() const { return drive_.get(); }
  /// Teleports (e.g. a drag in the GUI while paused); zeroes the velocity.
  void SetPose(const Pose2& pose);

 private:
  friend class World;
  RobotDef def_;
  b2Body* body_ = nullptr;
  std::unique_ptr<DriveModel> drive_;
};

class World {
 public:
  explicit World(const WorldDef& def = WorldDef{});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Replaces the world settings (floor friction, solver iterations), e.g. after reading
  /// `world:` in an experiment constructor. Call before the first Step.
  void SetDef(const WorldDef& def) { def_ = def; }
  const WorldDef& def() const { return def_; }

  Robot& CreateRobot(const RobotDef& def);
  void CreateObstacle(const ObstacleDef& def);
  void CreatePatch(const PatchDef& def);

  /// Applies every robot's drive, steps Box2D by dt, then collects collision events.
  void Step(double dt);
  double time() const { return time_; }

  /// Friction coefficient of the ground at p (the last patch containing p, else the floor).
  double FrictionAt(Vec2 p) const;
  const std::string& PatchNameAt(Vec2 p) const;

  /// First obstacle (and robot, if `include_robots`) hit along a ray, skipping `ignore`. A ray
  /// shorter than 1e-6 m or not finite hits nothing. Safe to call from several threads at once
  /// (it only reads the world). Many rays from one point: `RayFan` (ray_fan.hpp), same hits.
  RayHit RayCast(Vec2 from, Vec2 to, bool include_robots = false,
                 const Robot* ignore = nullptr) const;

  std::vector<std::unique_ptr<Robot>>& robots() { return robots_; }
  const std::vector<std::unique_ptr<Robot>>& robots() const { return robots_; }
  Robot* FindRobot(const std::string& name);
  const std::vector<ObstacleDef>& obstacles() const { return obstacle_defs_; }
  /// The Box2D body of each obstacle, in the order of obstacles() (distance queries).
  const std::vector<b2Body*>& obstacle_bodies() const { return obstacle_bodies_; }
  const std::vector<PatchDef>& patches() const { return patches_; }
  /// Moves a static obstacle (GUI drag while paused). Returns false if no such obstacle.
  bool MoveObstacle(const std::string& name, Vec2 p);

  /// Collision events that began during the last Step.
  const std::vector<CollisionEvent>& new_collisions() const { return new_collisions_; }
  /// All collision events since the start.
  const std::vector<CollisionEvent>& collisions() const { return collisions_; }

  /// Draws patches and obstacles (robots are drawn by their experiment, which knows colours).
  void Draw(DrawSink& draw) const;

  b2World& b2() { return *b2_; }
  const b2World& b2() const { return *b2_; }
  /// The name of a body of this world (obstacle or robot; empty for others).
  const std::string& BodyName(const b2Body* body) const;

 private:
  class ContactListener;
  WorldDef def_;
  std::unique_ptr<b2World> b2_;
  std::unique_ptr<ContactListener> listener_;
  std::vector<std::unique_ptr<Robot>> robots_;
  std::vector<ObstacleDef> obstacle_defs_;
  std::vector<b2Body*> obstacle_bodies_;
  std::vector<PatchDef> patches_;
  std::vector<CollisionEvent> new_collisions_, collisions_;
  std::vector<std::string> body_names_;  ///< indexed by b2Body user data
  double time_ = 0.0;
};

/// Reads the shared scenario blocks into defs: `world:` (floor_friction), `obstacles:` and
/// `patches:` lists. Defined in scenario_common.cpp. Declared here to keep one place for world
/// setup.
class YamlReader;
/// `floor_friction` is a tunable (group "Floor"): live when `friction_live` (the kind applies
/// world friction between steps), else on reset.
WorldDef ReadWorldDef(YamlReader& world_map, bool friction_live = false);
std::vector<ObstacleDef> ReadObstacles(YamlReader& root);
/// Patch names are unique, not "floor" and free of '.' and ',' (they address keys and
/// metrics); each patch's friction is a tunable "patches.NAME.friction" (on reset).
std::vector<PatchDef> ReadPatches(YamlReader& root);
/// Reads a robot body block (shape, size, mass) into def, leaving name/pose to the caller.
void ReadRobotBody(YamlReader& body_map, RobotDef& def);

}  // namespace formsim::sim
