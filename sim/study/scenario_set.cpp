#include "sim/study/scenario_set.hpp"

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include "sim/scenario/scenario_files.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {
namespace {

// The names of `@LIST` appended to `names`. A list is a small regular file: a folder, a device
// (/dev/zero) or a huge file is refused before a line of it is read.
void ReadList(const std::string& flag, std::vector<std::string>* names) {
  const std::string list = flag.substr(1);
  std::error_code ec;
  if (!fs::is_regular_file(list, ec))
    throw std::runtime_error("--scenario " + flag + ": the list must be a file of scenario names");
  if (fs::file_size(list, ec) > kMaxScenarioListBytes)
    throw std::runtime_error("--scenario " + flag + ": the list is larger than 1 MiB");
  std::ifstream in(list);
  if (!in) throw std::runtime_error("--scenario " + flag + ": cannot read the list file");
  const std::size_t before = names->size();
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::size_t a = line.find_first_not_of(" \t\r");
    if (a == std::string::npos) continue;
    names->push_back(line.substr(a, line.find_last_not_of(" \t\r") - a + 1));
  }
  if (names->size() == before)
    throw std::runtime_error("--scenario " + flag + ": the list names no scenario");
}

// "a real number" ... in the order of Param::Kind.
const char* KindWord(Param::Kind k) {
  static const char* const kWords[] = {"a real number", "an integer", "a flag", "a choice"};
  return kWords[static_cast<int>(k)];
}

}  // namespace

std::string ScenarioStem(const ScenarioSource& source) {
  return fs::path(source.file()).stem().string();
}

std::vector<ScenarioSource> ReadScenarioSet(const std::string& positional,
                                            const std::vector<std::string>& flags,
                                            const std::string& command) {
  std::vector<std::string> names;
  if (!positional.empty()) names.push_back(positional);
  for (const std::string& f : flags) {
    if (f.empty() || f[0] != '@')
      names.push_back(f);
    else
      ReadList(f, &names);
  }
  if (names.empty()) throw std::runtime_error(command + ": give a scenario (or --scenario)");
  std::vector<ScenarioSource> out;
  std::set<std::string> seen;
  std::map<std::string, std::string> stems;  // stem -> the name that has it
  for (const std::string& n : names) {
    const std::string file = ResolveScenario(n);
    if (!seen.insert(fs::absolute(file).lexically_normal().string()).second)
      throw std::runtime_error("--scenario " + n + ": named twice");
    out.push_back(ScenarioSource::FromFile(file));
    const auto [it, fresh] = stems.emplace(ScenarioStem(out.back()), n);
    if (!fresh)
      throw std::runtime_error("--scenario " + n + ": its name '" + it->first + "' is taken by " +
                               it->second +
                               " (scenarios are named by their file's stem in the tables, "
                               "legends and file names; rename one)");
  }
  return out;
}

void CheckScenarioKeys(const std::vector<ScenarioSource>& sources,
                       const std::vector<Override>& sets, const std::vector<const Param*>& keys,
                       const std::string& role) {
  for (std::size_t i = 1; i < sources.size(); ++i) {
    const ParsedScenario parsed = ParseScenario(sources[i], sets);
    for (const Param* p : keys) {
      const Param* q = parsed.params.Find(p->key);
      const std::string where = "--scenario " + sources[i].file();
      if (q == nullptr)
        throw ScenarioError(
            where, p->key,
            "this scenario has no such tunable (every scenario must have every " + role + " key)");
      if (q->kind != p->kind)
        throw ScenarioError(where, p->key,
                            std::string("is ") + KindWord(q->kind) + " in this scenario and " +
                                KindWord(p->kind) + " in " + sources[0].file());
      if (q->choices != p->choices)
        throw ScenarioError(where, p->key,
                            "has other choices in this scenario than in " + sources[0].file());
    }
  }
}

}  // namespace formsim::sim
