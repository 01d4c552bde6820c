#include "sim/core/world.hpp"
#include "sim/core/number_format.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace formsim::sim {
namespace {

b2Vec2 ToB2(Vec2 v) { return b2Vec2(static_cast<float>(v.x), static_cast<float>(v.y)); }
Vec2 FromB2(const b2Vec2& v) { return {v.x, v.y}; }

bool PointInPolygon(const std::vector<Vec2>& poly, Vec2 p) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 a = poly[i], b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
      inside = !inside;
  }
  return inside;
}

// Strictly convex (all turns the same way, none straight), either winding.
bool IsConvex(const std::vector<Vec2>& p) {
  int sign = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 a = p[i], b = p[(i + 1) % p.size()], c = p[(i + 2) % p.size()];
    const double cross = (b - a).Cross(c - b);
    if (std::abs(cross) < 1e-9) return false;
    const int s = cross > 0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

std::string CheckPoint(Vec2 p, const std::string& what) {
  using namespace world_limits;
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return what + " is not finite";
  if (std::abs(p.x) > kExtent || std::abs(p.y) > kExtent)
    return what + " (" + FormatSignificant(p.x) + ", " + FormatSignificant(p.y) + ") is outside the world (|x|, |y| <= " +
           FormatSignificant(kExtent) + " m)";
  return "";
}

std::string CheckSize(double v, const std::string& what) {
  using namespace world_limits;
  if (!(v >= kMinSize && v <= kMaxSize))
    return what + " " + FormatSignificant(v) + " m is outside [" + FormatSignificant(kMinSize) + ", " + FormatSignificant(kMaxSize) + "] m";
  return "";
}

double PolygonArea(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += p[i].Cross(p[(i + 1) % p.size()]);
  return 0.5 * std::abs(a);
}

}  // namespace

std::string CheckRobotDef(const RobotDef& def) {
  using namespace world_limits;
  std::string e = CheckPoint(def.pose.p(), "pose");
  if (!e.empty()) return e;
  if (!(std::abs(def.pose.theta) <= kMaxAngle)) return "heading " + FormatSignificant(def.pose.theta) + " rad is not within ±" + FormatSignificant(kMaxAngle) + " rad";
  if (def.shape == RobotDef::Shape::kCircle) {
    if (!(e = CheckSize(2 * def.radius, "diameter")).empty()) return e;
  } else {
    if (!(e = CheckSize(2 * def.half_length, "length")).empty()) return e;
    if (!(e = CheckSize(2 * def.half_width, "width")).empty()) return e;
  }
  if (!(def.mass >= kMinMass && def.mass <= kMaxMass))
    return "mass " + FormatSignificant(def.mass) + " kg is outside [" + FormatSignificant(kMinMass) + ", " + FormatSignificant(kMaxMass) + "] kg";
  return "";
}

std::string CheckObstacleDef(const ObstacleDef& def) {
  using namespace world_limits;
  std::string e;
  if (!(def.friction >= 0 && def.friction <= kMaxFriction))
    return "friction " + FormatSignificant(def.friction) + " is outside [0, " + FormatSignificant(kMaxFriction) + "]";
  if (def.shape != ObstacleDef::Shape::kWall) {
    if (!(e = CheckPoint(def.pose.p(), "centre")).empty()) return e;
    if (!(std::abs(def.pose.theta) <= kMaxAngle)) return "angle is not within ±" + FormatSignificant(kMaxAngle) + " rad";
  }
  switch (def.shape) {
    case ObstacleDef::Shape::kBox:
      if (!(e = CheckSize(2 * def.half_x, "size x")).empty()) return e;
      return CheckSize(2 * def.half_y, "size y");
    case ObstacleDef::Shape::kCircle:
      return CheckSize(2 * def.radius, "diameter");
    case ObstacleDef::Shape::kPolygon: {
      const auto& v = def.vertices;
      if (v.size() < 3 || v.size() > b2_maxPolygonVertices) return "a polygon needs 3 to 8 vertices";
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (!(e = CheckPoint(def.pose.ToWorld(v[i]), "vertex " + std::to_string(i))).empty()) return e;
        const double side = (v[(i + 1) % v.size()] - v[i]).Norm();
        if (!(side >= kMinSize)) return "side " + std::to_string(i) + " is " + FormatSignificant(side) + " m, shorter than " + FormatSignificant(kMinSize) + " m";
      }
      if (!IsConvex(v)) return "the vertices must form a convex polygon (no straight or reflex corner)";
      if (!(PolygonArea(v) >= kMinArea)) return "area " + FormatSignificant(PolygonArea(v)) + " m² is below " + FormatSignificant(kMinArea) + " m²";
      return "";
    }
    case ObstacleDef::Shape::kWall: {
      const auto& v = def.vertices;
      if (v.size() < 2) return "a wall needs at least 2 points";
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (!(e = CheckPoint(v[i], "point " + std::to_string(i))).empty()) return e;
        if (i + 1 < v.size() && !((v[i + 1] - v[i]).Norm() >= kMinSize))
          return "segment " + std::to_string(i) + " is shorter than " + FormatSignificant(kMinSize) + " m";
      }
      return "";
    }
  }
  return "";
}

