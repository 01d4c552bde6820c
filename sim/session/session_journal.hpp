#pragma once
/// \file The crash-safe journal of a window's session record. While `formsim gui` runs, every
/// event of its SessionRecord (scenario texts, edits with their steps, resets, ...) is appended
/// to a journal file as it happens and flushed to the disk (fflush + fdatasync), and so is the
/// step the run has reached, now and then. A kill -9, an OOM kill or a power cut therefore leaves
/// a journal that RecoverJournal turns back into a SessionRecord, which `formsim replay`
/// reproduces up to the last entry. The file is append-only: each entry is framed by its length
/// and checksum, so a torn last entry (the process died while writing it) is dropped on recovery.
///
/// Journals live in a per-user state folder (JournalDir()), one per running window, named by
/// the window's pid and start time and locked (flock) while the window runs: a journal nobody
/// holds is an unfinished session, offered for restore at the next start.

#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "sim/session/session_record.hpp"

namespace formsim::sim {

/// The folder journals are kept in: $FORMSIM_STATE_DIR if set (tests), else
/// $XDG_STATE_HOME/formsim, else ~/.local/state/formsim ("" when there is no home).
std::string JournalDir();

/// What a journal held when recovered.
struct RecoveredSession {
  std::string path;         ///< the journal file
  SessionRecord record;     ///< its events, end step = the last step written
  std::time_t started = 0;  ///< when the window that wrote it started
  std::string scenario;     ///< the name of the scenario it started with
  long pid = 0;             ///< the window's process
  std::size_t edits = 0;    ///< edit events in it
  bool torn = false;        ///< a torn trailing entry was dropped
};

/// Reads a journal back. Throws std::runtime_error naming the file when it is no journal or holds
/// no scenario; a torn or corrupt trailing entry ends the journal (what precedes it is kept).
RecoveredSession RecoverJournal(const std::string& path);
/// True when `text` starts like a journal (so `formsim replay` takes either file).
bool LooksLikeJournal(const std::string& text);
/// Parses journal text (as RecoverJournal, without the file).
RecoveredSession ParseJournal(const std::string& text, const std::string& path);

/// Journals in `dir` whose window is gone (no process holds its lock) and that hold at least a
/// scenario, the newest first. Unreadable ones are skipped.
std::vector<RecoveredSession> UnfinishedSessions(const std::string& dir);

/// The journal of this window: created and locked in `dir`, appended to as the record grows.
/// Every write is checked; a failed one is kept in error() (the window says so once) and the
/// journal stops writing rather than leaving a gap.
class SessionJournal {
 public:
  /// Creates `dir` if needed and a new journal "session-<pid>-<time>.journal" in it, locked.
  /// Throws std::runtime_error naming the file when it cannot.
  SessionJournal(const std::string& dir, const std::string& scenario_name);
  /// Closes the file (it stays on disk: Remove() deletes it).
  ~SessionJournal();
  SessionJournal(const SessionJournal&) = delete;
  SessionJournal& operator=(const SessionJournal&) = delete;

  /// Appends one event of the record (with the scenario text it refers to, once per text).
  void Append(const SessionEvent& e);
  /// Writes the step the run has reached, when it changed and `min_seconds` passed since the
  /// last write (so a replay of the journal goes up to about then).
  void NoteStep(long step, double min_seconds = 1.0);
  /// Starts the journal afresh with every event of `record` (a restored session).
  void Rewrite(const SessionRecord& record, long step);
  /// Deletes the journal file (the session was saved or the window closed cleanly).
  void Remove();
  const std::string& path() const { return path_; }
  /// "" or why the last write failed.
  const std::string& error() const { return error_; }

 private:
  void WriteEntry(const std::string& payload);
  void Open(bool truncate);

  std::string path_, scenario_, error_;
  std::FILE* file_ = nullptr;
  std::vector<std::string> written_sources_;  ///< SHA-256 of the texts already in the file
  long last_step_ = -1;
  double last_step_time_ = 0;
};

}  // namespace formsim::sim
