#include "sim/session/session_journal.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "sim/core/bounded_file.hpp"
#include "sim/core/fnv_hash.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/wall_clock.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {
namespace {

constexpr char kMagic[] = "formsim-journal 1\n";
// A journal larger than this is not read back (a scenario text is at most a few MB).
constexpr std::uintmax_t kMaxJournalBytes = std::uintmax_t{256} << 20;

std::string Hex(std::uint64_t v) {
  return Sprintf("%016llx", static_cast<unsigned long long>(v));
}

// Fields of an entry: "<length>:<bytes>" one after the other (any bytes, no escaping).
void Field(std::string& out, const std::string& v) {
  out += std::to_string(v.size());
  out += ':';
  out += v;
}

class Fields {
 public:
  explicit Fields(const std::string& s) : s_(s) {}
  std::string Next() {
    const auto colon = s_.find(':', pos_);
    if (colon == std::string::npos || colon == pos_ || colon - pos_ > 12)
      throw std::runtime_error("bad field");
    std::size_t n = 0;
    for (std::size_t i = pos_; i < colon; ++i) {
      if (s_[i] < '0' || s_[i] > '9') throw std::runtime_error("bad field length");
      n = n * 10 + static_cast<std::size_t>(s_[i] - '0');
    }
    if (n > s_.size() - colon - 1) throw std::runtime_error("field past the entry");
    std::string v = s_.substr(colon + 1, n);
    pos_ = colon + 1 + n;
    return v;
  }
  long Long() {
    long long v = 0;
    if (!ParseInteger(Next(), -(1LL << 62), 1LL << 62, &v)) throw std::runtime_error("bad number");
    return static_cast<long>(v);
  }
  double Real() {
    double v = 0;
    if (!ParseFiniteDouble(Next(), &v)) throw std::runtime_error("bad number");
    return v;
  }

 private:
  const std::string& s_;
  std::size_t pos_ = 0;
};

// Every text an event refers to.
const ScenarioSource* SourceOf(const SessionEvent& e) {
  return e.source.get();
}

std::string EventPayload(const SessionEvent& e) {
  std::string p;
  Field(p, "ev");
  Field(p, std::to_string(static_cast<int>(e.kind)));
  Field(p, std::to_string(e.step));
  Field(p, e.key);
  Field(p, e.value);
  Field(p, e.origin);
  Field(p, FormatDouble(e.x));
  Field(p, FormatDouble(e.y));
  Field(p, e.has_seed ? "1" : "0");
  Field(p, std::to_string(e.seed));
  Field(p, std::to_string(e.at));
  Field(p, e.source ? e.source->sha256() : "");
  Field(p, std::to_string(e.overrides.size()));
  for (const Override& o : e.overrides) {
    Field(p, o.key);
    Field(p, o.value);
    Field(p, o.origin);
    Field(p, std::to_string(o.step));
  }
  return p;
}

}  // namespace

std::string JournalDir() {
  if (const char* env = std::getenv("FORMSIM_STATE_DIR"); env != nullptr && *env != '\0')
    return env;
  if (const char* xdg = std::getenv("XDG_STATE_HOME"); xdg != nullptr && *xdg != '\0')
    return (fs::path(xdg) / "formsim").string();
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
    return (fs::path(home) / ".local" / "state" / "formsim").string();
  return "";
}

bool LooksLikeJournal(const std::string& text) {
  return text.compare(0, sizeof(kMagic) - 1, kMagic) == 0;
}

