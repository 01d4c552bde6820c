#pragma once
/// \file A session record: everything done to a tuning session, each with the step of the run it
/// happened at: the scenario loaded (its path, the SHA-256 of its text and the text itself, so a
/// replay never depends on the file staying as it was), the command-line overrides, every
/// accepted edit, every apply between two steps, drag, action, reset, seed change, reload,
/// branch, pin and the last step. Written as YAML by `formsim gui --session FILE` and the "Save
/// session" button; `formsim replay FILE` does it all again headless through sim::Session,
/// which, the simulation being deterministic, gives the same runs bit for bit.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/session/session.hpp"

namespace formsim::sim {

class SessionRecord {
 public:
  /// Appends an event (as a Session observer, and for loads, pins and notes of the GUI).
  void Add(const SessionEvent& e) {
    events_.push_back(e);
    if (listener_) listener_(e);
  }
  /// Called with every event added from now on (the window's crash-safe journal).
  void SetListener(std::function<void(const SessionEvent&)> listener) { listener_ = std::move(listener); }
  /// The step the record ends at when written without one (a recovered journal).
  void SetEndStep(long step) { end_step_ = step; }
  const std::vector<SessionEvent>& events() const { return events_; }
  bool empty() const { return events_.empty(); }

  /// The record as YAML text, ended by an `end` event at `end_step` (steps of the current run).
  std::string ToYaml(long end_step) const;
  /// Writes ToYaml(end_step) to `path` atomically. Throws std::runtime_error.
  void Write(const std::string& path, long end_step) const;
  /// Reads a record. Throws std::runtime_error naming file:line and the key at fault.
  static SessionRecord Parse(const std::string& text, const std::string& file);
  static SessionRecord Read(const std::string& file);
  /// The names of the events kept for the record only (SessionEvent::Kind::kNote).
  static const std::vector<std::string>& NoteNames();
  /// The step the record ends at, as read from a file (-1: none; the replay then stops after
  /// the last event).
  long end_step() const { return end_step_; }

 private:
  std::vector<SessionEvent> events_;
  long end_step_ = -1;
  std::function<void(const SessionEvent&)> listener_;
};

/// Does a record again, headless, through sim::Session: each event at its step (the run is
/// stepped until then), in order, then steps until the recorded end.
class SessionReplay {
 public:
  /// `run_setup` is applied to every experiment the replayed sessions build (streaming the rows
  /// to disk, the history bound), as the GUI applies its own. Throws std::runtime_error when the
  /// record does not start with a scenario or the scenario does not load.
  explicit SessionReplay(SessionRecord record, std::function<void(Experiment&)> run_setup = {});

  /// Does the events due at the current step, then one step of the run when the next event (or
  /// the end) lies ahead. Returns false once the record's end is reached. Throws
  /// std::runtime_error naming the event when the record does not fit (a step that lies
  /// behind the run, an edit refused now that was accepted then, a run that ended early).
  bool Advance();
  Session& session() { return *session_; }
  /// Hands over the replayed session (a restored window session goes on from it).
  std::unique_ptr<Session> Release() { return std::move(session_); }
  /// Events done so far and in all (for a progress line).
  std::size_t done() const { return next_; }
  std::size_t total() const { return record_.events().size(); }

 private:
  void Do(const SessionEvent& e, std::size_t index);

  SessionRecord record_;
  std::function<void(Experiment&)> run_setup_;
  std::unique_ptr<Session> session_;
  std::size_t next_ = 0;
  bool ended_ = false;
};

}  // namespace formsim::sim
