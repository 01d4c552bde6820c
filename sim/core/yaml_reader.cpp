#include "sim/core/yaml_reader.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/yaml_limits.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {
namespace {

// The world's extent and largest pose angle (sim/core/world.hpp world_limits, repeated here
// so the reader stays free of Box2D).
constexpr double kWorldExtent = 1e4;
constexpr double kMaxPoseAngle = 1e3;

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

// Bytes a terminal would interpret (control characters, DEL) shown as \xNN.
std::string Printable(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c < 0x20 || c == 0x7f) {
      AppendSprintf(out, "\\x%02x", c);
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

}  // namespace

ScenarioError::ScenarioError(const std::string& file, int line, int column, const std::string& key,
                             const std::string& message)
    : ScenarioError(Location(file, line, column), key, message) {
  line_ = line;
}

ScenarioError::ScenarioError(const std::string& location, const std::string& key,
                             const std::string& message)
    : std::runtime_error(location + ": " + (key.empty() ? "" : "key '" + key + "': ") + message),
      location_(location),
      key_(key),
      reason_(message) {}

YamlReader::YamlReader(YAML::Node node, std::shared_ptr<ReadContext> ctx, std::string path)
    : node_(std::move(node)), ctx_(std::move(ctx)), path_(std::move(path)) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap()) {
    const YAML::Mark m = node_.Mark();
    throw ScenarioError(ctx_->file, m.line + 1, m.column + 1, path_, "expected a map of keys");
  }
}

YamlReader::YamlReader(YAML::Node node, std::string file, std::string path)
    : YamlReader(std::move(node),
                 [&] {
                   auto c = std::make_shared<ReadContext>();
                   c->file = file;
                   c->dir = fs::path(file).parent_path().string();
                   return c;
                 }(),
                 std::move(path)) {}

void YamlReader::Fail(const std::string& key, const std::string& message) const {
  const std::string kp = KeyPath(key);
  // A value put there by --set or a GUI edit: name the override, not a file position.
  const std::map<std::string, std::string>& origins = ctx_->origins;
  for (auto it = origins.rbegin(); it != origins.rend(); ++it) {
    const std::string& o = it->first;
    if (kp == o || (kp.size() > o.size() && kp.compare(0, o.size(), o) == 0 && kp[o.size()] == '.'))
      throw ScenarioError(it->second, kp, message);
  }
  YAML::Mark m = KeyMark(node_, key);
  if (m.line < 0) m = node_.Mark();
  const int line = m.line >= 0 ? m.line + 1 : 0;
  throw ScenarioError(ctx_->file, line, m.column + 1, kp, message);
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
  if (ParseFiniteDouble(n.Scalar(), &v)) return v;
  // YAML spellings of non-finite values (.inf, .nan) and out-of-range literals (1e999).
  double parsed = 0;
  bool is_number = false;
  try {
    parsed = n.as<double>();
    is_number = true;
  } catch (const YAML::Exception&) {
  }
  if (is_number && !std::isfinite(parsed))
    r.Fail(key, "must be a finite number, got '" + Printable(n.Scalar()) + "'");
  r.Fail(key, "expected a number, got '" + Printable(n.Scalar()) + "'");
}

double YamlReader::Double(const std::string& key, double def) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  return ToDouble(*this, key, n);
}

double YamlReader::Double(const std::string& key, double def, const Tune& valid) {
  const double v = Double(key, def);
  if (const std::string err = valid.Check(v); !err.empty()) Fail(key, err);
  return v;
}

int YamlReader::Int(const std::string& key, int def, const Tune& valid) {
  const int v = Int(key, def);
  if (const std::string err = valid.Check(v); !err.empty()) Fail(key, err);
  return v;
}

std::vector<double> YamlReader::Doubles(const std::string& key, const std::vector<double>& def,
                                        const Tune& valid) {
  const std::vector<double> v = Doubles(key, def, static_cast<int>(def.size()));
  for (std::size_t i = 0; i < v.size(); ++i)
    if (const std::string err = valid.Check(v[i]); !err.empty())
      Fail(key, "item " + std::to_string(i) + " " + err);
  return v;
}

double YamlReader::RequiredDouble(const std::string& key) {
  if (!Has(key)) Fail(key, "required number is missing");
  return Double(key, 0.0);
}

