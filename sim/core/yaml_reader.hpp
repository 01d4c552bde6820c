#pragma once
/// \file Strict YAML reading (Flatland style): defaults at the call site; unknown keys, wrong
/// types and non-finite numbers are errors naming the file, line and key path, or the `--set`
/// / GUI edit that put the value there. Tunables are declared where they are read
/// (Real/Integer/Flag/Pick with a Tune), which fills the scenario's ParamTable.

#include <yaml-cpp/yaml.h>

#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/common/geometry.hpp"
#include "sim/core/param_table.hpp"

namespace formsim::sim {

/// A scenario error: "file:line:col: key 'a.b.c': message", or "--set a.b.c=v: key ...: ..."
/// when an override put the value there.
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(const std::string& file, int line, int column, const std::string& key,
                const std::string& message);
  /// `location` is already formatted ("file:3:7", "--set a=1", "GUI edit a=1").
  ScenarioError(const std::string& location, const std::string& key, const std::string& message);
  const std::string& location() const { return location_; }
  const std::string& key() const { return key_; }
  /// The message without location and key.
  const std::string& reason() const { return reason_; }
  int line() const { return line_; }

 private:
  std::string location_, key_, reason_;
  int line_ = 0;
};

/// A key whose value is a file path, resolved against the scenario's folder (Save rewrites it
/// when the scenario is written to another folder).
struct PathField {
  std::string key;       ///< full key path, e.g. "fuzzy.file"
  std::string text;      ///< as written (or the default)
  std::string resolved;  ///< the path the experiment opens
  bool in_file = false;
};

/// State shared by every reader of one scenario parse.
struct ReadContext {
  std::string file;        ///< for messages
  std::string dir;         ///< folder relative paths are resolved against
  ParamTable params;       ///< filled by the tunable readers
  std::vector<PathField> paths;
  /// Overrides by key path ("robots.R2.follow.k_l" -> "--set robots.R2.follow.k_l=-1"): an
  /// error at that key (or below it) names the override instead of a file position.
  std::map<std::string, std::string> origins;
};

/// A view of one YAML map that records which keys were read. Call Finish() when done: any key
/// not read is reported as unknown, with the list of allowed keys.
class YamlReader {
 public:
  /// A reader over `node`; `path` is the key path of `node` from the scenario root.
  YamlReader(YAML::Node node, std::shared_ptr<ReadContext> ctx, std::string path = "");
  /// A stand-alone reader (tests, fuzzy files): its own context.
  YamlReader(YAML::Node node, std::string file, std::string path = "");

  bool Has(const std::string& key) const;
  double Double(const std::string& key, double def);
  /// A number that is not a tunable but has a hard validity (the loader refuses the rest).
  double Double(const std::string& key, double def, const Tune& valid);
  int Int(const std::string& key, int def, const Tune& valid);
  /// A fixed-length list (the length of `def`) whose items must each satisfy `valid`.
  std::vector<double> Doubles(const std::string& key, const std::vector<double>& def, const Tune& valid);
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
  /// A file path: returns it resolved against the scenario's folder (absolute paths as given).
  std::string FilePath(const std::string& key, const std::string& def);

  /// Tunables: read with the default, checked against the declaration's validity and entered
  /// in the scenario's ParamTable under KeyPath(key).
  double Real(const std::string& key, double def, const Tune& tune);
  int Integer(const std::string& key, int def, const Tune& tune);
  bool Flag(const std::string& key, bool def, const Tune& tune);
  /// A choice among `choices`; returns the index.
  int Pick(const std::string& key, const std::vector<std::string>& choices, int def, const Tune& tune);
  /// A fixed-length list of tunable numbers; element i is the tunable "key.i", labelled
  /// `item_labels[i]` (default: the tune's label and the index).
  std::vector<double> Reals(const std::string& key, const std::vector<double>& def, const Tune& tune,
                            const std::vector<std::string>& item_labels = {});

  /// Sub-map (error if present and not a map). Returns an empty reader when absent.
  YamlReader Map(const std::string& key);
  /// Sequence of maps (error if present and not a sequence of maps). Item i's path is
  /// "key.NAME" when it has a `name`, else "key.i" (the same addressing as --set).
  std::vector<YamlReader> MapList(const std::string& key);
  /// Raw access for custom shapes (marks the key as read).
  YAML::Node Raw(const std::string& key);

  /// Throws ScenarioError for the first key never read.
  void Finish() const;
  /// Throws a ScenarioError located at `key` of this map (or at the map if key is absent).
  [[noreturn]] void Fail(const std::string& key, const std::string& message) const;

  const std::string& file() const { return ctx_->file; }
  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  ReadContext& context() const { return *ctx_; }
  std::shared_ptr<ReadContext> shared_context() const { return ctx_; }
  std::string KeyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

 private:
  YAML::Node Get(const std::string& key);
  void Enter(Param p, const std::string& key);
  YAML::Node node_;
  std::shared_ptr<ReadContext> ctx_;
  std::string path_;
  std::set<std::string> read_;
};

/// Parses YAML text; syntax errors become ScenarioErrors with the line. Duplicate keys in a
/// map are errors (yaml-cpp would silently keep the first).
YAML::Node LoadYamlText(const std::string& text, const std::string& file);
/// Reads and parses a YAML file.
YAML::Node LoadYamlFile(const std::string& file);

/// Applies `path.to.key=value` to a YAML tree. Sequence items are addressed by index or by the
/// value of their `name` key. The value is parsed as YAML (so `[1, 2, 0.5]` works); an empty
/// value is an error. Returns an error message, empty on success. Unknown keys are created and
/// later rejected by the strict reader, so a typo is reported with its path.
std::string ApplySet(YAML::Node& root, const std::string& assignment);
/// Writes a value into the tree at a dotted path (same addressing as ApplySet).
std::string SetAtPath(YAML::Node& root, const std::string& path, const YAML::Node& value);
/// The node at a dotted path, or an undefined node.
YAML::Node FindAtPath(const YAML::Node& root, const std::string& path);
/// Splits "a.b.c" into its segments.
std::vector<std::string> SplitKeyPath(const std::string& path);

/// A YAML scalar holding `v` as its shortest round-trip text, with -0 written as 0: how
/// formsim writes numbers into scenario text it generates.
YAML::Node NumberNode(double v);

}  // namespace formsim::sim
