// Large formations: the generated wedges hold together (no collision, saturation, singular
// configuration or filter fault after the start, errors as small as the paper's 3-robot run),
// the shipped formation_swarm_* scenarios are exactly what the generator writes, and a run gives
// the same bytes with one thread and with several.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/core/run_output.hpp"
#include "sim/formation/cascade_generator.hpp"
#include "sim/formation/formation_experiment.hpp"
#include "sim/scenario/scenario.hpp"
#include "tests/support/test_files.hpp"

namespace formsim::sim::formation {
namespace {

using testing::ReadText;

// The shipped swarms: robots, duration and one line of description.
struct Swarm {
  const char* name;
  int robots;
  double duration;
  const char* description;
};
const Swarm kSwarms[] = {
    {"formation_swarm_100", 100, 14.0,
     "100 robots in a wedge (one l-phi link, the rest l-l), a UKF per link, S-turns"},
    {"formation_swarm_1000", 1000, 14.0,
     "1000 robots in a wedge (one l-phi link, the rest l-l), a UKF per link, S-turns"},
};

std::string SwarmText(const Swarm& s) {
  CascadeOptions o;
  o.robots = s.robots;
  o.ukf = true;
  o.duration = s.duration;
  o.name = s.name;
  o.description = s.description;
  return MakeCascadeScenario(o);
}

// Set FORMSIM_REGENERATE_SWARMS=1 to write them after changing the generator.
TEST(Swarm, ShippedScenariosAreTheGeneratorsOutput) {
  for (const Swarm& s : kSwarms) {
    const std::string file =
        std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/" + s.name + ".yaml";
    const std::string text = SwarmText(s);
    if (std::getenv("FORMSIM_REGENERATE_SWARMS") != nullptr) std::ofstream(file, std::ios::binary) << text;
    EXPECT_EQ(ReadText(file), text) << file << " differs from MakeCascadeScenario's output";
  }
}

// Links, events and errors of a finished (or stopped) formation run.
void ExpectHolds(const Experiment& exp, double max_e_l, double max_e_phi, const std::string& what) {
  const auto& f = dynamic_cast<const FormationExperiment&>(exp);
  EXPECT_EQ(exp.status(), "completed") << what;
  // Nothing after the first 0.2 s: the start offsets may clamp a command for a step or two.
  for (const Event& e : exp.events().list()) EXPECT_LT(e.time, 0.2) << what << ": " << e.message;
  EXPECT_EQ(exp.events().Count(event::kCollision), 0) << what;
  EXPECT_EQ(exp.events().Count(event::kSingular), 0) << what;
  EXPECT_EQ(exp.events().Count(event::kFilterFault), 0) << what;
  for (const auto& l : f.Links()) {
    EXPECT_LT(l.e_l.max_abs_settled(), max_e_l) << what << " " << l.name;
    if (l.has_phi_target) {
      EXPECT_LT(l.e_phi.max_abs_settled(), max_e_phi) << what << " " << l.name;
    }
  }
}

TEST(Swarm, GeneratedWedgesOfAnySizeHold) {
  for (int n : {1, 2, 3, 4, 7, 10, 45, 50}) {
    for (bool ukf : {false, true}) {
      auto exp = LoadExperimentFromText(MakeCascadeScenario(n, ukf), "generated", {"duration=7"});
      ASSERT_EQ(exp->world().robots().size(), static_cast<std::size_t>(n));
      while (!exp->finished()) exp->Step();
      // The paper's 3-robot run with its UKF: 7 mm and 8 mrad at worst after its transient.
      ExpectHolds(*exp, ukf ? 0.007 : 1e-3, ukf ? 0.008 : 1e-3,
                  std::to_string(n) + (ukf ? " ukf" : " truth"));
    }
  }
  EXPECT_THROW(MakeCascadeScenario(0, false), std::invalid_argument);
  EXPECT_THROW(MakeCascadeScenario(10, false, 0.3), std::invalid_argument);
}

TEST(Swarm, HundredRobotSwarmHoldsThroughItsTurns) {
  auto exp = LoadExperiment(std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/formation_swarm_100.yaml");
  while (!exp->finished()) exp->Step();
  ExpectHolds(*exp, 0.007, 0.008, "formation_swarm_100");
}

// The CSV and the summary of a run, written as `formsim run` writes them.
std::pair<std::string, std::string> RunOutputs(const std::string& text, int threads,
                                               const std::string& dir) {
  auto exp = LoadExperimentFromText(text, "generated", {"duration=0.6", "record_every=3"});
  exp->SetThreads(threads);
  std::filesystem::create_directories(dir);
  exp->mutable_recorder().StreamTo(CsvPath(dir));
  while (!exp->finished()) exp->Step();
  WriteRunOutputs(*exp, dir);
  return {ReadText(CsvPath(dir)), ReadText(dir + "/summary.json")};
}

TEST(Swarm, SameBytesWithOneThreadAndWithSeveral) {
  // Wide enough that the recorder formats its rows in blocks on the pool as well.
  const std::string text = MakeCascadeScenario(300, true);
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/swarm_threads";
  const auto one = RunOutputs(text, 1, dir + "/1");
  ASSERT_GT(one.first.size(), 100000u);
  for (int threads : {2, 3}) {
    const auto many = RunOutputs(text, threads, dir + "/" + std::to_string(threads));
    EXPECT_TRUE(one.first == many.first) << "CSV differs with " << threads << " threads";
    EXPECT_TRUE(one.second == many.second) << "summary differs with " << threads << " threads";
  }
}

}  // namespace
}  // namespace formsim::sim::formation