RecoveredSession ParseJournal(const std::string& text, const std::string& path) {
  if (!LooksLikeJournal(text)) throw std::runtime_error(path + ": not a formsim session journal");
  RecoveredSession out;
  out.path = path;
  std::map<std::string, std::shared_ptr<const ScenarioSource>> sources;
  std::size_t pos = sizeof(kMagic) - 1;
  long step = -1;
  while (pos < text.size()) {
    // "J <length> <checksum>\n<payload>\n"; anything short or wrong ends the journal (torn).
    const auto eol = text.find('\n', pos);
    if (eol == std::string::npos || text.compare(pos, 2, "J ") != 0) {
      out.torn = true;
      break;
    }
    std::istringstream head(text.substr(pos + 2, eol - pos - 2));
    std::size_t len = 0;
    std::string sum;
    if (!(head >> len >> sum) || len > text.size() - eol - 1 || eol + 1 + len >= text.size() ||
        text[eol + 1 + len] != '\n') {
      out.torn = true;
      break;
    }
    const std::string payload = text.substr(eol + 1, len);
    if (Hex(Fnv1a64(payload)) != sum) {
      out.torn = true;
      break;
    }
    pos = eol + 2 + len;
    try {
      Fields f(payload);
      const std::string type = f.Next();
      if (type == "meta") {
        out.pid = f.Long();
        out.started = static_cast<std::time_t>(f.Long());
        out.scenario = f.Next();
      } else if (type == "src") {
        const std::string sha = f.Next(), file = f.Next(), dir = f.Next(), body = f.Next();
        auto src = std::make_shared<ScenarioSource>(ScenarioSource::FromText(body, file, dir));
        if (src->sha256() != sha) throw std::runtime_error("scenario text changed");
        sources[sha] = src;
      } else if (type == "step") {
        step = f.Long();
      } else if (type == "reset") {  // a restored session rewrote the journal
        out.record = SessionRecord();
        step = -1;
      } else if (type == "ev") {
        SessionEvent e;
        const long kind = f.Long();
        if (kind < 0 || kind > static_cast<long>(SessionEvent::Kind::kEnd))
          throw std::runtime_error("unknown event");
        e.kind = static_cast<SessionEvent::Kind>(kind);
        e.step = f.Long();
        e.key = f.Next();
        e.value = f.Next();
        e.origin = f.Next();
        e.x = f.Real();
        e.y = f.Real();
        e.has_seed = f.Next() == "1";
        if (!ParseUint64(f.Next(), &e.seed)) throw std::runtime_error("bad seed");
        e.at = f.Long();
        const std::string sha = f.Next();
        if (!sha.empty()) {
          const auto it = sources.find(sha);
          if (it == sources.end()) throw std::runtime_error("no text for " + sha);
          e.source = it->second;
        }
        const long n = f.Long();
        for (long i = 0; i < n; ++i) {
          Override o;
          o.key = f.Next();
          o.value = f.Next();
          o.origin = f.Next();
          o.step = f.Long();
          e.overrides.push_back(std::move(o));
        }
        if (e.kind == SessionEvent::Kind::kEdit) ++out.edits;
        if (out.record.empty() && e.kind != SessionEvent::Kind::kLoad)
          throw std::runtime_error("the first event is not a load");
        step = std::max(step, e.step);
        out.record.Add(e);
      }
    } catch (const std::exception&) {
      out.torn = true;  // a checksum that matches garbage: treat like a torn entry
      break;
    }
  }
  if (out.record.empty()) throw std::runtime_error(path + ": the journal holds no scenario yet");
  out.record.SetEndStep(step);
  return out;
}

RecoveredSession RecoverJournal(const std::string& path) {
  // Through the one bounded reader: checked on the opened descriptor, so the file cannot be
  // swapped for a device between the check and the read.
  return ParseJournal(ReadBoundedFile(path, kMaxJournalBytes), path);
}

std::vector<RecoveredSession> UnfinishedSessions(const std::string& dir) {
  std::vector<RecoveredSession> out;
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec)) return out;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string p = entry.path().string();
    if (entry.path().extension() != ".journal" || !entry.is_regular_file(ec)) continue;
    const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;
    // A window that runs holds its journal's lock; a journal nobody holds is unfinished.
    const bool free = ::flock(fd, LOCK_SH | LOCK_NB) == 0;
    ::close(fd);
    if (!free) continue;
    try {
      out.push_back(RecoverJournal(p));
    } catch (const std::exception&) {
    }
  }
  std::sort(out.begin(), out.end(), [](const RecoveredSession& a, const RecoveredSession& b) {
    return a.started != b.started ? a.started > b.started : a.path > b.path;
  });
  return out;
}

