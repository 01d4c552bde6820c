// The shipped formation scenarios give the same numbers as before the filter and the step were
// made fast (closed-form update, fast angle wrap, shared sines and cosines, the thread pool):
// tests/fixtures/reference/<scenario>.txt holds the results and some recorded rows of runs of the
// code as it was before, and every value must agree to within 1e-9 (relative above 1).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "sim/scenario/scenario.hpp"

namespace formsim::sim {
namespace {

constexpr double kTolerance = 1e-9;

std::string ReferenceFile(const std::string& name) {
  return std::string(FORMSIM_SOURCE_DIR) + "/tests/fixtures/reference/" + name + ".txt";
}

// Compares a finished run with its reference file; returns the number of values compared.
int CompareWithReference(const std::string& name, int threads) {
  auto exp = LoadExperiment(std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/" + name + ".yaml");
  exp->SetThreads(threads);
  while (!exp->finished()) exp->Step();
  const Metrics results = exp->Results();
  const Recorder& rec = exp->recorder();

  std::ifstream in(ReferenceFile(name));
  EXPECT_TRUE(in) << ReferenceFile(name);
  std::string line;
  int compared = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string key;
    double want = 0.0;
    fields >> key >> want;
    double got = std::nan("");
    if (key.rfind("results.", 0) == 0) {
      const double* v = results.Find(key.substr(8));
      if (v == nullptr) {
        ADD_FAILURE() << name << ": no result " << key;
        continue;
      }
      got = *v;
    } else {
      // "row<i>.<column>"
      const std::size_t dot = key.find('.');
      const std::size_t row = std::stoul(key.substr(3, dot - 3));
      const int column = rec.Column(key.substr(dot + 1));
      if (column < 0 || row >= rec.rows()) {
        ADD_FAILURE() << name << ": no recorded " << key;
        continue;
      }
      got = rec.At(row, column);
    }
    EXPECT_NEAR(got, want, kTolerance * std::max(1.0, std::abs(want))) << name << " " << key;
    ++compared;
  }
  return compared;
}

class PaperReference : public ::testing::TestWithParam<const char*> {};

TEST_P(PaperReference, SameNumbersAsBeforeWithinOneNanoPart) {
  for (int threads : {1, 2}) EXPECT_GT(CompareWithReference(GetParam(), threads), 20) << threads;
}

INSTANTIATE_TEST_SUITE_P(Scenarios, PaperReference,
                         ::testing::Values("formation_traj1", "formation_traj2", "formation_traj2_ukf",
                                           "formation_traj3", "formation_cascade7",
                                           "formation_traj2_noisy_raw", "formation_traj1_per_sample",
                                           "formation_traj2_per_sample",
                                           "formation_traj3_per_sample"));

}  // namespace
}  // namespace formsim::sim
