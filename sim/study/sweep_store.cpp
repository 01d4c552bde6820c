#include "sim/study/sweep_store.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {
namespace {

constexpr const char* kManifestHead = "formsim sweep manifest 1";
constexpr const char* kRecordHead = "formsim sweep run 1";

// One field of a line: backslash, space, newline and carriage return escaped, so a line splits
// on spaces and every byte of a message survives.
std::string Esc(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '\\':
        out += "\\\\";
        break;
      case ' ':
        out += "\\s";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        out += c;
    }
  }
  return out.empty() ? "\\e" : out;  // an empty field still takes its place
}

bool Unesc(const std::string& s, std::string* out) {
  out->clear();
  if (s == "\\e") return true;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\') {
      *out += s[i];
      continue;
    }
    if (++i == s.size()) return false;
    switch (s[i]) {
      case '\\':
        *out += '\\';
        break;
      case 's':
        *out += ' ';
        break;
      case 'n':
        *out += '\n';
        break;
      case 'r':
        *out += '\r';
        break;
      case 't':
        *out += '\t';
        break;
      default:
        return false;
    }
  }
  return true;
}

// Reads the lines of a manifest or record, failing with the file and line.
class LineReader {
 public:
  LineReader(const std::string& text, std::string where) : in_(text), where_(std::move(where)) {}
  // The next line's fields (unescaped); false at the end.
  bool Next(std::vector<std::string>* fields) {
    std::string line;
    if (!std::getline(in_, line)) return false;
    ++line_;
    fields->clear();
    std::istringstream ls(line);
    std::string f, u;
    while (ls >> f) {
      if (!Unesc(f, &u)) Fail("bad escape in '" + f + "'");
      fields->push_back(u);
    }
    return true;
  }
  [[noreturn]] void Fail(const std::string& why) const {
    throw std::runtime_error(where_ + ":" + std::to_string(line_) + ": " + why);
  }
  std::uint64_t Uint(const std::string& s) const {
    std::uint64_t v = 0;
    if (!ParseUint64(s, &v)) Fail("expected a non-negative integer, got '" + s + "'");
    return v;
  }

 private:
  std::istringstream in_;
  std::string where_;
  int line_ = 0;
};

// A manifest or run file; a manifest lists every value of every axis, so it gets the limit of
// any text file formsim reads (bounded_file.hpp).
std::string ReadText(const std::string& path) {
  return ReadBoundedFile(path);
}

const char* KindName(Param::Kind k) {
  switch (k) {
    case Param::Kind::kDouble:
      return "real";
    case Param::Kind::kInt:
      return "integer";
    case Param::Kind::kBool:
      return "flag";
    case Param::Kind::kChoice:
      return "choice";
  }
  return "real";
}

// Why two definitions of a sweep differ, in words.
std::string Difference(const SweepDefinition& a, const SweepDefinition& b) {
  if (a.scenarios.size() != b.scenarios.size())
    return "the scenarios differ (" + std::to_string(a.scenarios.size()) + " vs " +
           std::to_string(b.scenarios.size()) + ")";
  for (std::size_t i = 0; i < a.scenarios.size(); ++i)
    if (a.scenarios[i].sha256 != b.scenarios[i].sha256)
      return "the scenario's text differs (" + a.scenarios[i].file + " vs " + b.scenarios[i].file +
             ")";
  if (a.axes.size() != b.axes.size()) return "the varied keys differ";
  for (std::size_t i = 0; i < a.axes.size(); ++i) {
    if (a.axes[i].key != b.axes[i].key)
      return "the varied keys differ (" + a.axes[i].key + " vs " + b.axes[i].key + ")";
    if (a.axes[i].values != b.axes[i].values) return "the values of " + a.axes[i].key + " differ";
  }
  if (a.seeds != b.seeds) return "the seeds differ";
  if (a.sample_seed != b.sample_seed) return "the sample seed differs";
  return "the --set overrides differ";
}

const char* BetterName(Better b) {
  return b == Better::kLower ? "lower" : b == Better::kHigher ? "higher" : "none";
}

}  // namespace

void FillRecordMetrics(const Metrics& results, SweepRecord* rec) {
  rec->metrics = results.Scalars(MetricRole::kResult);
  rec->settings = results.Scalars(MetricRole::kSetting);
  rec->info.clear();
  for (const auto& m : rec->metrics) {
    const MetricInfo info = results.InfoOf(m.first);
    if (!info.label.empty() || !info.unit.empty() || info.better != Better::kNone ||
        info.headline != 0)
      rec->info.emplace_back(m.first, info);
  }
}