SessionJournal::SessionJournal(const std::string& dir, const std::string& scenario_name)
    : scenario_(scenario_name) {
  if (dir.empty()) throw std::runtime_error("no folder for the session journal (HOME is unset)");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error(dir + ": cannot create the session journal's folder");
  const std::time_t now = std::time(nullptr);
  // A new file (O_EXCL): a name taken (the same pid and second) gets a suffix.
  for (int n = 0;; ++n) {
    path_ = (fs::path(dir) / ("session-" + std::to_string(::getpid()) + "-" + std::to_string(now) +
                              (n > 0 ? "-" + std::to_string(n) : "") + ".journal"))
                .string();
    if (!fs::exists(path_, ec) || n >= 100) break;
  }
  Open(true);
  std::string meta;
  Field(meta, "meta");
  Field(meta, std::to_string(::getpid()));
  Field(meta, std::to_string(now));
  Field(meta, scenario_);
  WriteEntry(meta);
  if (!error_.empty()) throw std::runtime_error(error_);
}

void SessionJournal::Open(bool truncate) {
  const int fd =
      ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (truncate ? O_EXCL : O_APPEND), 0600);
  if (fd < 0)
    throw std::runtime_error(path_ +
                             ": cannot create the session journal: " + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    throw std::runtime_error(path_ + ": the session journal is held by another window");
  }
  file_ = ::fdopen(fd, "ab");
  if (file_ == nullptr) {
    ::close(fd);
    throw std::runtime_error(path_ + ": cannot open the session journal");
  }
  if (std::fwrite(kMagic, 1, sizeof(kMagic) - 1, file_) != sizeof(kMagic) - 1)
    error_ = path_ + ": cannot write the session journal";
}

SessionJournal::~SessionJournal() {
  if (file_ != nullptr) std::fclose(file_);  // releases the lock
}

void SessionJournal::WriteEntry(const std::string& payload) {
  if (file_ == nullptr || !error_.empty()) return;
  const std::string head = "J " + std::to_string(payload.size()) + " " + Hex(Fnv1a64(payload)) + "\n";
  const bool ok = std::fwrite(head.data(), 1, head.size(), file_) == head.size() &&
                  std::fwrite(payload.data(), 1, payload.size(), file_) == payload.size() &&
                  std::fputc('\n', file_) != EOF && std::fflush(file_) == 0 &&
                  ::fdatasync(::fileno(file_)) == 0;
  if (!ok)
    error_ = path_ + ": the session journal could not be written (" + std::strerror(errno) +
             "); the session is not protected against a crash";
}

void SessionJournal::Append(const SessionEvent& e) {
  if (const ScenarioSource* s = SourceOf(e);
      s != nullptr && std::find(written_sources_.begin(), written_sources_.end(), s->sha256()) ==
                          written_sources_.end()) {
    std::string p;
    Field(p, "src");
    Field(p, s->sha256());
    Field(p, s->file());
    Field(p, s->dir());
    Field(p, s->text());
    WriteEntry(p);
    written_sources_.push_back(s->sha256());
  }
  WriteEntry(EventPayload(e));
  last_step_ = std::max(last_step_, e.step);
}

void SessionJournal::NoteStep(long step, double min_seconds) {
  if (step == last_step_) return;
  const double now = WallSeconds();
  if (now - last_step_time_ < min_seconds) return;
  std::string p;
  Field(p, "step");
  Field(p, std::to_string(step));
  WriteEntry(p);
  last_step_ = step;
  last_step_time_ = now;
}

void SessionJournal::Rewrite(const SessionRecord& record, long step) {
  // Appended, not truncated: a crash while rewriting keeps the old content readable up to the
  // "reset" entry, after which the new content starts.
  std::string p;
  Field(p, "reset");
  WriteEntry(p);
  written_sources_.clear();
  last_step_ = -1;
  for (const SessionEvent& e : record.events()) Append(e);
  last_step_time_ = 0;
  NoteStep(step, 0);
}

void SessionJournal::Remove() {
  std::error_code ec;
  fs::remove(path_, ec);
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
}

}  // namespace formsim::sim
