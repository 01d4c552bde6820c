#include "sim/session/run_history.hpp"

#include <ctime>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>

#include "sim/core/number_format.hpp"
#include "sim/session/record_yaml.hpp"
#include "sim/core/run_output.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {
namespace {

std::string LocalTime() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  localtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S", &tm);
  return buf;
}

const char* BetterName(Better b) {
  return b == Better::kLower ? "lower" : b == Better::kHigher ? "higher" : "none";
}

bool EndsWithTail(const std::string& key, const std::string& tail) {
  return key == tail || (key.size() > tail.size() &&
                         key.compare(key.size() - tail.size(), tail.size(), tail) == 0 &&
                         key[key.size() - tail.size() - 1] == '.');
}

}  // namespace

int HistoryRow::mid_run_changes() const {
  int n = 0;
  for (const RunChange& c : log.changes)
    n += c.kind == RunChange::Kind::kEdits ? static_cast<int>(c.edits.size()) : 1;
  return n;
}

std::string HistoryRow::Value(const std::string& key, const ParamTable& text_params) const {
  for (const auto& [k, v] : settings)
    if (k == key) return v;
  const Param* p = text_params.Find(key);
  return p == nullptr ? "" : p->Text();
}

HistoryRow RunHistory::RowOf(const Session& session, const std::string& status) {
  const Experiment& exp = session.exp();
  HistoryRow row;
  row.when = LocalTime();
  row.t_end = exp.time();
  row.steps = exp.steps();
  row.status = status;
  row.seed = exp.setup().seed;
  row.source = std::make_shared<ScenarioSource>(session.source());
  row.log = session.run_log();
  const ParsedScenario text = ParseScenario(session.source(), {});
  for (const Param& p : session.params().all()) {
    const Param* in_text = text.params.Find(p.key);
    if (in_text == nullptr || in_text->Text() != p.Text())
      row.settings.emplace_back(p.key, p.Text());
  }
  row.metrics = exp.Results().Headlines();
  return row;
}

void RunHistory::Add(HistoryRow row) {
  row.number = rows_.empty() ? 1 : rows_.back().number + 1;
  rows_.push_back(std::move(row));
}

const HistoryRow* RunHistory::Find(int number) const {
  for (const HistoryRow& r : rows_)
    if (r.number == number) return &r;
  return nullptr;
}

std::string RunHistory::ToYaml() const {
  SourceList sources;
  for (const HistoryRow& r : rows_) AddSource(sources, r.source);
  auto emit = [&](bool quoted) {
    YAML::Emitter y;
    y << YAML::Comment(
             "formsim run history: one row per run that ended or was reset (the GUI's History "
             "tab); each row replays exactly from its scenario text and run log")
      << YAML::Newline;
    y << YAML::BeginMap << YAML::Key << "formsim_history" << YAML::Value << 1;
    EmitSources(y, "scenarios", sources, quoted);
    y << YAML::Key << "rows" << YAML::Value << YAML::BeginSeq;
    for (const HistoryRow& r : rows_) {
      y << YAML::BeginMap;
      y << YAML::Key << "number" << YAML::Value << r.number;
      y << YAML::Key << "when" << YAML::Value << r.when;
      y << YAML::Key << "t" << YAML::Value << FormatDouble(r.t_end);
      y << YAML::Key << "steps" << YAML::Value << r.steps;
      y << YAML::Key << "status" << YAML::Value << r.status;
      y << YAML::Key << "seed" << YAML::Value << std::to_string(r.seed);
      y << YAML::Key << "scenario" << YAML::Value << r.source->sha256();
      EmitRunLog(y, r.log);
      y << YAML::Key << "settings" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (const auto& [k, v] : r.settings)
        y << YAML::BeginMap << YAML::Key << "key" << YAML::Value << k << YAML::Key << "value"
          << YAML::Value << v << YAML::EndMap;
      y << YAML::EndSeq;
      y << YAML::Key << "metrics" << YAML::Value << YAML::BeginSeq;
      for (const Metrics::HeadlineValue& m : r.metrics)
        y << YAML::Flow << YAML::BeginMap << YAML::Key << "label" << YAML::Value << m.label
          << YAML::Key << "value" << YAML::Value << FormatDouble(m.value) << YAML::Key << "better"
          << YAML::Value << BetterName(m.better) << YAML::Key << "format" << YAML::Value << m.format
          << YAML::EndMap;
      y << YAML::EndSeq << YAML::EndMap;
    }
    y << YAML::EndSeq << YAML::EndMap;
    if (!y.good()) throw std::runtime_error(std::string("history: ") + y.GetLastError());
    return std::string(y.c_str()) + "\n";
  };
  const std::string text = emit(false);
  try {
    SourceList back;
    for (const HistoryRow& r : Parse(text, "(check)").rows_) AddSource(back, r.source);
    if (SameTexts(sources, back)) return text;
  } catch (const std::exception&) {
  }
  return emit(true);
}

