// The steered drive (Box2D, friction-limited) and the ray-cast laser scanner.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "control/inspection/paper_frame.hpp"
#include "control/inspection/post_detector.hpp"
#include "sim/inspection/laser_scanner.hpp"
#include "sim/inspection/steered_drive.hpp"

namespace formsim::sim::inspection {
namespace {

namespace ins = control::inspection;

struct Rig {
  explicit Rig(double mu = 0.8) : world(WorldDef{mu, 8, 3}) {
    RobotDef def = DefaultRobotDef();
    def.name = "R1";
    def.half_length = 0.45;
    def.half_width = 0.3;
    def.mass = 40.0;
    def.pose = {0.0, 0.0, M_PI / 2.0};  // facing +Y: paper heading 0
    robot = &world.CreateRobot(def);
    auto d = std::make_unique<SteeredDrive>(DefaultSteeredDriveDef());
    drive = d.get();
    robot->SetDrive(std::move(d));
  }
  void Run(double seconds) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds / 0.01)); ++k) world.Step(0.01);
  }
  World world;
  Robot* robot = nullptr;
  SteeredDrive* drive = nullptr;
};

TEST(SteeredDrive, LevelsMapToWheelSpeed) {
  Rig rig;
  rig.drive->SetCommand(3.0, 3.0, 360.0);
  rig.Run(3.0);
  EXPECT_NEAR(rig.robot->forward_speed(), 3.0 * 0.15, 0.01);
  EXPECT_NEAR(rig.robot->pose().x, 0.0, 1e-3);  // straight along +Y
  EXPECT_NEAR(rig.drive->wheel_distance_left(), rig.drive->wheel_distance_right(), 1e-6);
  EXPECT_FALSE(rig.drive->slipping());
  // Commands are clamped to the controller's ranges.
  rig.drive->SetCommand(7.0, -1.0, 900.0);
  EXPECT_EQ(rig.drive->u1(), 4.0);
  EXPECT_EQ(rig.drive->u2(), 0.0);
  EXPECT_EQ(rig.drive->u3(), 500.0);
  rig.drive->SetCommand(NAN, 2.0, NAN);
  EXPECT_EQ(rig.drive->u1(), 0.0);
  EXPECT_EQ(rig.drive->u3(), 360.0);
}

// u3 above the centre steers right (clockwise): the rear axle circles at R = wheelbase / tan δ.
TEST(SteeredDrive, ServoCommandSteersRightWithTheKinematicRadius) {
  Rig rig;
  const double delta = ins::Rad(15.0);
  const double u3 = 360.0 + 15.0 / DefaultSteeredDriveDef().steer_per_unit_deg;
  // Rear wheel speeds consistent with the turn (inner right wheel slower).
  const double r = 0.6 / std::tan(delta), k = 0.25 / r;
  rig.drive->SetCommand(2.0 * (1 + k), 2.0 * (1 - k), u3);
  rig.Run(2.0);
  EXPECT_NEAR(rig.drive->steer_angle(), delta, 1e-9);
  const double heading0 = ins::PaperFromMath(rig.robot->pose().theta);
  rig.Run(1.0);
  const double heading1 = ins::PaperFromMath(rig.robot->pose().theta);
  EXPECT_GT(heading1, heading0);               // clockwise = paper heading grows
  const double omega = rig.robot->yaw_rate();  // mathematical, < 0 clockwise
  EXPECT_LT(omega, 0.0);
  EXPECT_NEAR(rig.robot->forward_speed() / std::abs(omega), std::hypot(r, 0.3), 0.05 * r);
}

TEST(SteeredDrive, LowFrictionLimitsTractionAndFoolsTheEncoders) {
  Rig ice(0.02);
  ice.drive->SetCommand(4.0, 4.0, 360.0);
  ice.Run(1.0);
  EXPECT_TRUE(ice.drive->slipping());
  // The wheels spin: the encoders count more than the body moved.
  const double moved = ice.robot->pose().y;
  EXPECT_GT(ice.drive->wheel_distance_left(), 1.5 * moved);
  // Acceleration bounded by μ g times the driven share of the weight.
  EXPECT_LT(ice.robot->forward_speed(), 0.02 * kGravity * 0.6 * 1.0 + 1e-3);
}

TEST(LaserScanner, SeesPostsByRayCastsAndIsDeterministic) {
  World world;
  ObstacleDef post = DefaultObstacleDef();
  post.shape = ObstacleDef::Shape::kCircle;
  post.radius = 0.1;
  ins::PostMap map;
  map.radius = 0.1;
  const Vec2 posts[] = {{-1.3, 3.0}, {1.3, 4.5}, {-1.3, 6.0}};
  int i = 0;
  for (const Vec2& p : posts) {
    post.name = "P" + std::to_string(++i);
    post.pose = {p.x, p.y, 0.0};
    world.CreateObstacle(post);
    map.posts.push_back(p);
  }
  LaserScannerDef def;
  def.outlier_prob = 0.0;
  def.range_sigma = 0.0;
  def.angle_sigma_deg = 0.0;
  LaserScanner exact(def, Rng(7));
  const Pose2 sensor{0.0, 0.0, M_PI / 2.0};
  std::vector<Vec2> ends;
  const ins::Scan scan = exact.Sample(world, sensor, nullptr, &ends);
  EXPECT_EQ(scan.ranges.size(), 720u);
  EXPECT_EQ(ends.size(), 720u);
  const auto det = ins::DetectPosts(scan, {0.0, 0.0, 0.0}, map);
  ASSERT_EQ(det.sightings.size(), 3u);
  for (const auto& s : det.sightings)
    EXPECT_NEAR(s.range, map.posts[s.post].Norm(), 2e-3);  // Box2D works in floats
  const auto fix = ins::Localise(det.sightings);
  ASSERT_TRUE(fix.ok());
  EXPECT_NEAR(fix.position.x, 0.0, 5e-3);
  EXPECT_NEAR(fix.position.y, 0.0, 5e-3);
  EXPECT_NEAR(fix.heading, 0.0, ins::Rad(0.2));
  // Noisy scanners with the same stream give the same scan, another stream another.
  LaserScanner a(DefaultLaserScannerDef(), Rng(3)), b(DefaultLaserScannerDef(), Rng(3)),
      c(DefaultLaserScannerDef(), Rng(4));
  const auto sa = a.Sample(world, sensor, nullptr), sb = b.Sample(world, sensor, nullptr),
             sc = c.Sample(world, sensor, nullptr);
  int same = 0, differ = 0;
  for (std::size_t k = 0; k < sa.ranges.size(); ++k) {
    if (std::isnan(sa.ranges[k])) continue;
    same += sa.ranges[k] == sb.ranges[k];
    differ += sa.ranges[k] != sc.ranges[k];
  }
  EXPECT_GT(same, 10);
  EXPECT_EQ(differ, same);
}

}  // namespace
}  // namespace formsim::sim::inspection