int YamlReader::Int(const std::string& key, int def) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  if (!n.IsScalar()) Fail(key, "expected an integer");
  long long v = 0;
  if (!ParseInteger(n.Scalar(), -2147483647LL, 2147483647LL, &v))
    Fail(key, "expected an integer (|n| < 2^31), got '" + Printable(n.Scalar()) + "'");
  return static_cast<int>(v);
}

bool YamlReader::Bool(const std::string& key, bool def) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return def;
  if (!n.IsScalar()) Fail(key, "expected true or false");
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    Fail(key, "expected true or false, got '" + Printable(n.Scalar()) + "'");
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
  Fail(key, "'" + Printable(s) + "' is not one of: " + allowed);
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
      if (std::abs(out.back().x) > kWorldExtent || std::abs(out.back().y) > kWorldExtent)
        Fail(key, "point " + std::to_string(i) + " is outside the world (|x|, |y| <= 1e4 m)");
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
  if (std::abs(v[0]) > kWorldExtent || std::abs(v[1]) > kWorldExtent)
    Fail(key, "position outside the world (|x|, |y| <= 1e4 m)");
  if (std::abs(v[2]) > kMaxPoseAngle) Fail(key, "heading beyond ±1000 rad (angles are radians)");
  return {v[0], v[1], v[2]};
}

std::string YamlReader::FilePath(const std::string& key, const std::string& def) {
  const bool in_file = Has(key);
  const std::string text = String(key, def);
  if (text.empty()) Fail(key, "a file path must not be empty");
  PathField f;
  f.key = KeyPath(key);
  f.text = text;
  f.in_file = in_file;
  const fs::path p(text);
  f.resolved = p.is_absolute() || ctx_->dir.empty() ? text : (fs::path(ctx_->dir) / p).string();
  for (auto& q : ctx_->paths)
    if (q.key == f.key) {
      q = f;
      return f.resolved;
    }
  ctx_->paths.push_back(f);
  return f.resolved;
}

void YamlReader::Enter(Param p, const std::string& key) {
  p.key = KeyPath(key);
  p.in_file = Has(key);
  p.tune.CheckDeclaration(p.key);
  ctx_->params.Add(std::move(p));
}

double YamlReader::Real(const std::string& key, double def, const Tune& tune) {
  const double v = Double(key, def);
  const std::string err = tune.Check(v);
  if (!err.empty()) Fail(key, err);
  Param p;
  p.kind = Param::Kind::kDouble;
  p.tune = tune;
  p.value = v;
  Enter(std::move(p), key);
  return v;
}

int YamlReader::Integer(const std::string& key, int def, const Tune& tune) {
  const int v = Int(key, def);
  const std::string err = tune.Check(v);
  if (!err.empty()) Fail(key, err);
  Param p;
  p.kind = Param::Kind::kInt;
  p.tune = tune;
  p.value = v;
  Enter(std::move(p), key);
  return v;
}

bool YamlReader::Flag(const std::string& key, bool def, const Tune& tune) {
  const bool v = Bool(key, def);
  Param p;
  p.kind = Param::Kind::kBool;
  p.tune = tune;
  p.value = v ? 1.0 : 0.0;
  Enter(std::move(p), key);
  return v;
}

int YamlReader::Pick(const std::string& key, const std::vector<std::string>& choices, int def,
                     const Tune& tune) {
  const int v = Choice(key, choices, def);
  Param p;
  p.kind = Param::Kind::kChoice;
  p.tune = tune;
  p.choices = choices;
  p.value = v;
  Enter(std::move(p), key);
  return v;
}

std::vector<double> YamlReader::Reals(const std::string& key, const std::vector<double>& def,
                                      const Tune& tune, const std::vector<std::string>& item_labels) {
  const std::vector<double> v = Doubles(key, def, tune);
  for (std::size_t i = 0; i < v.size(); ++i) {
    Param p;
    p.kind = Param::Kind::kDouble;
    p.tune = tune;
    if (i < item_labels.size()) p.tune.label = item_labels[i];
    else if (!p.tune.label.empty()) p.tune.label += " " + std::to_string(i);
    p.value = v[i];
    p.key = KeyPath(key) + "." + std::to_string(i);
    p.in_file = Has(key);
    p.tune.CheckDeclaration(p.key);
    ctx_->params.Add(std::move(p));
  }
  return v;
}

