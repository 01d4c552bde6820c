#pragma once
/// \file Standard Mecanum kinematics (paper 002, eq. 1-6, whose bodies were lost in the text).
///
/// Frames and conventions (used everywhere in the Mecanum code):
///  - Body frame: origin at the body centre o_r, x forward, y to the left, z up; yaw rate ω is
///    counter-clockwise positive. A twist is (vx, vy, ω) in this frame.
///  - Wheel order: 0 = front-left (FL), 1 = front-right (FR), 2 = rear-left (RL), 3 = rear-right
///    (RR). Wheel i sits at (x_i, y_i) = (±lx, ±ly): FL (+lx, +ly), FR (+lx, -ly),
///    RL (-lx, +ly), RR (-lx, -ly), lx = half wheelbase, ly = half track.
///  - A positive wheel speed ω_i [rad/s] rolls the wheel so that it drives the body forward (+x).
///  - Rollers at α = 45° to the hub axis, "X" layout seen from above: the axis of the roller in
///    contact with the floor points along a_i = (1, s_i)/√2 in the body frame, with the roller
///    sign s_FL = s_RR = -1 and s_FR = s_RL = +1. The roller turns freely about a_i's
///    perpendicular, so the floor only transmits force along a_i and the no-slip condition is
///    a_i · v_contact = r ω_i (x̂ · a_i), i.e. r ω_i = v_cx + s_i v_cy.
///
/// Inverse kinematics (twist -> wheel speeds), L = lx + ly:
///   ω_FL = (vx - vy - L ω) / r     ω_FR = (vx + vy + L ω) / r
///   ω_RL = (vx + vy - L ω) / r     ω_RR = (vx - vy + L ω) / r
/// Forward kinematics (least squares, the pseudo-inverse of the above):
///   vx = r/4 ( ω_FL + ω_FR + ω_RL + ω_RR)
///   vy = r/4 (-ω_FL + ω_FR + ω_RL - ω_RR)
///   ω  = r/(4L) (-ω_FL + ω_FR - ω_RL + ω_RR)
/// Pure sideways motion to the left gives (-, +, +, -); pure CCW rotation gives (-, +, -, +).

#include <array>

#include "control/common/geometry.hpp"

namespace formsim::control::agv {

enum MecanumWheel { kFrontLeft = 0, kFrontRight = 1, kRearLeft = 2, kRearRight = 3 };
constexpr int kMecanumWheels = 4;
/// Short wheel names in that order (column names, labels).
inline constexpr const char* kWheelNames[kMecanumWheels] = {"FL", "FR", "RL", "RR"};

/// Four wheel values in the order FL, FR, RL, RR (speeds in rad/s, angles in rad, ...).
using WheelArray = std::array<double, kMecanumWheels>;

/// A planar body twist: vx forward and vy left [m/s] in the body frame, ω CCW [rad/s].
struct BodyTwist {
  double vx = 0.0;
  double vy = 0.0;
  double omega = 0.0;
};

/// Geometry of a four-wheel Mecanum platform.
struct MecanumGeometry {
  double wheel_radius = 0.076;   ///< r, m
  double half_wheelbase = 0.25;  ///< lx: body centre to front/rear axle, m
  double half_track = 0.22;      ///< ly: body centre to the left/right wheel plane, m

  /// Roller sign s_i of wheel i (-1 for FL and RR, +1 for FR and RL).
  static double RollerSign(int wheel);
  /// Position of wheel i's contact point in the body frame.
  Vec2 WheelPosition(int wheel) const;
  /// Unit vector of the contact roller's axis in the body frame: (1, s_i)/√2.
  static Vec2 RollerAxis(int wheel);
};

/// Wheel speeds [rad/s] that realise `twist` without slip.
WheelArray InverseKinematics(const MecanumGeometry& g, const BodyTwist& twist);
/// Least-squares body twist from four wheel speeds [rad/s]. Exact when the speeds are
/// consistent (come from InverseKinematics); otherwise the best fit.
BodyTwist ForwardKinematics(const MecanumGeometry& g, const WheelArray& wheel_speeds);

/// Scales all four speeds by one factor so that none exceeds `limit` in magnitude (keeps the
/// direction of motion). Returns the factor applied (1 when nothing was limited).
double ScaleToLimit(WheelArray& wheel_speeds, double limit);

}  // namespace formsim::control::agv
