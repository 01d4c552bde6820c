#include "sim/scenario/scenario.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/sha256.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {

ScenarioSource ScenarioSource::FromFile(const std::string& file) {
  std::string text;
  try {
    text = ReadBoundedFile(file);
  } catch (const FileReadError& e) {
    throw ScenarioError(file, 0, 0, "", e.reason());
  }
  return FromText(std::move(text), file, fs::path(file).parent_path().string());
}

ScenarioSource ScenarioSource::FromText(std::string text, std::string name, std::string dir) {
  ScenarioSource s;
  s.text_ = std::move(text);
  s.file_ = std::move(name);
  s.dir_ = std::move(dir);
  s.sha256_ = Sha256Hex(s.text_);
  return s;
}

namespace {

ExperimentSetup ReadRoot(YamlReader& r, const ScenarioSource& src) {
  ExperimentSetup s;
  s.file = src.file();
  s.dir = src.dir();
  s.type = r.RequiredString("type");
  s.name = r.String("name", fs::path(src.file()).stem().string());
  s.description = r.String("description", "");
  if (r.Has("seed")) {
    const YAML::Node n = r.Raw("seed");
    std::uint64_t seed = 0;
    if (!n.IsScalar() || !ParseUint64(n.Scalar(), &seed))
      r.Fail("seed", "must be an integer in [0, 18446744073709551615]");
    s.seed = seed;
  } else {
    r.Raw("seed");
  }
  s.dt = r.Double("dt", s.dt);
  if (!(s.dt > 0 && s.dt <= 0.1)) r.Fail("dt", "must be in (0, 0.1] s");
  s.duration = r.Double("duration", s.duration);
  if (!(s.duration > 0)) r.Fail("duration", "must be positive");
  s.record_every = r.Int("record_every", 1);
  if (s.record_every < 1) r.Fail("record_every", "must be >= 1");
  // An absurd step count (dt = 1e-9 s, duration = 1e12 s) is refused unless asked for: a run
  // that long is rarely meant, and it would hold the machine for hours.
  double max_steps = 1e8;
  if (r.Has("max_steps")) {
    const YAML::Node n = r.Raw("max_steps");
    std::uint64_t v = 0;
    if (!n.IsScalar() || !ParseUint64(n.Scalar(), &v) || v < 1)
      r.Fail("max_steps", "must be a whole number of steps >= 1");
    max_steps = static_cast<double>(v);
  } else {
    r.Raw("max_steps");
  }
  const double steps = std::ceil(s.duration / s.dt - 1e-9);
  if (steps > max_steps)
    r.Fail("duration", "gives " + Sprintf("%.3g", steps) + " steps of dt = " + FormatDouble(s.dt) +
                           " s, more than max_steps = " + Sprintf("%.3g", max_steps) +
                           "; raise max_steps (--max-steps N) for a run this long");
  return s;
}

}  // namespace

ParsedScenario ParseScenario(const ScenarioSource& source, const std::vector<Override>& overrides) {
  YAML::Node root = LoadYamlText(source.text(), source.file());
  auto ctx = std::make_shared<ReadContext>();
  ctx->file = source.file();
  ctx->dir = source.dir();
  for (const Override& o : overrides) {
    if (o.value.size() > kMaxOverrideBytes)
      throw ScenarioError(o.origin + " " + o.key + "=" + o.value.substr(0, 40) + "...", o.key,
                          "the value is " + std::to_string(o.value.size()) +
                              " characters long; a value of --set or an edit takes at most " +
                              std::to_string(kMaxOverrideBytes));
    const std::string where = o.origin + " " + o.key + "=" + o.value;
    YAML::Node value;
    if (o.value.find_first_not_of(" \t") == std::string::npos)
      throw ScenarioError(where, o.key, "empty value");
    try {
      value = LoadYamlText(o.value, where);
    } catch (const ScenarioError& e) {
      throw ScenarioError(where, o.key, "cannot parse the value: " + e.reason());
    }
    if (value.IsNull()) throw ScenarioError(where, o.key, "empty value");
    if (!root.IsMap()) break;  // reported below
    const std::string err = SetAtPath(root, o.key, value);
    if (!err.empty()) throw ScenarioError(where, o.key, err);
    ctx->origins[o.key] = where;
  }
  if (!root.IsMap()) throw ScenarioError(source.file(), 0, 0, "", "a scenario must be a YAML map of keys");

  YamlReader r(root, ctx);
  ParsedScenario out;
  try {
    out.setup = ReadRoot(r, source);
    out.kind = ExperimentRegistry::Find(out.setup.type);
    if (out.kind == nullptr) {
      std::string known;
      for (const auto& t : ExperimentRegistry::Types()) known += (known.empty() ? "" : ", ") + t;
      r.Fail("type", "unknown experiment type '" + out.setup.type + "' (known: " + known + ")");
    }
    out.config = out.kind->read(r, out.setup);
    // A lesson file is a scenario with its lesson text beside it.
    if (r.Has("lesson")) {
      YamlReader l = r.Map("lesson");
      out.lesson = ReadLesson(l);
    } else {
      r.Raw("lesson");
    }
    r.Finish();
  } catch (const ScenarioError& e) {
    // A check across keys (a formation triangle, a graph) can fail at a file position because of
    // an override elsewhere: say which overrides were in force.
    bool at_override = false;
    for (const auto& kv : ctx->origins) at_override = at_override || e.location() == kv.second;
    if (at_override || overrides.empty()) throw;
    std::string with;
    for (const Override& o : overrides)
      with += (with.empty() ? "" : ", ") + o.origin + " " + o.key + "=" + o.value;
    throw ScenarioError(e.location(), e.key(), e.reason() + " (with " + with + ")");
  }
  out.params = std::move(ctx->params);
  out.paths = std::move(ctx->paths);
  out.setup.provenance.file = source.file();
  out.setup.provenance.sha256 = source.sha256();
  out.setup.provenance.seed = out.setup.seed;
  out.setup.provenance.overrides = overrides;
  return out;
}

std::unique_ptr<Experiment> BuildExperiment(const ParsedScenario& parsed) {
  return parsed.kind->build(parsed.setup, *parsed.config);
}

std::vector<Override> CliOverrides(const std::vector<std::string>& sets, long long seed) {
  std::vector<Override> out;
  for (const std::string& a : sets) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0)
      throw ScenarioError("--set " + a, "", "expected path.to.key=value");
    out.push_back({a.substr(0, eq), a.substr(eq + 1), "--set", -1});
  }
  if (seed >= 0) out.push_back({"seed", std::to_string(seed), "--seed", -1});
  return out;
}

std::unique_ptr<Experiment> LoadExperiment(const std::string& file,
                                           const std::vector<std::string>& sets, long long seed) {
  return BuildExperiment(ParseScenario(ScenarioSource::FromFile(file), CliOverrides(sets, seed)));
}

std::unique_ptr<Experiment> LoadExperimentFromText(const std::string& text, const std::string& name,
                                                   const std::vector<std::string>& sets, long long seed) {
  return BuildExperiment(
      ParseScenario(ScenarioSource::FromText(text, name, ""), CliOverrides(sets, seed)));
}

}  // namespace formsim::sim