YamlReader YamlReader::Map(const std::string& key) {
  YAML::Node n = Get(key);
  if (n.IsDefined() && !n.IsNull() && !n.IsMap()) Fail(key, "expected a map");
  return YamlReader(n.IsDefined() && !n.IsNull() ? n : YAML::Node(YAML::NodeType::Map), ctx_,
                    KeyPath(key));
}

std::vector<YamlReader> YamlReader::MapList(const std::string& key) {
  YAML::Node n = Get(key);
  std::vector<YamlReader> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) Fail(key, "expected a list");
  for (std::size_t i = 0; i < n.size(); ++i) {
    const YAML::Node item = n[i];
    std::string id = std::to_string(i);
    if (item.IsMap() && item["name"] && item["name"].IsScalar() && !item["name"].Scalar().empty() &&
        item["name"].Scalar().find('.') == std::string::npos)
      id = item["name"].Scalar();
    const std::string item_path = KeyPath(key) + "." + id;
    if (!item.IsMap()) {
      const YAML::Mark m = item.Mark();
      throw ScenarioError(ctx_->file, m.line + 1, m.column + 1, item_path, "expected a map");
    }
    out.emplace_back(item, ctx_, item_path);
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

namespace {

// yaml-cpp keeps the first of two equal keys and drops the second without a word.
void CheckDuplicateKeys(const YAML::Node& n, const std::string& file, const std::string& path,
                        int depth) {
  if (depth > 64) return;  // LoadYamlText refuses deeper documents before we get here
  if (n.IsMap()) {
    std::set<std::string> seen;
    for (auto it = n.begin(); it != n.end(); ++it) {
      const std::string k = it->first.IsScalar() ? it->first.Scalar() : "";
      const std::string kp = path.empty() ? k : path + "." + k;
      if (it->first.IsScalar() && !seen.insert(k).second) {
        const YAML::Mark m = it->first.Mark();
        throw ScenarioError(file, m.line + 1, m.column + 1, kp,
                            "duplicate key (it already appears earlier in this map)");
      }
      CheckDuplicateKeys(it->second, file, kp, depth + 1);
    }
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      CheckDuplicateKeys(n[i], file, path + "." + std::to_string(i), depth + 1);
  }
}

// Nesting depth of flow/block collections, counted on the text so that a hostile document
// never reaches the recursive parser.
int NestingDepth(const std::string& text) {
  int depth = 0, max_depth = 0;
  bool in_single = false, in_double = false, comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      comment = false;
      continue;
    }
    if (comment) continue;
    if (in_double) {
      if (c == '\\') ++i;
      else if (c == '"') in_double = false;
      continue;
    }
    if (in_single) {
      if (c == '\'') in_single = false;
      continue;
    }
    if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t')) comment = true;
    else if (c == '"') in_double = true;
    else if (c == '\'' && (i == 0 || std::string(" [{,:").find(text[i - 1]) != std::string::npos)) in_single = true;
    else if (c == '[' || c == '{') max_depth = std::max(max_depth, ++depth);
    else if ((c == ']' || c == '}') && depth > 0) --depth;
  }
  // Block nesting: indentation levels of 1 space each would need as many columns.
  std::size_t line_start = 0;
  while (line_start < text.size()) {
    std::size_t k = line_start;
    while (k < text.size() && (text[k] == ' ' || text[k] == '-')) ++k;
    max_depth = std::max(max_depth, static_cast<int>((k - line_start) / 2));
    const std::size_t nl = text.find('\n', line_start);
    if (nl == std::string::npos) break;
    line_start = nl + 1;
  }
  return max_depth;
}

}  // namespace

