#include "sim/session/record_yaml.hpp"

#include <sstream>
#include <stdexcept>

#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

void RecordReader::Fail(const YAML::Node& at, const std::string& key,
                        const std::string& why) const {
  throw std::runtime_error(file + ":" + std::to_string(at.Mark().line + 1) + ": key '" + key +
                           "': " + why);
}

std::string RecordReader::Text(const YAML::Node& map, const std::string& key, bool required) const {
  const YAML::Node n = map[key];
  if (!n) {
    if (required) Fail(map, key, "missing");
    return "";
  }
  if (!n.IsScalar()) Fail(n, key, "must be a scalar");
  return n.Scalar();
}

long RecordReader::Step(const YAML::Node& map, const std::string& key) const {
  long long v = 0;
  if (!ParseInteger(Text(map, key), 0, 1LL << 60, &v)) Fail(map[key], key, "must be a step >= 0");
  return static_cast<long>(v);
}

double RecordReader::Real(const YAML::Node& map, const std::string& key) const {
  double v = 0;
  if (!ParseFiniteDouble(Text(map, key), &v)) Fail(map[key], key, "must be a finite number");
  return v;
}

YAML::Node RecordReader::List(const YAML::Node& map, const std::string& key, bool required) const {
  const YAML::Node n = map[key];
  if (!n) {
    if (required) Fail(map, key, "missing");
    return YAML::Node(YAML::NodeType::Sequence);
  }
  if (n.IsNull()) return YAML::Node(YAML::NodeType::Sequence);  // an empty list written as `key:`
  if (!n.IsSequence()) Fail(n, key, "must be a list");
  return n;
}

std::string ReadRecordFile(const std::string& file, const std::string& what) {
  try {
    return ReadBoundedFile(file);
  } catch (const FileReadError& e) {
    throw std::runtime_error(file + ": the " + what + " " + e.reason());
  }
}

YAML::Node LoadRecordText(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = LoadYamlText(text, file);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what());
  }
  if (!root.IsMap()) throw std::runtime_error(file + ": expected a YAML map of keys");
  return root;
}

void AddSource(SourceList& list, const std::shared_ptr<const ScenarioSource>& source) {
  if (!source) return;
  for (const auto& s : list)
    if (s->sha256() == source->sha256()) return;
  list.push_back(source);
}

void EmitSources(YAML::Emitter& y, const std::string& key, const SourceList& sources, bool quoted) {
  y << YAML::Key << key << YAML::Value << YAML::BeginSeq;
  for (const auto& s : sources)
    y << YAML::BeginMap << YAML::Key << "sha256" << YAML::Value << s->sha256() << YAML::Key
      << "file" << YAML::Value << s->file() << YAML::Key << "dir" << YAML::Value << s->dir()
      << YAML::Key << "text" << YAML::Value << (quoted ? YAML::DoubleQuoted : YAML::Literal)
      << s->text() << YAML::EndMap;
  y << YAML::EndSeq;
}

std::map<std::string, std::shared_ptr<const ScenarioSource>> ParseSources(const RecordReader& r,
                                                                          const YAML::Node& list) {
  std::map<std::string, std::shared_ptr<const ScenarioSource>> out;
  for (const YAML::Node& s : list) {
    if (!s.IsMap()) r.Fail(s, "text", "each scenario must be a map");
    auto src = std::make_shared<ScenarioSource>(
        ScenarioSource::FromText(r.Text(s, "text"), r.Text(s, "file"), r.Text(s, "dir", false)));
    if (src->sha256() != r.Text(s, "sha256"))
      r.Fail(s["text"], "text", "its SHA-256 is not the recorded one (the text was changed)");
    out[src->sha256()] = src;
  }
  return out;
}

bool SameTexts(const SourceList& a, const SourceList& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i]->text() != b[i]->text()) return false;
  return true;
}

void EmitOverrides(YAML::Emitter& y, const std::string& key, const std::vector<Override>& list) {
  y << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const Override& o : list)
    y << YAML::BeginMap << YAML::Key << "key" << YAML::Value << o.key << YAML::Key << "value"
      << YAML::Value << o.value << YAML::Key << "origin" << YAML::Value << o.origin << YAML::EndMap;
  y << YAML::EndSeq;
}

std::vector<Override> ParseOverrides(const RecordReader& r, const YAML::Node& map,
                                     const std::string& key) {
  std::vector<Override> out;
  for (const YAML::Node& o : r.List(map, key, false)) {
    if (!o.IsMap()) r.Fail(o, key, "each override must be a map {key, value, origin}");
    out.push_back({r.Text(o, "key"), r.Text(o, "value"), r.Text(o, "origin"), -1});
  }
  return out;
}

void EmitRunLog(YAML::Emitter& y, const RunLog& log) {
  EmitOverrides(y, "base", log.base);
  y << YAML::Key << "changes" << YAML::Value << YAML::BeginSeq;
  for (const RunChange& c : log.changes) {
    y << YAML::Flow << YAML::BeginMap << YAML::Key << "step" << YAML::Value << c.step;
    switch (c.kind) {
      case RunChange::Kind::kEdits:
        EmitOverrides(y, "edits", c.edits);
        break;
      case RunChange::Kind::kMove:
        y << YAML::Key << "move" << YAML::Value << c.name << YAML::Key << "x" << YAML::Value
          << FormatDouble(c.x) << YAML::Key << "y" << YAML::Value << FormatDouble(c.y);
        break;
      case RunChange::Kind::kAction:
        y << YAML::Key << "action" << YAML::Value << c.name << YAML::Key << "origin" << YAML::Value
          << c.origin;
        break;
    }
    y << YAML::EndMap;
  }
  y << YAML::EndSeq;
}

RunLog ParseRunLog(const RecordReader& r, const YAML::Node& map) {
  RunLog log;
  log.base = ParseOverrides(r, map, "base");
  for (const YAML::Node& n : r.List(map, "changes", false)) {
    if (!n.IsMap()) r.Fail(n, "changes", "each change must be a map");
    RunChange c;
    c.step = r.Step(n, "step");
    if (n["edits"]) {
      c.kind = RunChange::Kind::kEdits;
      c.edits = ParseOverrides(r, n, "edits");
      for (Override& o : c.edits) o.step = c.step;
    } else if (n["move"]) {
      c.kind = RunChange::Kind::kMove;
      c.name = r.Text(n, "move");
      c.x = r.Real(n, "x");
      c.y = r.Real(n, "y");
    } else if (n["action"]) {
      c.kind = RunChange::Kind::kAction;
      c.name = r.Text(n, "action");
      c.origin = r.Text(n, "origin");
    } else {
      r.Fail(n, "changes", "a change holds edits, a move or an action");
    }
    if (!log.changes.empty() && c.step < log.changes.back().step)
      r.Fail(n, "step", "changes must be in the order of their steps");
    log.changes.push_back(std::move(c));
  }
  return log;
}

}  // namespace formsim::sim
