// `formsim run --threads N`: the CSV and the summary are the same bytes for any N, and a bad N
// is refused naming the flag.
#include <gtest/gtest.h>

#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

TEST(Cli, SameCsvAndSummaryWithOneThreadAndWithSeveral) {
  const std::string dir = TempDir("cli_threads");
  std::string csv, summary;
  for (int threads : {1, 2, 3}) {
    const std::string out = dir + "/t" + std::to_string(threads);
    const int rc = RunShell(Binary() + " run formation_swarm_100 -q --set duration=1.5 --threads " +
                                std::to_string(threads) + " --out " + out,
                            dir + "/log.txt");
    ASSERT_EQ(rc, 0) << ReadText(dir + "/log.txt");
    const std::string c = ReadText(out + "/timeseries.csv"), s = ReadText(out + "/summary.json");
    ASSERT_GT(c.size(), 100000u);
    if (threads == 1) {
      csv = c, summary = s;
      continue;
    }
    EXPECT_TRUE(c == csv) << "timeseries.csv differs with --threads " << threads;
    EXPECT_TRUE(s == summary) << "summary.json differs with --threads " << threads;
  }
  EXPECT_NE(RunShell(Binary() + " run formation_traj2 -q --threads 0 --out " + dir + "/bad",
                     dir + "/bad.txt"),
            0);
  EXPECT_NE(ReadText(dir + "/bad.txt").find("--threads"), std::string::npos) << ReadText(dir + "/bad.txt");
}

}  // namespace
}  // namespace formsim::app
