#pragma once
/// \file Strict YAML reading (Flatland style): defaults at the call site, unknown keys, wrong
/// types and non-finite numbers are errors naming the file, line and key path.

#include <yaml-cpp/yaml.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/common/geometry.hpp"

namespace formsim::sim {

/// A scenario error: "file:line:col: key 'a.b.c': message".
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(const std::string& file, int line, int column, const std::string& key,
                const std::string& message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }

 private:
  std::string file_, key_;
  int line_ = 0;
};

/// A view of one YAML map that records which keys were read. Call Finish() when done: any key
/// not read is reported as unknown, with the list of allowed keys.
class YamlReader {
 public:
  YamlReader(YAML::Node node, std::string file, std::string path = "");

  bool Has(const std::string& key) const;
  double Double(const std::string& key, double def);
  double RequiredDouble(const std::string& key);
  int Int(const std::string& key, int def);
  bool Bool(const std::string& key, bool def);
  std::string String(const std::string& key, const std::string& def);
  std::string RequiredString(const std::string& key);
  /// A string that must be one of `choices`; returns its index.
  int Choice(const std::string& key, const std::vector<std::string>& choices, int def);
  /// A fixed-length list of numbers, e.g. pose: [x, y, theta].
  std::vector<double> Doubles(const std::string& key, const std::vector<double>& def, int length = -1);
  /// A list of points [[x, y], ...] with at least `min_count` entries.
  std::vector<Vec2> Points(const std::string& key, int min_count = 0);
  /// A pose [x, y, theta] (theta in radians), or `def` when absent.
  Pose2 Pose(const std::string& key, const Pose2& def);
  std::vector<std::string> Strings(const std::string& key, const std::vector<std::string>& def);
  /// Sub-map (error if present and not a map). Returns an empty reader when absent.
  YamlReader Map(const std::string& key);
  /// Sequence of maps (error if present and not a sequence of maps).
  std::vector<YamlReader> MapList(const std::string& key);
  /// Raw access for custom shapes (marks the key as read).
  YAML::Node Raw(const std::string& key);

  /// Throws ScenarioError for the first key never read.
  void Finish() const;
  /// Throws a ScenarioError located at `key` of this map (or at the map if key is absent).
  [[noreturn]] void Fail(const std::string& key, const std::string& message) const;

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  std::string KeyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

 private:
  YAML::Node Get(const std::string& key);
  YAML::Node node_;
  std::string file_, path_;
  std::set<std::string> read_;
};

/// Loads a YAML file; syntax errors become ScenarioErrors with the line.
YAML::Node LoadYamlFile(const std::string& file);

/// Applies `path.to.key=value` to a YAML tree. Sequence items are addressed by index or by the
/// value of their `name` key. The value is parsed as YAML (so `[1, 2, 0.5]` works). Returns an
/// error message, empty on success. Unknown keys are created and later rejected by the strict
/// reader, so a typo is reported with its path.
std::string ApplySet(YAML::Node& root, const std::string& assignment);
/// Writes a value into the tree at a dotted path (same addressing as ApplySet).
std::string SetAtPath(YAML::Node& root, const std::string& path, const YAML::Node& value);

}  // namespace formsim::sim
