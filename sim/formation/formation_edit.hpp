#pragma once
/// \file Structural changes of a formation scenario's text: the commands of
/// FormationExperiment::RestructuredText (Session::Restructure, the GUI's formation editor and
/// the `formation` script action). The result is only text: the one loader checks it (cycle,
/// missing leader, impossible or flat triangle) before anything runs it.
///
/// Commands (names as in the scenario, LEADERS comma-separated, coordinates in metres):
///   add LAW LEADERS X Y [NAME]   a follower at (X, Y), heading as its first leader, whose
///                                desired slot is where it is placed (l, φ or the two distances
///                                measured from its leaders as they are now); NAME defaults to
///                                the next free "R<k>"
///   remove NAME                  the robot goes (refused by the loader while others follow it)
///   attach NAME LAW LEADERS      new leaders and law (l_phi or l_l); the desired slot is where
///                                the follower is now, so it does not jump
///   shape KIND [SPACING]         the whole graph and slots of a named shape (column,
///                                line_abreast, wedge, diamond, v, grid) for the robots there
///                                are, `SPACING` m apart (default 0.5), the first root leader at
///                                its place and every other robot placed on its slot
///   ""                           nothing but the robots' poses

#include <map>
#include <string>

#include "control/common/geometry.hpp"

namespace formsim::sim::formation {

/// The formation as it is now: each robot's pose by name, and the control point offset.
struct FormationState {
  std::map<std::string, Pose2> poses;
  double L = 0.15;
  bool carry_poses = false;  ///< write every remaining robot's pose into the text
};

/// `text` with `command` applied. Throws std::runtime_error naming what is wrong with the
/// command (unknown robot, law or shape, malformed numbers).
std::string RestructureFormationText(const std::string& text, const std::string& command,
                                     const FormationState& state);

}  // namespace formsim::sim::formation