void RunHistory::Save(const std::string& path) const {
  WriteFileAtomic(path, ToYaml());
}

RunHistory RunHistory::Load(const std::string& path) {
  return Parse(ReadRecordFile(path, "history"), path);
}

RunHistory RunHistory::Parse(const std::string& text, const std::string& file) {
  const RecordReader r{file};
  const YAML::Node root = LoadRecordText(text, file);
  if (r.Text(root, "formsim_history") != "1")
    r.Fail(root["formsim_history"], "formsim_history", "unknown format (expected 1)");
  const auto sources = ParseSources(r, r.List(root, "scenarios"));
  RunHistory h;
  for (const YAML::Node& n : r.List(root, "rows")) {
    if (!n.IsMap()) r.Fail(n, "rows", "each row must be a map");
    HistoryRow row;
    long long number = 0;
    if (!ParseInteger(r.Text(n, "number"), 1, 1 << 30, &number))
      r.Fail(n["number"], "number", "must be a whole number >= 1");
    row.number = static_cast<int>(number);
    if (!h.rows_.empty() && row.number <= h.rows_.back().number)
      r.Fail(n["number"], "number", "rows must be numbered in increasing order");
    row.when = r.Text(n, "when");
    row.t_end = r.Real(n, "t");
    row.steps = r.Step(n, "steps");
    row.status = r.Text(n, "status");
    if (!ParseUint64(r.Text(n, "seed"), &row.seed))
      r.Fail(n["seed"], "seed", "must be a whole number in [0, 18446744073709551615]");
    const std::string sha = r.Text(n, "scenario");
    const auto it = sources.find(sha);
    if (it == sources.end()) r.Fail(n["scenario"], "scenario", "no text with SHA-256 " + sha);
    row.source = it->second;
    row.log = ParseRunLog(r, n);
    for (const YAML::Node& s : r.List(n, "settings", false))
      row.settings.emplace_back(r.Text(s, "key"), r.Text(s, "value"));
    for (const YAML::Node& m : r.List(n, "metrics", false)) {
      Metrics::HeadlineValue v;
      v.label = r.Text(m, "label");
      v.format = r.Text(m, "format", false);
      const std::string value = r.Text(m, "value");
      if (value == "nan" || value == "-nan") {
        v.value = std::numeric_limits<double>::quiet_NaN();
      } else if (!ParseFiniteDouble(value, &v.value)) {
        r.Fail(m["value"], "value", "must be a number or nan");
      }
      const std::string better = r.Text(m, "better", false);
      v.better = better == "lower"    ? Better::kLower
                 : better == "higher" ? Better::kHigher
                                      : Better::kNone;
      row.metrics.push_back(v);
    }
    h.rows_.push_back(std::move(row));
  }
  return h;
}

std::string RunHistory::PathFor(const std::string& scenario_file) {
  const fs::path p(scenario_file);
  return (p.parent_path() / (p.stem().string() + ".history.yaml")).string();
}

std::string ShortKey(const std::string& key, const ParamTable& params) {
  std::size_t start = key.size();
  while (true) {
    const std::size_t dot = start == 0 ? std::string::npos : key.rfind('.', start - 1);
    const std::string tail = dot == std::string::npos ? key : key.substr(dot + 1);
    bool shared = false;
    for (const Param& p : params.all())
      shared = shared || (p.key != key && EndsWithTail(p.key, tail));
    if (!shared || dot == std::string::npos) return tail;
    start = dot;
  }
}

std::vector<SettingChange> DifferencesOf(
    const std::vector<std::pair<std::string, std::string>>& from,
    const std::vector<std::pair<std::string, std::string>>& to, const ParamTable& params) {
  std::map<std::string, const std::string*> other;
  for (const auto& [key, b] : to) other[key] = &b;
  std::vector<SettingChange> out;
  for (const auto& [key, a] : from) {
    const auto it = other.find(key);
    if (it == other.end() || *it->second == a) continue;
    out.push_back({key, params.Find(key) ? ShortKey(key, params) : key, a, *it->second});
  }
  return out;
}

std::string DescribeDifferences(const std::vector<std::pair<std::string, std::string>>& from,
                                const std::vector<std::pair<std::string, std::string>>& to,
                                const ParamTable& params) {
  std::string out;
  for (const SettingChange& c : DifferencesOf(from, to, params))
    out += (out.empty() ? "" : ", ") + c.name + " " + c.from + " -> " + c.to;
  return out;
}

}  // namespace formsim::sim
