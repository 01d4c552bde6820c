#include "control/inspection/dead_reckoning.hpp"

#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::control::inspection {

OdometryIncrement DifferentialOdometry(double ds_left, double ds_right, double track) {
  OdometryIncrement inc;
  inc.ds = 0.5 * (ds_left + ds_right);
  inc.dtheta = track > 0.0 ? (ds_left - ds_right) / track : 0.0;
  return inc;
}

PaperPose DeadReckonStep(const PaperPose& pose, double ds, double theta) {
  PaperPose next = pose;
  next.x = pose.x + ds * std::sin(theta);
  next.y = pose.y + ds * std::cos(theta);
  return next;
}

void DeadReckoning::Step(const OdometryIncrement& inc) {
  pose_ = DeadReckonStep(pose_, inc.ds, pose_.theta);
  pose_.theta = WrapToPi(pose_.theta + inc.dtheta);
}

}  // namespace formsim::control::inspection
