// Tests of the experiment loop, the one load path, tunables and outputs with the minimal
// experiment kind of test_kind.hpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/core/run_output.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/session/session.hpp"
#include "sim/core/structure_editing.hpp"
#include "tests/sim/test_kind.hpp"

using namespace formsim;
using namespace formsim::sim;
using testkind::kScenario;
using testkind::NoisyCircle;

FORMSIM_REGISTER_EXPERIMENT("test_noisy_circle", NoisyCircle);

namespace {

std::string Csv(Experiment& e) {
  while (!e.finished()) e.Step();
  const std::string f = std::string(FORMSIM_BINARY_DIR) + "/noisy_circle.csv";
  e.recorder().WriteCsv(f);
  std::ifstream in(f);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string LoadError(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  try {
    LoadExperimentFromText(yaml, "x.yaml", sets);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Experiment, SameSeedGivesIdenticalCsvAndOtherSeedDiffers) {
  auto a = LoadExperimentFromText(kScenario, "a.yaml");
  auto b = LoadExperimentFromText(kScenario, "a.yaml");
  auto c = LoadExperimentFromText(kScenario, "a.yaml", {}, 4);
  const std::string ca = Csv(*a), cb = Csv(*b), cc = Csv(*c);
  EXPECT_EQ(ca, cb);
  EXPECT_NE(ca, cc);
  EXPECT_EQ(ca.substr(0, ca.find('\n')), "t,x,y,measured_v");
  EXPECT_EQ(a->recorder().rows(), 101u) << "row 0 plus one per step";
  EXPECT_EQ(a->steps(), 100);
  EXPECT_DOUBLE_EQ(a->time(), 1.0);
}

TEST(Experiment, LoaderRejectsBadRootsWithKeyAndLine) {
  EXPECT_NE(LoadError("type: nope\n").find("unknown experiment type 'nope'"), std::string::npos);
  EXPECT_NE(LoadError(std::string(kScenario) + "vv: 1\n").find("key 'vv': unknown key"),
            std::string::npos);
  const std::string flying = "type: test_noisy_circle\ndrive: {mode: flying}\n";
  EXPECT_NE(LoadError(flying).find("x.yaml:2:"), std::string::npos) << LoadError(flying);
  EXPECT_NE(LoadError(flying).find("key 'drive.mode'"), std::string::npos) << LoadError(flying);
  const std::string bad_dt = "type: test_noisy_circle\ndt: -1\n";
  EXPECT_NE(LoadError(bad_dt).find("x.yaml:2:"), std::string::npos) << LoadError(bad_dt);
  EXPECT_NE(LoadError("type: test_noisy_circle\nv: .nan\n").find("finite"), std::string::npos);
  EXPECT_NE(LoadError("type: test_noisy_circle\nv: -1\n").find("key 'v': must be >= 0"),
            std::string::npos);
  // A duplicate key is an error at the second occurrence (yaml-cpp would keep the first).
  const std::string dup = LoadError("type: test_noisy_circle\nv: 1\nv: 2\n");
  EXPECT_NE(dup.find("x.yaml:3:1: key 'v': duplicate key"), std::string::npos) << dup;
}

TEST(Experiment, OverridesAreNamedInMessages) {
  // A bad --set value is reported at the --set, not at a file position.
  const std::string e1 = LoadError(kScenario, {"v=-0.5"});
  EXPECT_NE(e1.find("--set v=-0.5: key 'v': must be >= 0"), std::string::npos) << e1;
  EXPECT_NE(LoadError(kScenario, {"v="}).find("empty value"), std::string::npos);
  EXPECT_NE(LoadError(kScenario, {"seed=1e19"}).find("--set seed=1e19"), std::string::npos);
  // A rule across keys broken by an override says which override was in force.
  const std::string e2 = LoadError(kScenario, {"v=3.6"});
  EXPECT_NE(e2.find("x.yaml:"), std::string::npos) << e2;
  EXPECT_NE(e2.find("(with --set v=3.6)"), std::string::npos) << e2;
}

TEST(Experiment, TunablesAreDeclaredOnceWithTheirValues) {
  const ParsedScenario p = ParseScenario(ScenarioSource::FromText(kScenario, "a.yaml", ""), {});
  const Param* v = p.params.Find("v");
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->value, 1.2);
  EXPECT_TRUE(v->in_file);
  EXPECT_EQ(v->tune.unit, "m/s");
  EXPECT_EQ(v->slider_min(), 0.0);
  EXPECT_EQ(v->slider_max(), 3.0);
  const Param* mode = p.params.Find("drive.mode");
  ASSERT_NE(mode, nullptr);
  EXPECT_EQ(mode->kind, Param::Kind::kChoice);
  EXPECT_EQ(mode->Text(), "ideal");
  EXPECT_FALSE(p.params.Find("sigma")->tune.live);
  // Every slider end is accepted by the loader.
  for (const Param& q : p.params.all()) {
    if (q.kind != Param::Kind::kDouble) continue;
    std::string canonical;
    EXPECT_EQ(q.Parse(std::to_string(q.slider_min()), &canonical), "") << q.key;
    EXPECT_EQ(q.Parse(std::to_string(q.slider_max()), &canonical), "") << q.key;
  }
}

TEST(Experiment, AKindWithoutCapabilitiesOffersNone) {
  auto e = LoadExperimentFromText(kScenario, "a.yaml");
  EXPECT_EQ(e->As<StructureEditing>(), nullptr);
  Session s(ScenarioSource::FromText(kScenario, "a.yaml", ""), {});
  EXPECT_NE(s.Restructure("remove R1",
                          [](const Experiment& now, const std::string& text) {
                            const auto* editing = now.As<StructureEditing>();
                            if (editing == nullptr)
                              throw std::runtime_error("no structural changes");
                            return editing->PlacedText(text);
                          })
                .find("no structural changes"),
            std::string::npos);
  EXPECT_EQ(s.restructures(), 0);
}

TEST(Experiment, SeedRoundTripsExactlyUpTo64Bits) {
  auto e = LoadExperimentFromText(kScenario, "a.yaml", {"seed=18446744073709551615"});
  EXPECT_EQ(e->setup().seed, 18446744073709551615ULL);
  const std::string json = e->Summary().Dump();
  EXPECT_NE(json.find("\"seed\": 18446744073709551615"), std::string::npos);
  auto f = LoadExperimentFromText(kScenario, "a.yaml", {"seed=12345678901"});
  EXPECT_NE(f->Summary().Dump().find("\"seed\": 12345678901,"), std::string::npos);
}

TEST(Experiment, ProvenanceRecordsFileHashOverridesAndVersion) {
  auto e = LoadExperimentFromText(kScenario, "a.yaml", {"v=0.7"}, 9);
  const std::string json = e->Summary().Dump();
  EXPECT_NE(json.find("\"scenario_sha256\": \"" + ScenarioSource::FromText(kScenario, "", "").sha256()),
            std::string::npos) << json;
  EXPECT_NE(json.find("\"origin\": \"--set\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"key\": \"v\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"origin\": \"--seed\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"formsim_version\""), std::string::npos) << json;
}

TEST(RunOutput, WritesFilesAndRejectsUnwritableFolder) {
  auto e = LoadExperimentFromText(kScenario, "a.yaml");
  while (!e->finished()) e->Step();
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/run_output_test";
  WriteRunOutputs(*e, dir);
  EXPECT_TRUE(std::filesystem::exists(dir + "/timeseries.csv"));
  std::ifstream in(dir + "/summary.json");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("\"scenario\": \"circle\""), std::string::npos) << ss.str();
  EXPECT_NE(ss.str().find("\"mode\": \"circle\""), std::string::npos) << ss.str();
  EXPECT_THROW(PrepareOutputDir("/proc/formsim_cannot_write_here"), std::runtime_error);
}