// Logs the start of every contact between two named bodies.
class World::ContactListener : public b2ContactListener {
 public:
  explicit ContactListener(World* world) : world_(world) {}
  void BeginContact(b2Contact* contact) override {
    const auto ia = contact->GetFixtureA()->GetBody()->GetUserData().pointer;
    const auto ib = contact->GetFixtureB()->GetBody()->GetUserData().pointer;
    if (ia == 0 || ib == 0) return;
    b2WorldManifold wm;
    contact->GetWorldManifold(&wm);
    CollisionEvent e;
    e.time = world_->time_;
    e.a = world_->body_names_[ia - 1];
    e.b = world_->body_names_[ib - 1];
    e.point = FromB2(contact->GetManifold()->pointCount > 0 ? wm.points[0]
                                                           : contact->GetFixtureA()->GetBody()->GetPosition());
    world_->new_collisions_.push_back(e);
  }

 private:
  World* world_;
};

// ---- Robot ----


double Robot::forward_speed() const {
  const double a = body_->GetAngle();
  const Vec2 v = world_velocity();
  return std::cos(a) * v.x + std::sin(a) * v.y;
}

double Robot::lateral_speed() const {
  const double a = body_->GetAngle();
  const Vec2 v = world_velocity();
  return -std::sin(a) * v.x + std::cos(a) * v.y;
}


std::vector<Vec2> Robot::outline() const {
  if (def_.shape == RobotDef::Shape::kCircle) {
    std::vector<Vec2> pts;
    for (int k = 0; k < 20; ++k) {
      const double a = 2.0 * M_PI * k / 20.0;
      pts.push_back({def_.radius * std::cos(a), def_.radius * std::sin(a)});
    }
    return pts;
  }
  const double hl = def_.half_length, hw = def_.half_width;
  return {{hl, hw}, {-hl, hw}, {-hl, -hw}, {hl, -hw}};
}

void Robot::SetPose(const Pose2& pose) {
  body_->SetTransform(b2Vec2(static_cast<float>(pose.x), static_cast<float>(pose.y)),
                      static_cast<float>(pose.theta));
  body_->SetLinearVelocity(b2Vec2(0, 0));
  body_->SetAngularVelocity(0);
}

// ---- World ----

World::World(const WorldDef& def)
    : def_(def), b2_(std::make_unique<b2World>(b2Vec2(0.0f, 0.0f))),
      listener_(std::make_unique<ContactListener>(this)) {
  b2_->SetContactListener(listener_.get());
  // Box2D computes times of impact only against static bodies (robots are dynamic and not
  // bullets), so continuous collision is switched on with the first obstacle: until then its
  // pass would find nothing to do, every step (2% of a three-robot step).
  b2_->SetContinuousPhysics(false);
}

World::~World() {
  // Bodies go with the b2World; drop the listener first so no callback sees a dead World.
  b2_->SetContactListener(nullptr);
}

Robot& World::CreateRobot(const RobotDef& def) {
  // The readers refuse all of this with file:line:key; this is the last line before Box2D.
  if (const std::string e = CheckRobotDef(def); !e.empty())
    throw std::invalid_argument("robot '" + def.name + "': " + e);
  for (const auto& r : robots_)
    if (r->name() == def.name) throw std::invalid_argument("duplicate robot name '" + def.name + "'");
  auto robot = std::make_unique<Robot>();
  robot->def_ = def;
  b2BodyDef bd;
  bd.type = b2_dynamicBody;
  bd.position = b2Vec2(static_cast<float>(def.pose.x), static_cast<float>(def.pose.y));
  bd.angle = static_cast<float>(def.pose.theta);
  bd.allowSleep = false;
  bd.bullet = false;
  body_names_.push_back(def.name);
  bd.userData.pointer = body_names_.size();
  robot->body_ = b2_->CreateBody(&bd);

  b2FixtureDef fd;
  b2PolygonShape box;
  b2CircleShape circle;
  double area;
  if (def.shape == RobotDef::Shape::kCircle) {
    circle.m_radius = static_cast<float>(def.radius);
    fd.shape = &circle;
    area = M_PI * def.radius * def.radius;
  } else {
    box.SetAsBox(static_cast<float>(def.half_length), static_cast<float>(def.half_width));
    fd.shape = &box;
    area = 4.0 * def.half_length * def.half_width;
  }
  fd.density = static_cast<float>(def.mass / area);
  fd.friction = 0.3f;
  fd.restitution = 0.1f;
  fd.filter.categoryBits = kRobotCategory;
  fd.filter.maskBits = def.collide_with_robots ? (kRobotCategory | kObstacleCategory) : kObstacleCategory;
  robot->body_->CreateFixture(&fd);
  robots_.push_back(std::move(robot));
  return *robots_.back();
}

