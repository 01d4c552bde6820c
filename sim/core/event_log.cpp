#include "sim/core/event_log.hpp"

namespace formsim::sim {

void EventLog::Increment(std::map<std::string, Counts, std::less<>>& table, const std::string& kind,
                         std::string_view key) {
  auto k = table.find(kind);
  if (k == table.end()) k = table.emplace(kind, Counts{}).first;
  auto c = k->second.find(key);
  if (c == k->second.end()) c = k->second.emplace(std::string(key), 0).first;
  ++c->second;
}

long EventLog::Lookup(const std::map<std::string, Counts, std::less<>>& table,
                      const std::string& kind, std::string_view key) {
  const auto k = table.find(kind);
  if (k == table.end()) return 0;
  const auto c = k->second.find(key);
  return c == k->second.end() ? 0 : c->second;
}

void EventLog::Add(double t, const std::string& kind, const std::string& robots,
                   const std::string& message, const std::string& subject) {
  auto kind_count = by_kind_.find(kind);
  if (kind_count == by_kind_.end()) kind_count = by_kind_.emplace(kind, 0).first;
  if (++kind_count->second <= kMaxStoredPerKind)
    events_.push_back({t, kind, robots, subject, message});
  // The ring's slots keep their strings, so assigning into them reuses their capacity.
  Event& r = recent_.PushSlot();
  r.time = t;
  r.kind = kind;
  r.robots = robots;
  r.subject = subject;
  r.message = message;
  ++total_;
  if (!subject.empty()) Increment(by_subject_, kind, subject);
  const std::string_view all(robots);
  std::size_t start = 0;
  while (start <= all.size()) {
    const std::size_t end = all.find(',', start);
    const std::string_view robot =
        all.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
    if (!robot.empty()) Increment(by_robot_, kind, robot);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
}

EventLog::ConditionId EventLog::DeclareCondition(const std::string& kind, const std::string& robots,
                                                 const std::string& subject) {
  conditions_.push_back({kind, robots, subject});
  active_.push_back(0);
  return static_cast<ConditionId>(conditions_.size() - 1);
}

long EventLog::Count(const std::string& kind) const {
  const auto it = by_kind_.find(kind);
  return it == by_kind_.end() ? 0 : it->second;
}

long EventLog::CountForRobot(const std::string& kind, const std::string& robot) const {
  return Lookup(by_robot_, kind, robot);
}

long EventLog::CountForSubject(const std::string& kind, const std::string& subject) const {
  return Lookup(by_subject_, kind, subject);
}

}  // namespace formsim::sim
