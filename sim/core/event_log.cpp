#include "sim/core/event_log.hpp"

namespace formsim::sim {

void EventLog::Add(double t, const std::string& kind, const std::string& robots,
                   const std::string& message, const std::string& subject) {
  Event e{t, kind, robots, subject, message};
  if (++by_kind_[kind] <= kMaxStoredPerKind) events_.push_back(e);
  recent_.push_back(std::move(e));
  if (recent_.size() > kRecent) recent_.pop_front();
  ++total_;
  if (!subject.empty()) ++by_subject_[{kind, subject}];
  std::size_t start = 0;
  while (start <= robots.size()) {
    const std::size_t end = robots.find(',', start);
    const std::string r = robots.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!r.empty()) ++by_robot_[{kind, r}];
    if (end == std::string::npos) break;
    start = end + 1;
  }
}

EventLog::ConditionId EventLog::DeclareCondition(const std::string& kind,
                                                 const std::string& robots,
                                                 const std::string& subject) {
  conditions_.push_back({kind, robots, subject, false});
  return static_cast<ConditionId>(conditions_.size() - 1);
}

long EventLog::Count(const std::string& kind) const {
  const auto it = by_kind_.find(kind);
  return it == by_kind_.end() ? 0 : it->second;
}

long EventLog::CountForRobot(const std::string& kind, const std::string& robot) const {
  const auto it = by_robot_.find({kind, robot});
  return it == by_robot_.end() ? 0 : it->second;
}

long EventLog::CountForSubject(const std::string& kind, const std::string& subject) const {
  const auto it = by_subject_.find({kind, subject});
  return it == by_subject_.end() ? 0 : it->second;
}

}  // namespace formsim::sim