void World::CreateObstacle(const ObstacleDef& def) {
  if (const std::string e = CheckObstacleDef(def); !e.empty())
    throw std::invalid_argument("obstacle '" + def.name + "': " + e);
  b2BodyDef bd;
  bd.type = b2_staticBody;
  b2_->SetContinuousPhysics(true);
  bd.position = b2Vec2(static_cast<float>(def.pose.x), static_cast<float>(def.pose.y));
  bd.angle = static_cast<float>(def.pose.theta);
  body_names_.push_back(def.name);
  bd.userData.pointer = body_names_.size();
  if (def.shape == ObstacleDef::Shape::kWall) {
    bd.position = b2Vec2(0, 0);
    bd.angle = 0;
  }
  b2Body* body = b2_->CreateBody(&bd);
  b2FixtureDef fd;
  fd.friction = static_cast<float>(def.friction);
  fd.filter.categoryBits = kObstacleCategory;
  switch (def.shape) {
    case ObstacleDef::Shape::kBox: {
      b2PolygonShape s;
      s.SetAsBox(static_cast<float>(def.half_x), static_cast<float>(def.half_y));
      fd.shape = &s;
      body->CreateFixture(&fd);
      break;
    }
    case ObstacleDef::Shape::kCircle: {
      b2CircleShape s;
      s.m_radius = static_cast<float>(def.radius);
      fd.shape = &s;
      body->CreateFixture(&fd);
      break;
    }
    case ObstacleDef::Shape::kPolygon: {
      std::vector<b2Vec2> v;
      for (const Vec2& p : def.vertices) v.push_back(ToB2(p));
      b2PolygonShape s;
      s.Set(v.data(), static_cast<int>(v.size()));
      fd.shape = &s;
      body->CreateFixture(&fd);
      break;
    }
    case ObstacleDef::Shape::kWall: {
      for (std::size_t i = 0; i + 1 < def.vertices.size(); ++i) {
        b2EdgeShape e;
        e.SetTwoSided(ToB2(def.vertices[i]), ToB2(def.vertices[i + 1]));
        fd.shape = &e;
        body->CreateFixture(&fd);
      }
      break;
    }
  }
  obstacle_defs_.push_back(def);
  obstacle_bodies_.push_back(body);
}

void World::CreatePatch(const PatchDef& def) {
  if (def.polygon.size() < 3)
    throw std::invalid_argument("patch '" + def.name + "' needs at least 3 points");
  patches_.push_back(def);
}

void World::Step(double dt) {
  for (auto& r : robots_)
    if (r->drive_) r->drive_->Apply(*r, *this, dt);
  new_collisions_.clear();
  b2_->Step(static_cast<float>(dt), def_.velocity_iterations, def_.position_iterations);
  time_ += dt;
  for (auto& e : new_collisions_) e.time = time_;
  collisions_.insert(collisions_.end(), new_collisions_.begin(), new_collisions_.end());
}

double World::FrictionAt(Vec2 p) const {
  for (auto it = patches_.rbegin(); it != patches_.rend(); ++it)
    if (PointInPolygon(it->polygon, p)) return it->friction;
  return def_.floor_friction;
}

const std::string& World::PatchNameAt(Vec2 p) const {
  static const std::string kFloor = "floor";
  for (auto it = patches_.rbegin(); it != patches_.rend(); ++it)
    if (PointInPolygon(it->polygon, p)) return it->name;
  return kFloor;
}

namespace {
class ClosestRay : public b2RayCastCallback {
 public:
  ClosestRay(bool robots, const b2Body* ignore) : robots_(robots), ignore_(ignore) {}
  float ReportFixture(b2Fixture* f, const b2Vec2& point, const b2Vec2&, float fraction) override {
    if (f->GetBody() == ignore_) return -1.0f;
    if (!robots_ && (f->GetFilterData().categoryBits & kRobotCategory)) return -1.0f;
    hit = true;
    this->point = point;
    this->fraction = fraction;
    body = f->GetBody();
    return fraction;
  }
  bool hit = false;
  b2Vec2 point;
  float fraction = 1.0f;
  const b2Body* body = nullptr;

 private:
  bool robots_;
  const b2Body* ignore_;
};
}  // namespace