namespace {

// A number of a record, or "-" for one the run could not compute (NaN).
void AppendRecordNumber(std::string& t, double value) {
  // "nan" and "inf" are never written, so one found in a run file was put there by hand.
  if (std::isfinite(value))
    AppendDouble(t, value);
  else
    t += "-";
}

}  // namespace

std::string ManifestPath(const std::string& dir) {
  return (fs::path(dir) / "sweep.manifest").string();
}

std::string RecordPath(const std::string& dir, std::size_t run) {
  return (fs::path(dir) / "runs" / Sprintf("%06zu.run", run)).string();
}

std::string ManifestText(const SweepDefinition& def) {
  std::string t = std::string(kManifestHead) + "\n";
  t += "id " + def.id + "\n";
  for (const SweepScenario& sc : def.scenarios) {
    t += "scenario " + Esc(sc.file) + "\n";
    t += "scenario_sha256 " + sc.sha256 + "\n";
  }
  t += "sample_seed " + std::to_string(def.sample_seed) + "\n";
  t += "seeds";
  for (std::uint64_t s : def.seeds) t += " " + std::to_string(s);
  t += "\n";
  for (const Override& o : def.sets)
    t += "set " + Esc(o.key) + " " + Esc(o.value) + " " + Esc(o.origin) + "\n";
  for (const SweepAxis& a : def.axes) {
    t += "axis " + Esc(a.key) + " " + KindName(a.kind) + " " + (a.log_scale ? "log" : "linear") +
         " " + (a.random ? "random" : "grid") + " " + Esc(a.spec) + "\n";
    for (const std::string& c : a.choices) t += "choice " + Esc(c) + "\n";
    for (const std::string& v : a.values) t += "value " + Esc(v) + "\n";
  }
  t += "runs " + std::to_string(def.runs()) + "\nend\n";
  return t;
}

SweepDefinition ParseManifest(const std::string& text, const std::string& where) {
  LineReader in(text, where);
  std::vector<std::string> f;
  if (!in.Next(&f) || f.size() != 4 || f[0] + " " + f[1] + " " + f[2] + " " + f[3] != kManifestHead)
    in.Fail("not a formsim sweep manifest");
  SweepDefinition def;
  std::string id;
  std::uint64_t runs = 0;
  bool ended = false;
  while (in.Next(&f)) {
    if (f.empty()) continue;
    const std::string& k = f[0];
    auto need = [&](std::size_t n) {
      if (f.size() != n) in.Fail("'" + k + "' takes " + std::to_string(n - 1) + " fields");
    };
    if (k == "id") {
      need(2);
      id = f[1];
    } else if (k == "scenario") {
      need(2);
      def.scenarios.push_back({f[1], ""});  // one line pair per scenario, in order
    } else if (k == "scenario_sha256") {
      need(2);
      if (def.scenarios.empty()) in.Fail("'scenario_sha256' before any 'scenario'");
      def.scenarios.back().sha256 = f[1];
    } else if (k == "sample_seed") {
      need(2);
      def.sample_seed = in.Uint(f[1]);
    } else if (k == "seeds") {
      for (std::size_t i = 1; i < f.size(); ++i) def.seeds.push_back(in.Uint(f[i]));
    } else if (k == "set") {
      need(4);
      def.sets.push_back({f[1], f[2], f[3], -1});
    } else if (k == "axis") {
      need(6);
      SweepAxis a;
      a.key = f[1];
      if (f[2] == "real")
        a.kind = Param::Kind::kDouble;
      else if (f[2] == "integer")
        a.kind = Param::Kind::kInt;
      else if (f[2] == "flag")
        a.kind = Param::Kind::kBool;
      else if (f[2] == "choice")
        a.kind = Param::Kind::kChoice;
      else
        in.Fail("unknown axis kind '" + f[2] + "'");
      a.log_scale = f[3] == "log";
      a.random = f[4] == "random";
      a.spec = f[5];
      def.axes.push_back(a);
    } else if (k == "choice" || k == "value") {
      need(2);
      if (def.axes.empty()) in.Fail("'" + k + "' before any axis");
      (k == "choice" ? def.axes.back().choices : def.axes.back().values).push_back(f[1]);
    } else if (k == "runs") {
      need(2);
      runs = in.Uint(f[1]);
    } else if (k == "end") {
      ended = true;
      break;
    } else {
      in.Fail("unknown line '" + k + "'");
    }
  }
  if (!ended) in.Fail("incomplete manifest (no 'end' line)");
  if (def.seeds.empty()) in.Fail("no seeds");
  if (def.scenarios.empty()) in.Fail("no scenario");
  for (const SweepAxis& a : def.axes)
    if (a.values.empty()) in.Fail("axis " + a.key + " has no values");
  try {
    def.Finish();
  } catch (const std::exception& e) {
    in.Fail(e.what());
  }
  if (def.id != id || def.runs() != runs)
    throw std::runtime_error(where + ": the manifest does not match its id (edited by hand?)");
  return def;
}