YAML::Node LoadYamlText(const std::string& text, const std::string& file) {
  constexpr int kMaxDepth = 64;
  if (NestingDepth(text) > kMaxDepth)
    throw ScenarioError(file, 0, 0, "",
                        "nested deeper than " + std::to_string(kMaxDepth) +
                            " levels (a scenario needs a handful)");
  YAML::Node root;
  try {
    // Aliases expand: the event stream is counted first, so a "billion laughs" document is
    // refused at its alias before any walk over the tree could take hours.
    CheckYamlLimits(text, file);
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ScenarioError(file, e.mark.line + 1, e.mark.column + 1, "",
                        "YAML syntax error: " + Printable(e.msg));
  } catch (const YAML::Exception& e) {
    throw ScenarioError(file, 0, 0, "", "YAML error: " + Printable(e.msg));
  }
  CheckDuplicateKeys(root, file, "", 0);
  return root;
}

YAML::Node LoadYamlFile(const std::string& file) {
  std::string text;
  try {
    text = ReadBoundedFile(file);
  } catch (const FileReadError& e) {
    throw ScenarioError(file, 0, 0, "", e.reason());
  }
  return LoadYamlText(text, file);
}

std::vector<std::string> SplitKeyPath(const std::string& path) {
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

namespace {

bool IsIndex(const std::string& s) {
  return !s.empty() && s.size() < 10 && s.find_first_not_of("0123456789") == std::string::npos;
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
      if (cur[i].IsMap() && cur[i]["name"] && cur[i]["name"].IsScalar() &&
          cur[i]["name"].Scalar() == seg) {
        out.reset(cur[i]);
        return "";
      }
    }
    return "no list item named '" + Printable(seg) + "'";
  }
  if (!cur.IsMap() && !cur.IsNull()) return "'" + Printable(seg) + "' is inside a value that is not a map";
  if (cur.IsMap() && !cur[seg] && !create) return "no key '" + Printable(seg) + "'";
  if (cur.IsNull() && !create) return "no key '" + Printable(seg) + "'";
  if (!cur[seg]) cur[seg] = YAML::Node(YAML::NodeType::Map);
  out.reset(cur[seg]);
  return "";
}

}  // namespace

YAML::Node FindAtPath(const YAML::Node& root, const std::string& path) {
  YAML::Node cur;
  cur.reset(root);
  for (const std::string& seg : SplitKeyPath(path)) {
    if (seg.empty()) return YAML::Node(YAML::NodeType::Undefined);
    YAML::Node next;
    if (!cur.IsMap() && !cur.IsSequence()) return YAML::Node(YAML::NodeType::Undefined);
    if (!Child(cur, seg, false, next).empty()) return YAML::Node(YAML::NodeType::Undefined);
    cur.reset(next);
  }
  return cur;
}

std::string SetAtPath(YAML::Node& root, const std::string& path, const YAML::Node& value) {
  const std::vector<std::string> segs = SplitKeyPath(path);
  for (const auto& s : segs)
    if (s.empty()) return "malformed key path '" + Printable(path) + "'";
  YAML::Node cur;
  cur.reset(root);
  for (std::size_t i = 0; i + 1 < segs.size(); ++i) {
    YAML::Node next;
    const std::string err = Child(cur, segs[i], true, next);
    if (!err.empty()) return "'" + Printable(path) + "': " + err;
    cur.reset(next);
  }
  const std::string& last = segs.back();
  if (cur.IsSequence()) {
    if (!IsIndex(last)) return "'" + Printable(path) + "': '" + Printable(last) + "' must be an index into a list";
    const std::size_t i = std::stoul(last);
    if (i >= cur.size()) return "'" + Printable(path) + "': index out of range";
    cur[i] = value;
    return "";
  }
  if (!cur.IsMap() && !cur.IsNull()) return "'" + Printable(path) + "': parent is not a map";
  cur[last] = value;
  return "";
}

std::string ApplySet(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    return "expected path.to.key=value, got '" + Printable(assignment) + "'";
  const std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (text.find_first_not_of(" \t") == std::string::npos)
    return Printable(path) + ": empty value (write the value after '=')";
  YAML::Node value;
  try {
    value = LoadYamlText(text, "value");
  } catch (const ScenarioError& e) {
    return Printable(path) + ": cannot parse value '" + Printable(text) + "': " + e.reason();
  }
  if (value.IsNull()) return Printable(path) + ": empty value '" + Printable(text) + "'";
  return SetAtPath(root, path, value);
}

YAML::Node NumberNode(double v) {
  return YAML::Node(FormatDouble(v + 0.0));
}

}  // namespace formsim::sim
