#include "sim/core/yaml_reader.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace formsim::sim {
namespace {

std::string Location(const std::string& file, int line, int col) {
  std::ostringstream os;
  os << file;
  if (line > 0) os << ":" << line << ":" << col;
  return os.str();
}

// The mark of `key` inside map `node` (the key itself, so the line points at the typo), or the
// mark of the map when the key is absent.
YAML::Mark KeyMark(const YAML::Node& node, const std::string& key) {
  if (node.IsMap())
    for (auto it = node.begin(); it != node.end(); ++it)
      if (it->first.IsScalar() && it->first.Scalar() == key) return it->first.Mark();
  return node.Mark();
}

}  // namespace

ScenarioError::ScenarioError(const std::string& file, int line, int column, const std::string& key,
                             const std::string& message)
    : std::runtime_error(Location(file, line, column) + ": " +
                         (key.empty() ? "" : "key '" + key + "': ") + message),
      file_(file),
      key_(key),
      line_(line) {}

YamlReader::YamlReader(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap()) {
    const YAML::Mark m = node_.Mark();
    throw ScenarioError(file_, m.line + 1, m.column + 1, path_, "expected a map of keys");
  }
}

void YamlReader::Fail(const std::string& key, const std::string& message) const {
  const YAML::Mark m = KeyMark(node_, key);
  const int line = m.line >= 0 ? m.line + 1 : 0;
  throw ScenarioError(file_, line, m.column + 1, KeyPath(key), message);
}

bool YamlReader::Has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node YamlReader::Get(const std::string& key) {
  read_.insert(key);
  if (!node_.IsMap()) return YAML::Node();
  const YAML::Node& cnode = node_;
  YAML::Node n = cnode[key];
  return n;
}

static double ToDouble(const YamlReader& r, const std::string& key, const YAML::Node& n) {
  if (!n.IsScalar()) r.Fail(key, "expected a number");
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    r.Fail(key, "expected a number, got '" + n.Scalar() + "'");
  }
  if (!std::isfinite(v)) r.Fail(key, "must be a finite number, got '" + n.Scalar() + "'");
  return v;
}

double YamlReader::Double(const std::string& key, double def) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  return ToDouble(*this, key, n);
}

double YamlReader::RequiredDouble(const std::string& key) {
  if (!Has(key)) Fail(key, "required number is missing");
  return Double(key, 0.0);
}

int YamlReader::Int(const std::string& key, int def) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  if (!n.IsScalar()) Fail(key, "expected an integer");
  try {
    return n.as<int>();
  } catch (const YAML::Exception&) {
    Fail(key, "expected an integer, got '" + n.Scalar() + "'");
  }
}

bool YamlReader::Bool(const std::string& key, bool def) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  if (!n.IsScalar()) Fail(key, "expected true or false");
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    Fail(key, "expected true or false, got '" + n.Scalar() + "'");
  }
}

std::string YamlReader::String(const std::string& key, const std::string& def) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  if (!n.IsScalar()) Fail(key, "expected a string");
  return n.Scalar();
}

std::string YamlReader::RequiredString(const std::string& key) {
  if (!Has(key)) Fail(key, "required string is missing");
  return String(key, "");
}

int YamlReader::Choice(const std::string& key, const std::vector<std::string>& choices, int def) {
  if (!Has(key)) {
    read_.insert(key);
    return def;
  }
  const std::string s = String(key, "");
  for (std::size_t i = 0; i < choices.size(); ++i)
    if (choices[i] == s) return static_cast<int>(i);
  std::string allowed;
  for (const auto& c : choices) allowed += (allowed.empty() ? "" : ", ") + c;
  Fail(key, "'" + s + "' is not one of: " + allowed);
}

std::vector<double> YamlReader::Doubles(const std::string& key, const std::vector<double>& def,
                                        int length) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  if (!n.IsSequence()) Fail(key, "expected a list of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) out.push_back(ToDouble(*this, key, n[i]));
  if (length >= 0 && static_cast<int>(out.size()) != length)
    Fail(key, "expected " + std::to_string(length) + " numbers, got " + std::to_string(out.size()));
  return out;
}

std::vector<std::string> YamlReader::Strings(const std::string& key,
                                             const std::vector<std::string>& def) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  if (n.IsScalar()) return {n.Scalar()};
  if (!n.IsSequence()) Fail(key, "expected a list of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsScalar()) Fail(key, "expected a list of strings");
    out.push_back(n[i].Scalar());
  }
  return out;
}

std::vector<Vec2> YamlReader::Points(const std::string& key, int min_count) {
  YAML::Node n = Get(key);
  std::vector<Vec2> out;
  if (n.IsDefined() && !n.IsNull()) {
    if (!n.IsSequence()) Fail(key, "expected a list of [x, y] points");
    for (std::size_t i = 0; i < n.size(); ++i) {
      if (!n[i].IsSequence() || n[i].size() != 2) Fail(key, "each point must be [x, y]");
      out.push_back({ToDouble(*this, key, n[i][0]), ToDouble(*this, key, n[i][1])});
    }
  }
  if (static_cast<int>(out.size()) < min_count)
    Fail(key, "needs at least " + std::to_string(min_count) + " points");
  return out;
}

