#pragma once
/// \file Structural changes of a formation scenario's text (FormationEditing::Restructured:
/// Session::Restructure through formation::Restructure, the window's formation editor and the
/// `formation` script action). The result is only text: the one loader checks it (cycle,
/// missing leader, impossible or flat triangle) before anything runs it.
///
///   AddFollower     a follower at (x, y), heading as its first leader, whose desired slot is
///                   where it is placed (l, φ or the two distances measured from its leaders as
///                   they are now); the name defaults to the next free "R<k>"
///   RemoveRobot     the robot goes (refused by the loader while others follow it)
///   AttachFollower  new leaders and law; the desired slot is where the follower is now, so it
///                   does not jump
///   ApplyShape      the whole graph and slots of a named shape (column, line_abreast, wedge,
///                   diamond, v, grid) for the robots there are, `spacing` m apart, the first
///                   root leader at its place and every other robot placed on its slot
/// Every follow block is written by WriteFollow (formation_follow.hpp).

#include <map>
#include <string>

#include "control/common/geometry.hpp"
#include "sim/formation/formation_editing.hpp"

namespace formsim::sim::formation {

/// The formation as it is now: each robot's pose by name, and the control point offset.
struct FormationState {
  std::map<std::string, Pose2> poses;
  double L = 0.15;
  bool carry_poses = false;  ///< write every remaining robot's pose into the text
};

/// `text` with `change` applied. Throws std::runtime_error naming what is wrong with the change
/// (unknown robot, wrong number of leaders, spacing out of range).
std::string RestructureFormationText(const std::string& text, const StructureChange& change,
                                     const FormationState& state);
/// `text` with nothing changed but the robots' poses (when `state.carry_poses`).
std::string PlacedFormationText(const std::string& text, const FormationState& state);

}  // namespace formsim::sim::formation
