#include "sim/scenario/yaml_patch.hpp"

#include <yaml-cpp/yaml.h>

#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {
namespace {

// End of the bracketed collection that opens at text[pos] ('[' or '{'), just past the closer;
// npos when unbalanced. Quotes are skipped.
std::size_t MatchingClose(const std::string& text, std::size_t pos) {
  int depth = 0;
  for (std::size_t i = pos; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
    } else if (c == '\'') {
      for (++i; i < text.size(); ++i) {
        if (text[i] == '\'' && i + 1 < text.size() && text[i + 1] == '\'') ++i;
        else if (text[i] == '\'') break;
      }
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      if (--depth == 0) return i + 1;
    }
  }
  return std::string::npos;
}

// The characters [begin, end) of a scalar or flow-collection node in the text; false when the
// node's text cannot be delimited safely (block collections, multi-line scalars).
bool NodeSpan(const std::string& text, const YAML::Node& node, std::size_t* begin, std::size_t* end) {
  const YAML::Mark m = node.Mark();
  if (m.pos < 0 || static_cast<std::size_t>(m.pos) >= text.size()) return false;
  const std::size_t b = static_cast<std::size_t>(m.pos);
  const char c = text[b];
  if (node.IsScalar()) {
    if (c == '"' || c == '\'') {
      std::size_t i = b + 1;
      for (; i < text.size(); ++i) {
        if (c == '"' && text[i] == '\\') { ++i; continue; }
        if (text[i] == c && c == '\'' && i + 1 < text.size() && text[i + 1] == '\'') { ++i; continue; }
        if (text[i] == c) break;
        if (text[i] == '\n') return false;
      }
      if (i >= text.size()) return false;
      *begin = b;
      *end = i + 1;
      return true;
    }
    const std::string& s = node.Scalar();
    if (s.empty() || text.compare(b, s.size(), s) != 0) return false;  // folded or multi-line
    *begin = b;
    *end = b + s.size();
    return true;
  }
  if ((node.IsSequence() || node.IsMap()) && (c == '[' || c == '{')) {
    const std::size_t e = MatchingClose(text, b);
    if (e == std::string::npos) return false;
    *begin = b;
    *end = e;
    return true;
  }
  return false;
}

std::size_t LineStart(const std::string& text, std::size_t pos) {
  const std::size_t nl = pos == 0 ? std::string::npos : text.rfind('\n', pos - 1);
  return nl == std::string::npos ? 0 : nl + 1;
}

bool OnlySpacesBefore(const std::string& text, std::size_t pos) {
  for (std::size_t i = LineStart(text, pos); i < pos; ++i)
    if (text[i] != ' ') return false;
  return true;
}

// Inserts "key: value" into map `map` of the text.
bool InsertIntoMap(std::string& text, const YAML::Node& map, const std::string& key,
                   const std::string& value, std::string* why) {
  const YAML::Mark m = map.Mark();
  if (m.pos < 0) {
    *why = "no position for the map";
    return false;
  }
  const std::size_t pos = static_cast<std::size_t>(m.pos);
  if (pos < text.size() && text[pos] == '{') {
    const std::size_t close = MatchingClose(text, pos);
    if (close == std::string::npos) {
      *why = "unbalanced flow map";
      return false;
    }
    const std::string entry = (map.size() > 0 ? ", " : "") + key + ": " + value;
    text.insert(close - 1, entry);
    return true;
  }
  // Block map: a new line at the indentation of an entry whose key starts its line.
  for (auto it = map.begin(); it != map.end(); ++it) {
    const YAML::Mark km = it->first.Mark();
    if (km.pos < 0) continue;
    const std::size_t kpos = static_cast<std::size_t>(km.pos);
    if (!OnlySpacesBefore(text, kpos)) continue;
    const std::size_t ls = LineStart(text, kpos);
    text.insert(ls, std::string(kpos - ls, ' ') + key + ": " + value + "\n");
    return true;
  }
  // All keys follow a "- " (a one-key list item): put the new key on the line after the
  // first key's line, indented like that key, when that key's value ends on its line.
  auto it = map.begin();
  if (it != map.end() && it->first.Mark().pos >= 0) {
    std::size_t b = 0, e = 0;
    if (NodeSpan(text, it->second, &b, &e) && text.find('\n', static_cast<std::size_t>(it->first.Mark().pos)) >= e) {
      const std::size_t kpos = static_cast<std::size_t>(it->first.Mark().pos);
      const std::size_t col = kpos - LineStart(text, kpos);
      std::size_t eol = text.find('\n', e);
      if (eol == std::string::npos) {
        text += "\n";
        eol = text.size() - 1;
      }
      text.insert(eol + 1, std::string(col, ' ') + key + ": " + value + "\n");
      return true;
    }
  }
  *why = "no place to insert '" + key + "'";
  return false;
}

bool PatchOne(std::string& text, const std::string& path, const std::string& value, std::string* why) {
  YAML::Node root;
  try {
    root = LoadYamlText(text, "the text");  // aliases and nesting bounded like any scenario
  } catch (const std::exception& e) {
    *why = std::string("text does not parse: ") + e.what();
    return false;
  }
  const std::vector<std::string> segs = SplitKeyPath(path);
  YAML::Node node = FindAtPath(root, path);
  if (node.IsDefined() && !node.IsNull()) {
    std::size_t b = 0, e = 0;
    if (!NodeSpan(text, node, &b, &e)) {
      *why = "the value of '" + path + "' is not on one line";
      return false;
    }
    text.replace(b, e - b, value);
    return true;
  }
  // Deepest existing map on the path; the rest is written inline as nested flow maps.
  std::size_t have = segs.size() - 1;
  YAML::Node parent;
  while (true) {
    std::string prefix;
    for (std::size_t i = 0; i < have; ++i) prefix += (i ? "." : "") + segs[i];
    parent = have == 0 ? root : FindAtPath(root, prefix);
    if (parent.IsDefined() && !parent.IsNull()) break;
    if (have == 0) {
      *why = "empty document";
      return false;
    }
    --have;
  }
  if (!parent.IsMap()) {
    *why = "'" + path + "' is inside a list item that does not exist";
    return false;
  }
  std::string inner = value;
  for (std::size_t i = segs.size() - 1; i > have; --i) inner = "{" + segs[i] + ": " + inner + "}";
  return InsertIntoMap(text, parent, segs[have], inner, why);
}

}  // namespace

bool PatchYamlText(const std::string& text, const std::vector<std::pair<std::string, std::string>>& edits,
                   std::string* out, std::string* why) {
  std::string t = text;
  for (const auto& [path, value] : edits)
    if (!PatchOne(t, path, value, why)) return false;
  *out = std::move(t);
  return true;
}

}  // namespace formsim::sim