bool HasManifest(const std::string& dir) {
  std::error_code ec;
  return fs::exists(ManifestPath(dir), ec);
}

SweepDefinition ReadManifest(const std::string& dir) {
  if (!HasManifest(dir))
    throw std::runtime_error("'" + dir + "' holds no sweep (no sweep.manifest)");
  return ParseManifest(ReadText(ManifestPath(dir)), ManifestPath(dir));
}

void WriteManifest(const std::string& dir, const SweepDefinition& def) {
  PrepareOutputDir(dir);
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "runs", ec);
  if (ec)
    throw std::runtime_error("cannot create '" + (fs::path(dir) / "runs").string() +
                             "': " + ec.message());
  if (HasManifest(dir)) {
    const SweepDefinition there = ReadManifest(dir);
    if (there.id != def.id)
      throw std::runtime_error("'" + dir + "' holds another sweep: " + Difference(there, def) +
                               "; choose another --out");
    return;
  }
  WriteFileAtomic(ManifestPath(dir), ManifestText(def));
}

std::string RecordText(const SweepDefinition& def, const SweepRecord& rec) {
  std::string t = std::string(kRecordHead) + "\n";
  t += "sweep " + def.id + "\n";
  t += "run " + std::to_string(rec.run) + "\n";
  t += "status " + Esc(rec.status) + "\n";
  t += "message " + Esc(rec.message) + "\n";
  // A metric the run could not compute (a route never completed: NaN) is written as "-".
  for (const auto& [name, value] : rec.metrics) {
    t += "m " + Esc(name) + " ";
    AppendRecordNumber(t, value);
    t += "\n";
  }
  for (const auto& [name, value] : rec.settings) {
    t += "s " + Esc(name) + " ";
    AppendRecordNumber(t, value);
    t += "\n";
  }
  // d NAME BETTER HEADLINE UNIT LABEL: what the kind declared about a metric.
  for (const auto& [name, info] : rec.info)
    t += "d " + Esc(name) + " " + BetterName(info.better) + " " + std::to_string(info.headline) +
         " " + Esc(info.unit) + " " + Esc(info.label) + "\n";
  t += "end\n";
  return t;
}

SweepRecord ParseRecord(const std::string& text, const SweepDefinition& def,
                        const std::string& where) {
  LineReader in(text, where);
  std::vector<std::string> f;
  if (!in.Next(&f) || f.size() != 4 || f[0] + " " + f[1] + " " + f[2] + " " + f[3] != kRecordHead)
    in.Fail("not a formsim sweep run record");
  SweepRecord rec;
  bool ended = false, has_run = false;
  while (in.Next(&f)) {
    if (f.empty()) continue;
    const std::string& k = f[0];
    if (k == "sweep") {
      if (f.size() != 2 || f[1] != def.id) in.Fail("the record belongs to another sweep");
    } else if (k == "run" && f.size() == 2) {
      rec.run = static_cast<std::size_t>(in.Uint(f[1]));
      has_run = true;
    } else if (k == "status" && f.size() == 2) {
      rec.status = f[1];
    } else if (k == "message" && f.size() == 2) {
      rec.message = f[1];
    } else if ((k == "m" || k == "s") && f.size() == 3) {
      double v = 0;
      // "-": the run computed no value (NaN in the tables). Anything else is a finite number:
      // formsim never writes nan or inf here, so such a value was edited in, and is refused.
      if (f[2] == "-")
        v = std::numeric_limits<double>::quiet_NaN();
      else if (!ParseFiniteDouble(f[2], &v))
        in.Fail("metric '" + f[1] + "': '" + f[2] +
                "' is not a finite number (a run file holds finite numbers, or '-' for a value "
                "the run could not compute; was it edited?)");
      (k == "m" ? rec.metrics : rec.settings).emplace_back(f[1], v);
    } else if (k == "d" && f.size() == 6) {
      MetricInfo info;
      if (f[2] == "lower")
        info.better = Better::kLower;
      else if (f[2] == "higher")
        info.better = Better::kHigher;
      else if (f[2] != "none")
        in.Fail("metric '" + f[1] + "': unknown direction '" + f[2] + "'");
      info.headline = static_cast<int>(std::min<std::uint64_t>(in.Uint(f[3]), 1000000));
      info.unit = f[4];
      info.label = f[5];
      rec.info.emplace_back(f[1], info);
    } else if (k == "end") {
      ended = true;
      break;
    } else {
      in.Fail("unexpected line '" + k + "'");
    }
  }
  if (!ended || !has_run || rec.status.empty()) in.Fail("incomplete record");
  if (rec.run >= def.runs()) in.Fail("run " + std::to_string(rec.run) + " is not in the sweep");
  return rec;
}