RayHit World::RayCast(Vec2 from, Vec2 to, bool include_robots, const Robot* ignore) const {
  RayHit out;
  // Box2D asserts on a zero-length or non-finite ray: such a ray hits nothing.
  const Vec2 d = to - from;
  if (!std::isfinite(from.x) || !std::isfinite(from.y) || !std::isfinite(to.x) ||
      !std::isfinite(to.y) || !(d.x * d.x + d.y * d.y >= 1e-12))
    return out;
  ClosestRay cb(include_robots, ignore ? ignore->body() : nullptr);
  b2_->RayCast(&cb, ToB2(from), ToB2(to));
  if (!cb.hit) return out;
  out.hit = true;
  out.point = FromB2(cb.point);
  out.distance = (out.point - from).Norm();
  out.body_name = BodyName(cb.body);
  return out;
}

const std::string& World::BodyName(const b2Body* body) const {
  static const std::string kNone;
  const auto id = const_cast<b2Body*>(body)->GetUserData().pointer;
  return id > 0 && id <= body_names_.size() ? body_names_[id - 1] : kNone;
}

Robot* World::FindRobot(const std::string& name) {
  for (auto& r : robots_)
    if (r->name() == name) return r.get();
  return nullptr;
}

bool World::MoveObstacle(const std::string& name, Vec2 p) {
  if (!CheckPoint(p, "position").empty()) return false;
  for (std::size_t i = 0; i < obstacle_defs_.size(); ++i) {
    if (obstacle_defs_[i].name != name || obstacle_defs_[i].shape == ObstacleDef::Shape::kWall) continue;
    obstacle_bodies_[i]->SetTransform(ToB2(p), obstacle_bodies_[i]->GetAngle());
    obstacle_defs_[i].pose.x = p.x;
    obstacle_defs_[i].pose.y = p.y;
    return true;
  }
  return false;
}

void World::Draw(DrawSink& draw) const {
  for (const auto& patch : patches_) {
    // Low friction reads cold (blue), high friction warm (sand): the floor is the reference.
    const float slip = static_cast<float>(std::clamp(1.0 - patch.friction / std::max(def_.floor_friction, 1e-3), -1.0, 1.0));
    const Color fill = slip > 0 ? Color{0.55f, 0.75f, 0.95f, 0.25f + 0.35f * slip}
                                : Color{0.85f, 0.75f, 0.55f, 0.25f - 0.15f * slip};
    draw.Polygon(patch.polygon, fill, fill.WithAlpha(0.8f));
    double cx = 0, cy = 0;
    for (const Vec2& p : patch.polygon) { cx += p.x; cy += p.y; }
    const double n = static_cast<double>(patch.polygon.size());
    draw.Text({cx / n, cy / n}, Sprintf("%s μ=%.2f", patch.name.c_str(), patch.friction),
              Color{0.2f, 0.3f, 0.45f, 1});
  }
  const Color fill{0.55f, 0.55f, 0.58f, 1}, edge{0.25f, 0.25f, 0.28f, 1};
  for (const auto& o : obstacle_defs_) {
    switch (o.shape) {
      case ObstacleDef::Shape::kBox:
        draw.Polygon({o.pose.ToWorld({o.half_x, o.half_y}), o.pose.ToWorld({-o.half_x, o.half_y}),
                      o.pose.ToWorld({-o.half_x, -o.half_y}), o.pose.ToWorld({o.half_x, -o.half_y})},
                     fill, edge);
        break;
      case ObstacleDef::Shape::kCircle:
        draw.Circle(o.pose.p(), o.radius, fill, edge);
        break;
      case ObstacleDef::Shape::kPolygon: {
        std::vector<Vec2> w;
        for (const Vec2& v : o.vertices) w.push_back(o.pose.ToWorld(v));
        draw.Polygon(w, fill, edge);
        break;
      }
      case ObstacleDef::Shape::kWall:
        for (std::size_t i = 0; i + 1 < o.vertices.size(); ++i)
          draw.Segment(o.vertices[i], o.vertices[i + 1], edge, 4.0f);
        break;
    }
  }
}

}  // namespace formsim::sim

// Box2D's profiling timers, made free. Box2D 2.4 fills b2World::GetProfile() by reading the clock
// (gettimeofday) about four times per island per step; robots that do not touch are islands of
// their own, so a thousand-robot step read the clock four thousand times, which was 60% of
// Box2D's time for such a world. formsim never reads the profile, so these definitions replace
// the library's: a program's own definitions take precedence over a shared library's for the
// library's calls too (ELF symbol interposition; Box2D is linked as libbox2d.so). The profile then
// reads 0; tests/sim/test_world.cpp checks that the replacement is in effect.
b2Timer::b2Timer() = default;
void b2Timer::Reset() {}
float b2Timer::GetMilliseconds() const { return 0.0f; }
