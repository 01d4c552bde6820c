#pragma once
/// \file A generated cascade of N robots as a scenario tree (for benchmarks and tests).
///
/// Layout: a grid of ⌈√N⌉ columns at `spacing` metres, filled row by row behind the root R1
/// (row 0 is the front line, column 0 the left edge). Front-line robots follow their left
/// neighbour with l-φ (control point beside it), column-0 robots follow the robot ahead with
/// l-φ (straight behind), every other robot follows the robot ahead and its left neighbour with
/// l-l; the cascade depth is rows + columns − 2. Robots start on their desired slots displaced
/// by a deterministic few centimetres, so the controllers have something to correct. The root
/// runs the line-curve schedule at 2.5 m/s with a gentle ω = 0.05 rad/s (turn radius 50 m, wide
/// enough for a 1000-robot grid of about 16 m).

#include <string>

namespace formsim::sim::formation {

/// The YAML text of a `type: formation` scenario with `n_robots` robots (≥ 1); with `ukf` every follower
/// runs a UKF per link on noisy angle measurements (the paper's noise), otherwise it uses the
/// true link state. dt = Tc = 0.01 s, duration 10 s, per-sample gains, record_every 10.
std::string MakeCascadeScenario(int n_robots, bool ukf, double spacing = 0.5);

}  // namespace formsim::sim::formation