void WriteRecord(const std::string& dir, const SweepDefinition& def, const SweepRecord& rec) {
  // Temp file + rename: whole or absent whatever happens to the process. Not synced one by one
  // (an fsync costs as much as a run); SyncFileSystem at the end, RemoveDamagedRecords after a
  // power cut.
  WriteFileAtomic(RecordPath(dir, rec.run), RecordText(def, rec), false);
}

std::vector<std::string> RemoveDamagedRecords(const std::string& dir,
                                              const std::vector<std::size_t>& runs) {
  std::vector<std::string> removed;
  std::error_code ec;
  for (std::size_t r : runs) {
    const std::string path = RecordPath(dir, r);
    if (!fs::exists(path, ec)) continue;
    const std::string text = ReadText(path);
    if (text.size() >= 4 && text.compare(text.size() - 4, 4, "end\n") == 0) continue;
    fs::remove(path, ec);
    removed.push_back(path);
  }
  return removed;
}

std::vector<SweepRecord> ReadRecords(const std::string& dir, const SweepDefinition& def) {
  std::vector<SweepRecord> out;
  const fs::path runs = fs::path(dir) / "runs";
  std::error_code ec;
  if (!fs::is_directory(runs, ec)) return out;
  for (const auto& entry : fs::directory_iterator(runs)) {
    const std::string name = entry.path().filename().string();
    if (name.size() < 5 || name.compare(name.size() - 4, 4, ".run") != 0)
      continue;  // .tmp leftovers
    const std::string stem = name.substr(0, name.size() - 4);
    std::uint64_t run = 0;
    if (!ParseUint64(stem, &run)) continue;
    SweepRecord rec = ParseRecord(ReadText(entry.path().string()), def, entry.path().string());
    if (rec.run != run)
      throw std::runtime_error(entry.path().string() + ": holds run " + std::to_string(rec.run));
    out.push_back(std::move(rec));
  }
  std::sort(out.begin(), out.end(),
            [](const SweepRecord& a, const SweepRecord& b) { return a.run < b.run; });
  return out;
}

std::vector<std::size_t> PendingRuns(const std::string& dir, const std::vector<std::size_t>& runs) {
  std::vector<std::size_t> out;
  std::error_code ec;
  for (std::size_t r : runs)
    if (!fs::exists(RecordPath(dir, r), ec)) out.push_back(r);
  return out;
}

std::vector<std::size_t> ShardRuns(std::size_t total, int k, int n) {
  std::vector<std::size_t> out;
  for (std::size_t r = static_cast<std::size_t>(k - 1); r < total; r += static_cast<std::size_t>(n))
    out.push_back(r);
  return out;
}

void ParseShard(const std::string& text, int* k, int* n) {
  const std::size_t slash = text.find('/');
  long long a = 0, b = 0;
  if (slash == std::string::npos || !ParseInteger(text.substr(0, slash), 1, 1000000, &a) ||
      !ParseInteger(text.substr(slash + 1), 1, 1000000, &b) || a > b)
    throw std::runtime_error("--shard '" + text + "': expected K/N with 1 <= K <= N, e.g. 3/8");
  *k = static_cast<int>(a);
  *n = static_cast<int>(b);
}

}  // namespace formsim::sim
