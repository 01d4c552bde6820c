#pragma once
/// \file Events: things that happened to robots (collisions, saturations, singular formations,
/// filter faults, numerical faults), with time, robots and the subject they concern (a link, a
/// filter). Conditions that last (a saturated drive) raise one event on entry, not one per
/// step. Counts are exact and indexed by kind, robot and subject, so summaries are linear in
/// the number of links plus events.
///
/// Raising an event allocates nothing once the log has seen its kind, robots and subject and its
/// storage for that kind is full: counts are looked up without temporaries, the recent events
/// are a ring whose strings keep their capacity, and a condition's message can be written into
/// the log's own buffer (a message function taking std::string&).

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "sim/core/ring_buffer.hpp"

namespace formsim::sim {

/// Kinds used by more than one experiment (an experiment may add its own strings).
namespace event {
inline constexpr const char* kCollision = "collision";
inline constexpr const char* kSaturation = "saturation";
inline constexpr const char* kSingular = "singular";
inline constexpr const char* kFilterFault = "filter_fault";
inline constexpr const char* kNumericalFault = "numerical_fault";
}  // namespace event

/// Something that happened.
struct Event {
  double time = 0.0;
  std::string kind;     ///< "collision", "saturation", "singular", "filter_fault", ...
  std::string robots;   ///< e.g. "R3" or "R1,R2"
  std::string subject;  ///< what it concerns beyond the robots, e.g. link "R1-R2"; may be empty
  std::string message;
};

class EventLog {
 public:
  /// Events stored per kind; later ones are counted (exactly) but not stored, so a run that
  /// collides a million times keeps a bounded log.
  static constexpr long kMaxStoredPerKind = 1000;
  /// The most recent events kept for display (flashes), whatever their kind.
  static constexpr std::size_t kRecent = 64;

  EventLog() : recent_(kRecent) {}

  /// Records an event at time `t`. `robots` is a comma-separated list of robot names.
  void Add(double t, const std::string& kind, const std::string& robots, const std::string& message,
           const std::string& subject = "");
  /// A lasting condition (a drive saturating, a follower near its singular line), declared
  /// once; Update() then raises one event on each entry into it and costs nothing per step
  /// otherwise (no allocation: `message` is only called when an event is raised). `message`
  /// either returns the text or, taking a std::string&, appends it to an empty buffer of the
  /// log's (which allocates nothing once the buffer has grown).
  using ConditionId = int;
  ConditionId DeclareCondition(const std::string& kind, const std::string& robots,
                               const std::string& subject = "");
  template <class MessageFn>
  bool Update(ConditionId id, double t, bool active, MessageFn&& message) {
    // Only the byte of its state is read unless an event is raised: a step over ten thousand
    // conditions that stay off touches 10 kB, not ten thousand Conds with their strings.
    unsigned char& on = active_[static_cast<std::size_t>(id)];
    const bool raise = active && !on;
    on = active;
    if (raise) {
      const Cond& c = conditions_[static_cast<std::size_t>(id)];
      if constexpr (std::is_invocable_v<MessageFn&, std::string&>) {
        message_.clear();
        message(message_);
        Add(t, c.kind, c.robots, message_, c.subject);
      } else {
        Add(t, c.kind, c.robots, message(), c.subject);
      }
    }
    return raise;
  }
  bool IsActive(ConditionId id) const { return active_[static_cast<std::size_t>(id)] != 0; }

  /// Stored events in time order (at most kMaxStoredPerKind of each kind).
  const std::vector<Event>& list() const { return events_; }
  /// The last kRecent events, stored or not, oldest first.
  const RingBuffer<Event>& recent() const { return recent_; }
  /// Number of events so far, stored or not.
  long total() const { return total_; }
  bool empty() const { return total_ == 0; }
  /// Events of `kind` so far (exact).
  long Count(const std::string& kind) const;
  /// Events of `kind` whose robots include `robot`.
  long CountForRobot(const std::string& kind, const std::string& robot) const;
  /// Events of `kind` about `subject`.
  long CountForSubject(const std::string& kind, const std::string& subject) const;
  /// Every kind seen, with its count, sorted by kind.
  const std::map<std::string, long>& counts() const { return by_kind_; }

 private:
  // Counts per kind, then per robot or subject (looked up by string_view: no temporaries).
  using Counts = std::map<std::string, long, std::less<>>;
  static void Increment(std::map<std::string, Counts, std::less<>>& table, const std::string& kind,
                        std::string_view key);
  static long Lookup(const std::map<std::string, Counts, std::less<>>& table,
                     const std::string& kind, std::string_view key);

  std::vector<Event> events_;
  RingBuffer<Event> recent_;
  long total_ = 0;
  std::map<std::string, long> by_kind_;
  std::map<std::string, Counts, std::less<>> by_robot_, by_subject_;
  std::string message_;  ///< the buffer condition messages are written into
  struct Cond {
    std::string kind, robots, subject;
  };
  std::vector<Cond> conditions_;
  std::vector<unsigned char> active_;  ///< per condition: on (kept apart from the strings)
};

}  // namespace formsim::sim
