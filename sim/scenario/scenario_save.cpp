#include "sim/scenario/scenario_save.hpp"

#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "sim/scenario/yaml_patch.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {
namespace {

// A path as YAML text: plain when it is safe, double-quoted otherwise.
std::string YamlPathText(const std::string& p) {
  bool plain = !p.empty();
  for (char c : p)
    plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '/' || c == '.' ||
                      c == '_' || c == '-');
  if (plain) return p;
  std::string q = "\"";
  for (char c : p) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

}  // namespace

std::vector<Override> LastValuePerKey(const std::vector<Override>& in) {
  std::vector<Override> out;
  for (std::size_t i = 0; i < in.size(); ++i) {
    bool later = false;
    for (std::size_t j = i + 1; j < in.size() && !later; ++j) later = in[j].key == in[i].key;
    if (later) continue;
    Override o = in[i];
    o.step = -1;
    out.push_back(o);
  }
  return out;
}

std::string TunedScenarioText(const ScenarioSource& source, const std::vector<Override>& given,
                              const std::string& path, std::string* note) {
  const std::vector<Override> overrides = LastValuePerKey(given);
  std::vector<std::pair<std::string, std::string>> edits;
  for (const Override& o : overrides) edits.emplace_back(o.key, o.value);
  // Relative file paths must still point at the same files from the new folder.
  const fs::path target_dir = fs::absolute(fs::path(path)).parent_path();
  const ParsedScenario expected = ParseScenario(source, overrides);
  for (const PathField& f : expected.paths) {
    if (fs::path(f.text).is_absolute()) continue;
    const fs::path abs = fs::absolute(f.resolved).lexically_normal();
    std::string rel = abs.lexically_relative(target_dir).string();
    if (rel.empty()) rel = abs.string();
    if (rel != f.text || !f.in_file) edits.emplace_back(f.key, YamlPathText(rel));
  }
  const std::string target_name = path;
  auto verify = [&](const std::string& text) -> std::string {
    try {
      const ParsedScenario got =
          ParseScenario(ScenarioSource::FromText(text, target_name, target_dir.string()), {});
      for (const Param& p : expected.params.all()) {
        const Param* q = got.params.Find(p.key);
        if (q == nullptr || q->Text() != p.Text())
          return "'" + p.key + "' reads back as " + (q ? q->Text() : "missing") + ", not " +
                 p.Text();
      }
      if (got.setup.seed != expected.setup.seed) return "the seed reads back differently";
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  std::string text, why;
  if (PatchYamlText(source.text(), edits, &text, &why)) {
    why = verify(text);
    if (why.empty()) return text;
  }
  // Fall back to writing the whole tree (values as written, comments lost).
  YAML::Node tree = LoadYamlText(source.text(), source.file());
  for (const auto& [key, value] : edits) {
    const std::string err = SetAtPath(tree, key, LoadYamlText(value, key));
    if (!err.empty()) throw std::runtime_error("cannot save: " + err);
  }
  YAML::Emitter out;
  out.SetIndent(2);
  out << tree;
  text = "# Tuned with formsim from " + fs::path(source.file()).filename().string() + "\n" +
         out.c_str() + "\n";
  const std::string err = verify(text);
  if (!err.empty()) throw std::runtime_error("cannot save a scenario that loads back: " + err);
  if (note) *note = "comments of the original could not be kept (" + why + ")";
  return text;
}

}  // namespace formsim::sim