Pose2 YamlReader::Pose(const std::string& key, const Pose2& def) {
  if (!Has(key)) {
    read_.insert(key);
    return def;
  }
  const std::vector<double> v = Doubles(key, {}, 3);
  return {v[0], v[1], v[2]};
}

YamlReader YamlReader::Map(const std::string& key) {
  YAML::Node n = Get(key);
  if (n.IsDefined() && !n.IsNull() && !n.IsMap()) Fail(key, "expected a map");
  return YamlReader(n.IsDefined() ? n : YAML::Node(YAML::NodeType::Map), file_, KeyPath(key));
}

std::vector<YamlReader> YamlReader::MapList(const std::string& key) {
  YAML::Node n = Get(key);
  std::vector<YamlReader> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) Fail(key, "expected a list");
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string item = KeyPath(key) + "[" + std::to_string(i) + "]";
    if (!n[i].IsMap()) {
      const YAML::Mark m = n[i].Mark();
      throw ScenarioError(file_, m.line + 1, m.column + 1, item, "expected a map");
    }
    out.emplace_back(n[i], file_, item);
  }
  return out;
}

YAML::Node YamlReader::Raw(const std::string& key) { return Get(key); }

void YamlReader::Finish() const {
  if (!node_.IsMap()) return;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (read_.count(key)) continue;
    std::string allowed;
    for (const auto& k : read_) allowed += (allowed.empty() ? "" : ", ") + k;
    Fail(key, "unknown key" + (allowed.empty() ? std::string() : " (allowed here: " + allowed + ")"));
  }
}

YAML::Node LoadYamlFile(const std::string& file) {
  try {
    return YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw ScenarioError(file, 0, 0, "", "cannot open file");
  } catch (const YAML::ParserException& e) {
    throw ScenarioError(file, e.mark.line + 1, e.mark.column + 1, "", "YAML syntax error: " + e.msg);
  }
}

namespace {

// Splits "a.b.c" into segments.
std::vector<std::string> SplitPath(const std::string& path) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : path) {
    if (c == '.') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

bool IsIndex(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

// Finds the child `seg` of `cur` (map key, sequence index or sequence item with name: seg).
// Creates missing map entries when `create`. Returns an error message or "".
std::string Child(YAML::Node& cur, const std::string& seg, bool create, YAML::Node& out) {
  if (cur.IsSequence()) {
    if (IsIndex(seg)) {
      const std::size_t i = std::stoul(seg);
      if (i >= cur.size()) return "index " + seg + " out of range (list has " + std::to_string(cur.size()) + " items)";
      out.reset(cur[i]);
      return "";
    }
    for (std::size_t i = 0; i < cur.size(); ++i) {
      if (cur[i].IsMap() && cur[i]["name"] && cur[i]["name"].Scalar() == seg) {
        out.reset(cur[i]);
        return "";
      }
    }
    return "no list item named '" + seg + "'";
  }
  if (!cur.IsMap() && !cur.IsNull()) return "'" + seg + "' is inside a value that is not a map";
  if (!cur[seg] && !create) return "no key '" + seg + "'";
  if (!cur[seg]) cur[seg] = YAML::Node(YAML::NodeType::Map);
  out.reset(cur[seg]);
  return "";
}

}  // namespace

std::string SetAtPath(YAML::Node& root, const std::string& path, const YAML::Node& value) {
  const std::vector<std::string> segs = SplitPath(path);
  for (const auto& s : segs)
    if (s.empty()) return "malformed key path '" + path + "'";
  YAML::Node cur;
  cur.reset(root);
  for (std::size_t i = 0; i + 1 < segs.size(); ++i) {
    YAML::Node next;
    const std::string err = Child(cur, segs[i], true, next);
    if (!err.empty()) return "'" + path + "': " + err;
    cur.reset(next);
  }
  const std::string& last = segs.back();
  if (cur.IsSequence()) {
    if (!IsIndex(last)) return "'" + path + "': '" + last + "' must be an index into a list";
    const std::size_t i = std::stoul(last);
    if (i >= cur.size()) return "'" + path + "': index out of range";
    cur[i] = value;
    return "";
  }
  if (!cur.IsMap() && !cur.IsNull()) return "'" + path + "': parent is not a map";
  cur[last] = value;
  return "";
}

std::string ApplySet(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    return "--set expects path.to.key=value, got '" + assignment + "'";
  const std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    return "--set " + path + ": cannot parse value '" + text + "': " + e.msg;
  }
  return SetAtPath(root, path, value);
}

}  // namespace formsim::sim
