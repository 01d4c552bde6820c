// Mutation stays caught: for each shipped lesson, a deliberate error in its scenario (a gain ×10
// or ÷10, a sensor noise ×10, a flipped choice) applied to every run with `formsim lessons check
// --set` makes at least one of the lesson's checks fail on seed 1 — the checks measure the
// effects the lesson teaches, not numbers that hold whatever the scenario does.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sim/scenario/scenario_files.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

// Lesson -> the error put into its scenario.
const std::vector<std::pair<std::string, std::string>> kMutations = {
    {"agv_odometry_beacon_kf", "beacon.sigma_xy=0.1"},           // beacon noise ×10
    {"agv_outliers_gate", "beacon.sigma_xy=0.1"},                // beacon noise ×10
    {"agv_r_matches_sigma", "beacon.sigma_xy=0.1"},              // beacon noise ×10
    {"deep_cascade", "robots.R7.follow.k_l=0.3"},                // the deepest gain ×10
    {"inspection_dead_reckoning", "laser.range_sigma=0.2"},      // laser noise ×10
    {"inspection_fuzzy_rules", "fuzzy.s_scale=0.1"},             // the offset's gain ×10
    {"inspection_kalman_per_axis", "laser.range_sigma=0.2"},     // laser noise ×10
    {"inspection_post_geometry", "laser.range_sigma=0.2"},       // laser noise ×10
    {"ll_singularity", "robots.R3.follow.k_l=10"},               // gain ×10
    {"lphi_time_constant", "robots.R2.follow.k_l=10"},           // gain ×10
    {"noise_and_ukf", "noise.phi_variance=0.9186e-2"},           // angle noise σ ×10
    {"printed_vs_per_sample", "robots.R2.follow.k_l=1.5"},       // gain ×10
    {"switching_around_obstacles", "avoidance.safety_distance=0.03"},  // safety distance ÷10
    {"velocity_slippery_floor", "terrain.gravel.shear_slip=0.025"},    // gravel's slip ÷10
    {"velocity_three_estimates", "sensors.camera.bearing_noise=0.02"},  // camera noise ×10
};

TEST(LessonMutation, EveryLessonCatchesADeliberateError) {
  const std::string dir = TempDir("lesson_mutation");
  std::set<std::string> covered;
  for (const auto& [lesson, edit] : kMutations) {
    covered.insert(lesson);
    const std::string log = dir + "/" + lesson + ".txt";
    const int rc = RunShell(Binary() + " lessons check " + lesson + " --seeds 1 --jobs 2 --set " + edit, log);
    const std::string out = ReadText(log);
    // 1: a check failed (2 would be a refused edit: the mutation must be a real scenario edit).
    EXPECT_EQ(rc, 1) << lesson << " --set " << edit << " is not caught:\n" << out;
    EXPECT_NE(out.find(" FAILS"), std::string::npos) << lesson;
    EXPECT_EQ(out.find("run error"), std::string::npos) << lesson << ": a run failed, not a check\n" << out;
  }
  for (const std::string& file : sim::ShippedLessons()) {
    const std::string stem = file.substr(file.find_last_of('/') + 1, file.size() - file.find_last_of('/') - 6);
    EXPECT_TRUE(covered.count(stem)) << stem << " has no mutation in kMutations";
  }
}

// Bad input to `lessons check --set` and `lessons show --seed` is refused by name (exit 2) before
// anything runs: not a check failing on every seed, not a seed wrapped around 2^64.
TEST(LessonMutation, BadSetsAndSeedsAreRefusedByName) {
  const std::string dir = TempDir("lesson_bad_input");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"check lphi_time_constant --seeds 1 --set nosuch.key=1", "key 'nosuch': unknown key"},
      {"check lphi_time_constant --seeds 1 --set robots.R2.follow.k_l=nan",
       "--set robots.R2.follow.k_l=nan"},
      {"show lphi_time_constant --seed -1", "--seed '-1'"},
      {"show lphi_time_constant --seed 18446744073709551616", "--seed '18446744073709551616'"},
      {"show lphi_time_constant --seed 1..3", "expected one seed"},
  };
  for (const auto& [args, message] : cases) {
    const std::string log = dir + "/log.txt";
    EXPECT_EQ(RunShell(Binary() + " lessons " + args, log), 2) << args;
    const std::string out = ReadText(log);
    EXPECT_NE(out.find(message), std::string::npos) << args << ":\n" << out;
    EXPECT_EQ(out.find(" FAILS"), std::string::npos) << args << ": ran checks\n" << out;
  }
}

}  // namespace
}  // namespace formsim::app
