// Formation switching (scheduled and asked-for transitions of every slot) and obstacle
// avoidance (the obstacle law and its switch events) of the formation experiment, with the
// bookkeeping of how the formation recovers after each switch.
#include <algorithm>
#include <cmath>

#include "sim/core/number_format.hpp"
#include "sim/formation/formation_experiment.hpp"

namespace formsim::sim::formation {
namespace {

using cf::FormationLaw;

constexpr const char* kFormationSwitch = "formation_switch";
constexpr const char* kAvoidance = "avoidance";
constexpr const char* kAvoidanceEnd = "avoidance_end";
constexpr const char* kSwitchAction = "switch-formation";

}  // namespace

std::vector<ActionSpec> FormationExperiment::Actions() const {
  std::vector<ActionSpec> out;
  if (!cfg_.switching.enabled()) return out;
  const std::string g = "Switching";
  out.push_back({kSwitchAction, "Next formation (n)", g,
                 "switch to the next shape (initial, then the shapes in order) over the transition time"});
  out.push_back({std::string(kSwitchAction) + ":initial", "initial", g, "switch to the follow: formation"});
  for (const ShapeDef& s : cfg_.switching.shapes)
    out.push_back({std::string(kSwitchAction) + ":" + s.name, s.name, g, "switch to shape " + s.name});
  return out;
}

std::string FormationExperiment::RunAction(const std::string& id) {
  const std::string prefix = std::string(kSwitchAction) + ":";
  if (!cfg_.switching.enabled() || (id != kSwitchAction && id.rfind(prefix, 0) != 0))
    return Experiment::RunAction(id);
  int shape;
  if (id == kSwitchAction) {
    // The next shape in the cycle initial, shapes[0], shapes[1], ...
    const int from = in_transition_ ? target_ : shape_;
    shape = from + 1 >= static_cast<int>(cfg_.switching.shapes.size()) ? -1 : from + 1;
  } else {
    shape = cfg_.switching.Find(id.substr(prefix.size()));
    if (shape == -2) return "no shape '" + id.substr(prefix.size()) + "' in this scenario";
  }
  return StartSwitch(shape, time(), cfg_.switching.transition, "asked for");
}

std::string FormationExperiment::StartSwitch(int shape, double t, double duration, const std::string& why) {
  auto name = [&](int s) { return s < 0 ? std::string("initial") : cfg_.switching.shapes[s].name; };
  if (in_transition_)
    return "a transition to '" + name(target_) + "' is in progress until t = " +
           Sprintf("%.2f", transition_.start + transition_.duration) + " s";
  if (shape == shape_) return "the formation is already '" + name(shape) + "'";
  transition_.from = slots_;
  transition_.to = cfg_.ShapeSlots(shape);
  transition_.start = t;
  transition_.duration = duration;
  in_transition_ = true;
  target_ = shape;
  std::string root;
  for (const FormationRobotDef& r : cfg_.robots)
    if (r.node.law == FormationLaw::kRoot) root += (root.empty() ? "" : ",") + r.body.name;
  events_.Add(t, kFormationSwitch, root,
              "formation '" + name(shape_) + "' -> '" + name(shape) + "' over " +
                  Sprintf("%.3g", duration) + " s (" + why + ")",
              name(shape));
  OpenRecord(t, "formation", name(shape));
  return "";
}

void FormationExperiment::UpdateSlots(double t) {
  if (in_transition_ && transition_.Done(t)) {
    in_transition_ = false;
    shape_ = target_;
  }
  // The schedule, in order; an entry due during a transition waits for its end.
  const auto& schedule = cfg_.switching.schedule;
  if (!in_transition_ && next_switch_ < schedule.size()) {
    const SwitchDef& s = schedule[next_switch_];
    bool due = false;
    std::string why;
    if (s.trigger == SwitchDef::Trigger::kTime) {
      due = t >= s.at - 1e-9;
      if (due) why = Sprintf("scheduled at t = %g s", s.at);
    } else {
      const Vec2 p = agents_[static_cast<std::size_t>(s.robot)].robot->pose().p();
      due = (p - s.waypoint).Norm() <= s.radius;
      if (due)
        why = "waypoint [" + Sprintf("%g, %g", s.waypoint.x, s.waypoint.y) + "] reached by " +
              cfg_.robots[static_cast<std::size_t>(s.robot)].body.name;
    }
    if (due) {
      ++next_switch_;
      StartSwitch(s.shape, t, s.transition, why);  // refused only when already in that shape
    }
  }
  if (in_transition_) {
    for (std::size_t j = 0; j < slots_.size(); ++j) slots_[j] = transition_.At(static_cast<int>(j), t, &slot_rates_[j]);
    return;
  }
  for (std::size_t j = 0; j < slots_.size(); ++j) {
    slots_[j] = shape_ < 0 ? cf::SlotOf(cfg_.robots[j].node) : cfg_.switching.shapes[shape_].slots[j];
    slot_rates_[j] = {};
  }
}

void FormationExperiment::OpenRecord(double t, const std::string& kind, const std::string& what) {
  if (!switches_.empty() && switches_.back().end < 0.0) switches_.back().end = t;
  SwitchRecord r;
  r.time = t;
  r.kind = kind;
  r.what = what;
  switches_.push_back(r);
}

cf::Twist FormationExperiment::Avoid(int j, double t, const cf::Twist& nominal) {
  Agent& a = agents_[static_cast<std::size_t>(j)];
  const FormationRobotDef& r = cfg_.robots[static_cast<std::size_t>(j)];
  const AvoidanceConfig& av = cfg_.avoidance;
  const bool usable = av.enabled && a.near.obstacle >= 0;
  const Pose2 pose = a.robot->pose();
  const double rate = usable ? cf::DistanceRate(a.near.point, pose, nominal, cfg_.L) : 0.0;
  const bool next =
      usable && cf::NextAvoiding(a.avoiding, a.near.distance, a.slot_d, rate, t - a.avoid_since, av.def);
  if (next != a.avoiding) {
    const std::string obstacle =
        a.near.obstacle >= 0 ? world_.obstacles()[static_cast<std::size_t>(a.near.obstacle)].name : "";
    const std::string& leader = cfg_.robots[static_cast<std::size_t>(links_[a.links[0]].leader)].body.name;
    if (next) {
      ++avoid_entries_;
      events_.Add(t, kAvoidance, r.body.name,
                  r.body.name + Sprintf(" within %.3f m of ", a.near.distance) + "'" + obstacle +
                      "': l-l law with " + leader + " and the obstacle's nearest point [" +
                      Sprintf("%.3f, %.3f", a.near.point.x, a.near.point.y) + "] as virtual leader at " +
                      Sprintf("%g m", av.def.safety_distance),
                  obstacle);
    } else {
      events_.Add(t, kAvoidanceEnd, r.body.name,
                  r.body.name + " clear of '" + obstacle + "'" +
                      (a.near.obstacle >= 0 ? Sprintf(" (slot %.3f m away)", a.slot_d) : std::string()) +
                      ": back to its " + (r.node.law == FormationLaw::kLPhi ? "l-φ" : "l-l") + " law",
                  obstacle);
      OpenRecord(t, "avoidance_end", r.body.name);
    }
    a.avoiding = next;
    a.avoid_since = t;
  }
  if (!next) return nominal;
  const Link& l1 = links_[a.links[0]];
  const cf::FormationGains gains{Gain(r.follow.k1), Gain(av.k_obstacle)};
  const cf::SlotValues& s = slots_[static_cast<std::size_t>(j)];
  const double l_rate = in_transition_ ? slot_rates_[static_cast<std::size_t>(j)].l_des : 0.0;
  return cf::AvoidanceControl(ForControl(l1), agents_[l1.leader].cmd, s.l_des, l_rate, a.near.point,
                              pose, av.def.safety_distance, gains, cfg_.L, cfg_.singular_threshold)
      .cmd;
}

double FormationExperiment::FormationError() const {
  double worst = 0.0;
  for (const Link& l : links_) {
    if (agents_[static_cast<std::size_t>(l.follower)].avoiding) continue;
    worst = std::max(worst, std::abs(DesiredL(l) - l.truth.l));
    if (cfg_.robots[static_cast<std::size_t>(l.follower)].node.law == FormationLaw::kLPhi)
      worst = std::max(worst, std::abs(control::WrapToPi(slots_[static_cast<std::size_t>(l.follower)].phi_des -
                                                          l.truth.phi)));
  }
  return worst;
}

void FormationExperiment::TrackSwitches(double t) {
  const bool settled = t >= cfg_.settle_time - 1e-9;
  for (const CollisionEvent& c : world_.new_collisions())
    if (c.time >= cfg_.settle_time - 1e-9) ++collisions_after_;
  formation_error_ = FormationError();
  if (settled) max_error_settled_ = std::max(max_error_settled_, formation_error_);
  if (!switches_.empty() && switches_.back().end < 0.0 && formation_error_ >= kRecoveredError)
    switches_.back().last_above = t;
}

}  // namespace formsim::sim::formation
