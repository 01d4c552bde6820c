#pragma once
/// \file YAML pieces shared by the files that record runs (session records, run histories):
/// scenario texts kept by SHA-256 (so a record never depends on the file staying as it was),
/// override lists, run logs, and strict reads whose errors name file:line and the key.

#include <yaml-cpp/yaml.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "sim/session/run_log.hpp"
#include "sim/scenario/scenario.hpp"

namespace formsim::sim {

/// Strict reads of a record file: each error names file:line and the key.
struct RecordReader {
  std::string file;
  [[noreturn]] void Fail(const YAML::Node& at, const std::string& key,
                         const std::string& why) const;
  /// A scalar's text; "" when absent and not required.
  std::string Text(const YAML::Node& map, const std::string& key, bool required = true) const;
  long Step(const YAML::Node& map, const std::string& key) const;    ///< a whole number >= 0
  double Real(const YAML::Node& map, const std::string& key) const;  ///< finite
  /// The sequence at `key` (empty when absent and not required).
  YAML::Node List(const YAML::Node& map, const std::string& key, bool required = true) const;
};

/// Reads `file` whole. Throws std::runtime_error naming it.
std::string ReadRecordFile(const std::string& file, const std::string& what);
/// Parses a record's text into a map. Throws std::runtime_error naming file:line.
YAML::Node LoadRecordText(const std::string& text, const std::string& file);

/// The distinct scenario texts, in order of first appearance.
using SourceList = std::vector<std::shared_ptr<const ScenarioSource>>;
void AddSource(SourceList& list, const std::shared_ptr<const ScenarioSource>& source);
/// `key`: a list of {sha256, file, dir, text}; `quoted` writes the texts double-quoted (exact
/// for any text) instead of as literal blocks.
void EmitSources(YAML::Emitter& y, const std::string& key, const SourceList& sources, bool quoted);
/// Reads them back, checking each text against its SHA-256.
std::map<std::string, std::shared_ptr<const ScenarioSource>> ParseSources(const RecordReader& r,
                                                                          const YAML::Node& list);
/// True when every text of `a` equals the one of `b` at the same place.
bool SameTexts(const SourceList& a, const SourceList& b);

void EmitOverrides(YAML::Emitter& y, const std::string& key, const std::vector<Override>& list);
std::vector<Override> ParseOverrides(const RecordReader& r, const YAML::Node& map,
                                     const std::string& key);

void EmitRunLog(YAML::Emitter& y, const RunLog& log);  ///< keys `base` and `changes`
RunLog ParseRunLog(const RecordReader& r, const YAML::Node& map);

}  // namespace formsim::sim
