// The sliding-window estimator's normal equations factored by Eigen's own LDLT and by DenseLdlt
// (each of its paths) give the same bytes of CSV and summary for shipped velocity scenarios,
// shortened: the whole-run counterpart of tests/common/dense_ldlt_test.cpp's matrix-by-matrix
// comparison. A changed rounding in the factorisation shows in the estimates within a second.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "control/common/cpu_features.hpp"
#include "control/common/dense_ldlt.hpp"
#include "sim/core/run_output.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/velocity/velocity_experiment.hpp"
#include "tests/support/test_files.hpp"

namespace formsim::sim::velocity {
namespace {

using control::LdltPath;

struct LdltPathScope {
  explicit LdltPathScope(LdltPath p) : saved(control::DefaultLdltPath()) {
    control::SetDefaultLdltPath(p);
  }
  ~LdltPathScope() { control::SetDefaultLdltPath(saved); }
  LdltPath saved;
};

// CSV + summary of a shipped scenario run with the LDLT on `path`.
std::string RunBytes(const std::string& name, const std::vector<std::string>& sets, LdltPath path) {
  LdltPathScope scope(path);
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/ldlt_paths/" + name + "_" +
                          std::to_string(static_cast<int>(path));
  std::filesystem::create_directories(dir);
  auto exp =
      LoadExperiment(std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/" + name + ".yaml", sets);
  exp->mutable_recorder().StreamTo(CsvPath(dir));
  while (!exp->finished()) exp->Step();
  WriteRunOutputs(*exp, dir);
  return testing::ReadText(CsvPath(dir)) + "\n--- summary ---\n" +
         testing::ReadText(dir + "/summary.json");
}

TEST(LdltPaths, ShippedVelocityScenariosAreTheSameBytesWithEigensLdlt) {
  std::vector<LdltPath> paths{LdltPath::kPortable, LdltPath::kAuto};
  if (control::CpuHasAvx2()) paths.push_back(LdltPath::kAvx2);
  for (const char* name : {"velocity_constant", "velocity_steps", "velocity_angular_high"}) {
    const std::vector<std::string> sets{"duration=6"};
    const std::string reference = RunBytes(name, sets, LdltPath::kEigen);
    ASSERT_GT(reference.size(), 10000u) << name;
    for (LdltPath path : paths)
      EXPECT_TRUE(RunBytes(name, sets, path) == reference)
          << name << " differs on path " << static_cast<int>(path);
  }
}

}  // namespace
}  // namespace formsim::sim::velocity
