// The wheel-level Mecanum drive in Box2D, the encoders and the beacon sensor.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "control/common/angle.hpp"
#include "control/agv/kinematics.hpp"
#include "sim/core/world.hpp"
#include "sim/agv/beacon_sensor.hpp"
#include "sim/agv/mecanum_drive.hpp"
#include "sim/agv/wheel_encoders.hpp"

namespace formsim::sim::agv {
namespace {

using control::agv::BodyTwist;
using control::agv::InverseKinematics;

struct Rig {
  explicit Rig(double floor_mu, MecanumDriveDef def = DefaultMecanumDriveDef()) {
    WorldDef wd;
    wd.floor_friction = floor_mu;
    world = std::make_unique<World>(wd);
    RobotDef rd;
    rd.name = "AGV";
    rd.half_length = 0.35;
    rd.half_width = 0.28;
    rd.mass = 30.0;
    robot = &world->CreateRobot(rd);
    auto d = std::make_unique<MecanumDrive>(def);
    drive = d.get();
    robot->SetDrive(std::move(d));
  }
  void Command(const BodyTwist& t) {
    drive->SetWheelCommand(InverseKinematics(drive->def().geometry, t));
  }
  void Run(double seconds, double dt = 1.0 / 300) {
    const int n = static_cast<int>(std::lround(seconds / dt));
    for (int i = 0; i < n; ++i) world->Step(dt);
  }
  std::unique_ptr<World> world;
  Robot* robot = nullptr;
  MecanumDrive* drive = nullptr;
};

TEST(MecanumDrive, SidewaysCommandMovesSidewaysWithoutTurning) {
  Rig rig(0.8);
  rig.Command({0.0, 0.2, 0.0});
  rig.Run(2.0);
  EXPECT_NEAR(rig.robot->lateral_speed(), 0.2, 2e-3);
  EXPECT_NEAR(rig.robot->forward_speed(), 0.0, 2e-3);
  EXPECT_NEAR(rig.robot->yaw_rate(), 0.0, 2e-3);
  EXPECT_NEAR(rig.robot->pose().theta, 0.0, 2e-3);
  EXPECT_GT(rig.robot->pose().y, 0.3);
  EXPECT_FALSE(rig.drive->slipping());
}

TEST(MecanumDrive, RotationCommandTurnsOnTheSpot) {
  Rig rig(0.8);
  rig.Command({0.0, 0.0, 0.8});
  rig.Run(2.0);
  EXPECT_NEAR(rig.robot->yaw_rate(), 0.8, 5e-3);
  EXPECT_LT(rig.robot->pose().p().Norm(), 5e-3);
}

TEST(MecanumDrive, TrueRadiusSetsGroundSpeed) {
  // All wheels 1 % larger than nominal: the body goes 1 % faster than commanded.
  MecanumDriveDef def = DefaultMecanumDriveDef();
  def.radius_error = {0.01, 0.01, 0.01, 0.01};
  Rig rig(0.8, def);
  rig.Command({0.3, 0.0, 0.0});
  rig.Run(1.0);
  EXPECT_NEAR(rig.robot->forward_speed(), 0.303, 5e-4);
}

TEST(MecanumDrive, IceLimitsTractionAndWheelsOutrunTheBody) {
  Rig ice(0.02), dry(0.8);
  for (Rig* r : {&ice, &dry}) {
    r->Command({0.5, 0.0, 0.0});
    r->Run(0.3);
  }
  // Dry floor: the body follows the wheels. Ice: at most μ g / √2 of forward acceleration
  // (each roller force is at 45°), so after 0.3 s the body is far slower than the wheels.
  EXPECT_NEAR(dry.robot->forward_speed(), 0.5, 0.01);
  EXPECT_FALSE(dry.drive->slipping());
  EXPECT_TRUE(ice.drive->slipping());
  EXPECT_LT(ice.robot->forward_speed(), 0.02 * kGravity / std::sqrt(2.0) * 0.3 * 1.02);
  const double wheel_ground_speed = ice.drive->wheel_speeds()[0] * ice.drive->true_radius(0);
  EXPECT_GT(wheel_ground_speed, 5.0 * ice.robot->forward_speed());
}

TEST(MecanumDrive, SlipperyPatchOnlyAffectsWheelsOnIt) {
  Rig rig(0.8);
  PatchDef p;
  p.name = "ice";
  p.friction = 0.0;
  p.polygon = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};  // under the front-left wheel
  rig.world->CreatePatch(p);
  // In steady motion the three other wheels still determine the body's three degrees of freedom.
  rig.Command({0.2, 0.0, 0.0});
  rig.Run(1.0);
  EXPECT_NEAR(rig.robot->forward_speed(), 0.2, 2e-3);
  EXPECT_TRUE(rig.drive->wheel_slipping(control::agv::kFrontLeft));
  EXPECT_FALSE(rig.drive->wheel_slipping(control::agv::kRearRight));
  EXPECT_DOUBLE_EQ(rig.drive->traction()[control::agv::kFrontLeft], 0.0);
}

TEST(WheelEncoders, CountTicksAndAddNoise) {
  WheelEncoderDef def;
  def.ticks_per_rev = 100;
  def.speed_noise = 0.0;
  WheelEncoders enc(def, Rng(3));
  enc.Latch({0, 0, 0, 0});
  const double tick = 2 * control::kPi / 100;
  const control::agv::WheelArray w = enc.Read({10.5 * tick, -3.2 * tick, 0, 2 * control::kPi}, 0.1);
  EXPECT_NEAR(w[0], 10 * tick / 0.1, 1e-9);
  EXPECT_NEAR(w[1], -4 * tick / 0.1, 1e-9);  // floor: -3.2 ticks reads -4
  EXPECT_NEAR(w[3], 2 * control::kPi / 0.1, 1e-9);
  def.speed_noise = 0.1;
  enc.SetDef(def);
  enc.Latch({0, 0, 0, 2 * control::kPi});
  double sum_sq = 0;
  const int n = 4000;
  for (int k = 0; k < n; ++k) {
    const control::agv::WheelArray r = enc.Read({0, 0, 0, 2 * control::kPi}, 0.1);
    sum_sq += r[0] * r[0];
  }
  EXPECT_NEAR(std::sqrt(sum_sq / n), 0.1, 0.005);
}

TEST(BeaconSensor, PeriodNoiseOutliersAndDropouts) {
  BeaconDef def;
  def.period = 0.1;
  def.sigma_xy = 0.01;
  def.outlier_probability = 0.1;
  def.outlier_size = 0.5;
  def.dropout_probability = 0.2;
  BeaconSensor b(def, Rng(11));
  const Pose2 truth{1.0, 2.0, control::kPi - 0.001};
  int samples = 0, dropouts = 0, outliers = 0, far_outliers = 0;
  double sum_sq = 0;
  for (int step = 0; step <= 100000; ++step) {
    const double t = step * 0.01;
    if (!b.Due(t)) continue;
    const BeaconFix f = b.Sample(t, truth);
    ++samples;
    EXPECT_LE(std::abs(f.pose.theta), control::kPi);  // wrapped
    if (!f.valid) {
      ++dropouts;
      continue;
    }
    const double d = (f.pose.p() - truth.p()).Norm();
    if (f.outlier) {
      ++outliers;
      if (d > 0.2) ++far_outliers;
    } else {
      sum_sq += (f.pose.x - truth.x) * (f.pose.x - truth.x);
    }
  }
  EXPECT_EQ(samples, 10001);  // every 10th step of 0.01 s
  EXPECT_NEAR(dropouts / double(samples), 0.2, 0.015);
  EXPECT_NEAR(outliers / double(samples - dropouts), 0.1, 0.01);
  EXPECT_EQ(far_outliers, outliers);  // size 0.5·U(0.5, 1.5) ≥ 0.25 m minus noise
  EXPECT_NEAR(std::sqrt(sum_sq / (samples - dropouts - outliers)), 0.01, 0.001);
}

TEST(BeaconSensor, SameSeedSameReadingsWhateverTheRates) {
  // The noise of a sample does not depend on the outlier or dropout settings (fixed draws).
  BeaconDef a, b;
  b.outlier_probability = 0.0;
  a.outlier_probability = 0.0;
  b.dropout_probability = 0.5;
  BeaconSensor sa(a, Rng(5)), sb(b, Rng(5));
  for (int k = 0; k < 50; ++k) {
    const BeaconFix fa = sa.Sample(k * 0.1, {}), fb = sb.Sample(k * 0.1, {});
    EXPECT_DOUBLE_EQ(fa.pose.x, fb.pose.x);
  }
}

}  // namespace
}  // namespace formsim::sim::agv
