#include "sim/session/session_record.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <stdexcept>

#include "sim/core/number_format.hpp"
#include "sim/session/record_yaml.hpp"
#include "sim/core/run_output.hpp"
#include "sim/session/session_journal.hpp"

namespace formsim::sim {
namespace {

using Kind = SessionEvent::Kind;

// The name of each kind in the file (`do:`), both ways.
const std::vector<std::pair<Kind, std::string>>& KindNames() {
  static const std::vector<std::pair<Kind, std::string>> k = {
      {Kind::kLoad, "load"},     {Kind::kEdit, "edit"},     {Kind::kApply, "apply"},
      {Kind::kAction, "action"}, {Kind::kMove, "move"},     {Kind::kReset, "reset"},
      {Kind::kReload, "reload"}, {Kind::kBranch, "branch"}, {Kind::kEnd, "end"},
      {Kind::kRestructure, "restructure"}};
  return k;
}

std::string KindName(const SessionEvent& e) {
  if (e.kind == Kind::kNote) return e.key;
  for (const auto& [k, n] : KindNames())
    if (k == e.kind) return n;
  return "?";
}

SourceList Sources(const std::vector<SessionEvent>& events) {
  SourceList out;
  for (const SessionEvent& e : events) AddSource(out, e.source);
  return out;
}

std::string Emit(const std::vector<SessionEvent>& events, long end_step, bool quoted_texts) {
  YAML::Emitter y;
  y << YAML::Comment(
           "formsim session: what was done in the window, step by step. Replay it headless "
           "with `formsim replay FILE --out DIR`")
    << YAML::Newline;
  y << YAML::BeginMap;
  y << YAML::Key << "formsim_session" << YAML::Value << 1;
  y << YAML::Key << "formsim_version" << YAML::Value << FormsimVersion();
  EmitSources(y, "scenarios", Sources(events), quoted_texts);
  y << YAML::Key << "events" << YAML::Value << YAML::BeginSeq;
  auto event = [&](const SessionEvent& e) {
    y << YAML::Flow << YAML::BeginMap << YAML::Key << "do" << YAML::Value << KindName(e)
      << YAML::Key << "step" << YAML::Value << e.step;
    switch (e.kind) {
      case Kind::kLoad:
        y << YAML::Key << "scenario" << YAML::Value << e.source->sha256();
        EmitOverrides(y, "overrides", e.overrides);
        break;
      case Kind::kReload:
        y << YAML::Key << "scenario" << YAML::Value << e.source->sha256();
        break;
      case Kind::kRestructure:
        y << YAML::Key << "scenario" << YAML::Value << e.source->sha256() << YAML::Key
          << "command" << YAML::Value << e.key << YAML::Key << "origin" << YAML::Value
          << e.origin;
        break;
      case Kind::kEdit:
        y << YAML::Key << "key" << YAML::Value << e.key << YAML::Key << "value" << YAML::Value
          << e.value << YAML::Key << "origin" << YAML::Value << e.origin;
        break;
      case Kind::kAction:
        y << YAML::Key << "id" << YAML::Value << e.key << YAML::Key << "origin" << YAML::Value
          << e.origin;
        break;
      case Kind::kMove:
        y << YAML::Key << "name" << YAML::Value << e.key << YAML::Key << "x" << YAML::Value
          << FormatDouble(e.x) << YAML::Key << "y" << YAML::Value << FormatDouble(e.y);
        break;
      case Kind::kReset:
        if (e.has_seed) y << YAML::Key << "seed" << YAML::Value << std::to_string(e.seed);
        break;
      case Kind::kBranch:
        y << YAML::Key << "at" << YAML::Value << e.at;
        break;
      case Kind::kNote:
        if (!e.value.empty()) y << YAML::Key << "detail" << YAML::Value << e.value;
        break;
      case Kind::kApply:
      case Kind::kEnd:
        break;
    }
    y << YAML::EndMap;
  };
  for (const SessionEvent& e : events) event(e);
  SessionEvent end;
  end.kind = Kind::kEnd;
  end.step = end_step;
  event(end);
  y << YAML::EndSeq << YAML::EndMap;
  if (!y.good()) throw std::runtime_error(std::string("session record: ") + y.GetLastError());
  return std::string(y.c_str()) + "\n";
}

}  // namespace

const std::vector<std::string>& SessionRecord::NoteNames() {
  static const std::vector<std::string> k = {"pin",     "unpin",   "unpin-all",
                                             "pin-row", "restore", "seeds"};
  return k;
}

std::string SessionRecord::ToYaml(long end_step) const {
  std::string text = Emit(events_, end_step, false);
  // Literal blocks cannot hold every text (trailing spaces, tabs, a leading blank line): when a
  // text does not read back exactly, every text is written double-quoted (always exact).
  try {
    const SessionRecord back = Parse(text, "(check)");
    if (SameTexts(Sources(events_), Sources(back.events_))) return text;
  } catch (const std::exception&) {
  }
  return Emit(events_, end_step, true);
}

void SessionRecord::Write(const std::string& path, long end_step) const {
  WriteFileAtomic(path, ToYaml(end_step));
}

SessionRecord SessionRecord::Read(const std::string& file) {
  const std::string text = ReadRecordFile(file, "session file");
  // A window's crash-safe journal replays like a session file (up to its last entry).
  if (LooksLikeJournal(text)) return ParseJournal(text, file).record;
  return Parse(text, file);
}

SessionRecord SessionRecord::Parse(const std::string& text, const std::string& file) {
  const RecordReader r{file};
  const YAML::Node root = LoadRecordText(text, file);
  if (r.Text(root, "formsim_session") != "1")
    r.Fail(root["formsim_session"], "formsim_session", "unknown format (expected 1)");
  const auto sources = ParseSources(r, r.List(root, "scenarios"));
  auto source = [&](const YAML::Node& e) {
    const std::string sha = r.Text(e, "scenario");
    const auto it = sources.find(sha);
    if (it == sources.end()) r.Fail(e, "scenario", "no text with SHA-256 " + sha + " in scenarios");
    return it->second;
  };
  const YAML::Node events = r.List(root, "events");
  SessionRecord out;
  for (const YAML::Node& n : events) {
    if (!n.IsMap()) r.Fail(n, "events", "each event must be a map");
    SessionEvent e;
    const std::string what = r.Text(n, "do");
    e.step = r.Step(n, "step");
    e.kind = Kind::kNote;
    for (const auto& [k, name] : KindNames())
      if (name == what) e.kind = k;
    switch (e.kind) {
      case Kind::kLoad:
        e.source = source(n);
        e.overrides = ParseOverrides(r, n, "overrides");
        break;
      case Kind::kReload:
        e.source = source(n);
        break;
      case Kind::kRestructure:
        e.source = source(n);
        e.key = r.Text(n, "command", false);
        e.origin = r.Text(n, "origin");
        break;
      case Kind::kEdit:
        e.key = r.Text(n, "key");
        e.value = r.Text(n, "value");
        e.origin = r.Text(n, "origin");
        break;
      case Kind::kAction:
        e.key = r.Text(n, "id");
        e.origin = r.Text(n, "origin");
        break;
      case Kind::kMove:
        e.key = r.Text(n, "name");
        e.x = r.Real(n, "x");
        e.y = r.Real(n, "y");
        break;
      case Kind::kReset:
        if (n["seed"]) {
          e.has_seed = true;
          if (!ParseUint64(r.Text(n, "seed"), &e.seed))
            r.Fail(n["seed"], "seed", "must be a whole number in [0, 18446744073709551615]");
        }
        break;
      case Kind::kBranch:
        e.at = r.Step(n, "at");
        break;
      case Kind::kNote:
        if (std::find(NoteNames().begin(), NoteNames().end(), what) == NoteNames().end())
          r.Fail(n["do"], "do", "unknown event '" + what + "'");
        e.key = what;
        e.value = r.Text(n, "detail", false);
        break;
      case Kind::kApply:
      case Kind::kEnd:
        break;
    }
    if (!out.events_.empty() && out.events_.back().kind == Kind::kEnd)
      r.Fail(n, "do", "an event after the end");
    out.events_.push_back(std::move(e));
  }
  if (out.events_.empty() || out.events_.front().kind != Kind::kLoad)
    r.Fail(events, "events", "must start with a load (the scenario)");
  // The end is written by ToYaml only; in memory a record never holds one.
  if (out.events_.back().kind == Kind::kEnd) {
    out.end_step_ = out.events_.back().step;
    out.events_.pop_back();
  }
  return out;
}

SessionReplay::SessionReplay(SessionRecord record, std::function<void(Experiment&)> run_setup)
    : record_(std::move(record)), run_setup_(std::move(run_setup)) {
  if (record_.empty() || record_.events().front().kind != Kind::kLoad)
    throw std::runtime_error("a session record starts with the scenario it loaded");
  Do(record_.events().front(), 0);
  next_ = 1;
}

void SessionReplay::Do(const SessionEvent& e, std::size_t index) {
  const std::string where = "event " + std::to_string(index + 1) + " (" + KindName(e) +
                            " at step " + std::to_string(e.step) + ")";
  auto check = [&](const std::string& err) {
    if (!err.empty())
      throw std::runtime_error("replay: " + where + " went otherwise than recorded: " + err);
  };
  switch (e.kind) {
    case Kind::kLoad: {
      std::unique_ptr<Session> s;
      try {
        s = std::make_unique<Session>(*e.source, e.overrides);
      } catch (const std::exception& ex) {
        throw std::runtime_error("replay: " + where + ": " + ex.what());
      }
      if (session_ && run_setup_) session_->exp().mutable_recorder().AbandonStream();
      if (run_setup_) s->SetRunSetup(run_setup_);
      session_ = std::move(s);
      break;
    }
    case Kind::kEdit:
      check(session_->Edit(e.key, e.value, e.origin));
      break;
    case Kind::kApply:
      session_->ApplyPending();
      break;
    case Kind::kAction:
      check(session_->Action(e.key, e.origin));
      break;
    case Kind::kMove:
      session_->Move(e.key, e.x, e.y);
      break;
    case Kind::kReset:
      check(e.has_seed ? session_->Reset(e.seed) : session_->Reset());
      break;
    case Kind::kReload:
      check(session_->ReloadFrom(*e.source));
      break;
    case Kind::kRestructure:
      check(session_->RestructureFrom(*e.source, e.key, e.origin));
      break;
    case Kind::kBranch:
      check(session_->Branch(e.at));
      break;
    case Kind::kNote:
    case Kind::kEnd:
      break;
  }
}

bool SessionReplay::Advance() {
  if (ended_) return false;
  const auto& events = record_.events();
  while (next_ <= events.size()) {
    const bool at_end = next_ == events.size();
    Experiment& exp = session_->exp();
    const long due = !at_end                   ? events[next_].step
                     : record_.end_step() >= 0 ? record_.end_step()
                                               : exp.steps();
    if (exp.steps() < due) {
      if (exp.finished())
        throw std::runtime_error("replay: the run ended at step " + std::to_string(exp.steps()) +
                                 ", before step " + std::to_string(due) +
                                 " of the record: it went otherwise than recorded");
      session_->Step();
      return true;
    }
    if (exp.steps() > due)
      throw std::runtime_error("replay: event " + std::to_string(next_ + 1) + " is at step " +
                               std::to_string(due) + " but the run is at step " +
                               std::to_string(exp.steps()) + " already");
    if (at_end) break;
    Do(events[next_], next_);
    ++next_;
  }
  ended_ = true;
  return false;
}

}  // namespace formsim::sim
