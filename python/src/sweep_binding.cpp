#include "python/src/sweep_binding.hpp"

#include <pybind11/stl.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "sim/scenario/scenario.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/study/sweep.hpp"
#include "sim/study/sweep_spec.hpp"
#include "sim/study/sweep_store.hpp"
#include "sim/study/sweep_tables.hpp"

namespace py = pybind11;

namespace formsim::python {
namespace {

// The scenario as a worker rebuilds it: the same name, folder and text as FromFile gave.
sim::ScenarioSource Source(const std::string& file, const std::string& text) {
  return sim::ScenarioSource::FromText(text, file,
                                       std::filesystem::path(file).parent_path().string());
}

// (file, text, manifest, runs): what every run needs, as `formsim sweep` defines it.
std::tuple<std::string, std::string, std::string, std::size_t> Define(
    const std::string& name_or_path, const std::vector<std::pair<std::string, std::string>>& sets,
    const std::vector<std::string>& vary, const std::optional<std::string>& seeds,
    std::uint64_t sample_seed, std::size_t max_runs) {
  const std::string file = sim::ResolveScenario(name_or_path);
  const sim::ScenarioSource source = sim::ScenarioSource::FromFile(file);
  std::vector<sim::Override> overrides;
  for (const auto& [key, value] : sets) overrides.push_back({key, value, "--set", -1});
  const std::vector<std::uint64_t> seed_list =
      seeds ? sim::ParseSeeds(*seeds) : std::vector<std::uint64_t>{};
  if (max_runs < 1 || max_runs > sim::kMaxSweepRuns)
    throw std::runtime_error("max_runs " + std::to_string(max_runs) + ": must be in 1 ... " +
                             std::to_string(sim::kMaxSweepRuns));
  const sim::SweepDefinition def =
      sim::DefineSweep(source, overrides, vary, seed_list, sample_seed, max_runs);
  return {file, source.text(), sim::ManifestText(def), def.runs()};
}

// One run's record text (the bytes of runs/NNNNNN.run), without the GIL.
std::string Run(const std::string& file, const std::string& text, const std::string& manifest,
                std::size_t run) {
  const sim::ScenarioSource source = Source(file, text);
  const sim::SweepDefinition def = sim::ParseManifest(manifest, "sweep manifest");
  if (def.scenarios.size() != 1 || def.scenarios[0].sha256 != source.sha256())
    throw std::runtime_error(
        "sweep_run: the scenario text is not the one the sweep was defined on");
  if (run >= def.runs())
    throw std::runtime_error("sweep_run: run " + std::to_string(run) + " of a sweep of " +
                             std::to_string(def.runs()) + " runs");
  std::optional<sim::SweepRecord> rec;
  {
    py::gil_scoped_release free;
    rec = sim::RunSweepRun(source, def, run);
  }
  if (!rec) throw std::runtime_error("sweep_run: run " + std::to_string(run) + " was abandoned");
  return sim::RecordText(def, *rec);
}

// (runs.csv, aggregate.csv) from the records' texts.
std::pair<std::string, std::string> Tables(const std::string& manifest,
                                           const std::vector<std::string>& records) {
  const sim::SweepDefinition def = sim::ParseManifest(manifest, "sweep manifest");
  std::vector<sim::SweepRecord> parsed;
  parsed.reserve(records.size());
  for (std::size_t i = 0; i < records.size(); ++i)
    parsed.push_back(sim::ParseRecord(records[i], def, "record " + std::to_string(i)));
  const sim::SweepTables tables = sim::BuildSweepTables(def, std::move(parsed));
  return {tables.runs_csv, tables.aggregate_csv};
}

}  // namespace

void BindSweep(py::module_& m) {
  m.def("sweep_define", &Define, py::arg("name_or_path"), py::arg("sets"), py::arg("vary"),
        py::arg("seeds"), py::arg("sample_seed"), py::arg("max_runs"),
        "Defines a sweep as `formsim sweep` does. Returns (file, scenario text, manifest text, "
        "number of runs).");
  m.def("sweep_run", &Run, py::arg("file"), py::arg("text"), py::arg("manifest"), py::arg("run"),
        "Runs run `run` of a sweep (without the GIL). Returns its record's text.");
  m.def("sweep_tables", &Tables, py::arg("manifest"), py::arg("records"),
        "(runs.csv, aggregate.csv) of a sweep from its records' texts.");
}

}  // namespace formsim::python
