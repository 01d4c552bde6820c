// The differential drive with DC motors: the motor law, traction limited by the floor's
// friction (slip emerges), steady slip growing on soft or slippery floors.
#include "sim/velocity/diff_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace formsim::sim::velocity {
namespace {

struct Rig {
  World world;
  Robot* robot = nullptr;
  DiffDrive* drive = nullptr;
  explicit Rig(double mu, TerrainDef terrain = TerrainDef{}) {
    WorldDef wd;
    wd.floor_friction = mu;
    world.SetDef(wd);
    RobotDef rd = DefaultRobotDef();
    rd.half_length = 0.22;
    rd.half_width = 0.17;
    rd.mass = 10.0;
    robot = &world.CreateRobot(rd);
    DiffDriveDef dd;
    dd.floor_terrain = terrain;
    auto d = std::make_unique<DiffDrive>(dd);
    drive = d.get();
    robot->SetDrive(std::move(d));
  }
  void Run(double seconds, double ul, double ur) {
    drive->SetVoltages(ul, ur);
    const int n = static_cast<int>(std::lround(seconds / 0.005));
    for (int k = 0; k < n; ++k) world.Step(0.005);
  }
};

TEST(DiffDrive, SteadySpeedFollowsTheMotorLaw) {
  Rig rig(0.9);
  rig.Run(3.0, 6.0, 6.0);
  const DiffDriveDef& d = rig.drive->def();
  const double w = rig.drive->wheel_speed(DiffDrive::kLeft);
  // Back-EMF balance: V = R i + k G ω with the small current that overcomes the losses.
  const double i = rig.drive->current(DiffDrive::kLeft);
  EXPECT_NEAR(6.0, d.motor.resistance * i + d.motor.torque_constant * d.motor.gear_ratio * w, 1e-3);
  EXPECT_GT(i, 0.0);
  EXPECT_LT(i, 1.0);
  // The body follows the wheels up to a small slip, straight ahead.
  EXPECT_NEAR(rig.robot->forward_speed(), w * d.wheel_radius, 0.01 * w * d.wheel_radius);
  EXPECT_LT(std::abs(rig.robot->yaw_rate()), 1e-3);
  EXPECT_LT(std::abs(rig.robot->pose().y), 1e-3);
}

TEST(DiffDrive, FullVoltageOnLowFrictionSpinsTheWheels) {
  Rig low(0.1), high(0.9);
  low.Run(0.4, 12.0, 12.0);
  high.Run(0.4, 12.0, 12.0);
  const double r = low.drive->def().wheel_radius;
  // The ground can push the robot at most with μ·(weight on the driven wheels).
  const double a_max = 0.1 * kGravity * (1.0 - low.drive->def().caster_load);
  EXPECT_LE(low.robot->forward_speed(), a_max * 0.4 + 1e-3);
  EXPECT_GT(low.drive->slip_ratio(DiffDrive::kLeft), 0.3);
  EXPECT_GT(low.drive->wheel_speed(DiffDrive::kLeft) * r, 1.5 * low.robot->forward_speed());
  EXPECT_TRUE(low.drive->slipping());
  // On a grippy floor the same voltage accelerates the robot far more, with little slip.
  EXPECT_GT(high.robot->forward_speed(), 2.0 * low.robot->forward_speed());
  EXPECT_LT(high.drive->slip_ratio(DiffDrive::kLeft), 0.3);
}

TEST(DiffDrive, SteadySlipGrowsOnSoftAndSlipperyGround) {
  // Same voltage, same speed range: slip at cruise is set by rolling resistance / μ and κ0.
  Rig tile(0.8, TerrainDef{0.015, 0.04});
  Rig gravel(0.55, TerrainDef{0.07, 0.25});
  tile.Run(3.0, 6.0, 6.0);
  gravel.Run(3.0, 6.0, 6.0);
  const double k_tile = tile.drive->slip_ratio(DiffDrive::kLeft);
  const double k_gravel = gravel.drive->slip_ratio(DiffDrive::kLeft);
  EXPECT_GT(k_tile, 0.0);
  EXPECT_GT(k_gravel, 10.0 * k_tile);
  // Terrain-shear law at steady state: κ = -κ0 ln(1 - F/μN) with F the rolling resistance.
  const double load = 10.0 * kGravity * 0.8 / 2.0;
  const double f = (0.07 * 10.0 * kGravity) / 2.0;  // wheels carry all rolling resistance
  EXPECT_NEAR(k_gravel, -0.25 * std::log(1.0 - f / (0.55 * load)), 0.15 * k_gravel);
}

TEST(DiffDrive, OppositeVoltagesTurnOnTheSpot) {
  Rig rig(0.9);
  rig.Run(2.0, -4.0, 4.0);
  EXPECT_GT(rig.robot->yaw_rate(), 1.0);
  EXPECT_LT(std::abs(rig.robot->forward_speed()), 0.02);
  EXPECT_LT(rig.robot->pose().p().Norm(), 0.05);
}

}  // namespace
}  // namespace formsim::sim::velocity
