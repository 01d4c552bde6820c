// Never lose a run, at the outputs: an export that fails (a full disk, /dev/full, ffmpeg dying)
// never costs the simulation's results; a results file that cannot be written completely is
// never left truncated under its name; Ctrl-C or SIGTERM writes what was simulated. Each test
// runs the built formsim binary as a user would.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "app/export/video_writer.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;
using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

bool IsCharDevice(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

int CsvLines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) ++n;
  return n;
}

using testing::AnyTmp;

TEST(OutputFaults, SnapshotToAFullDeviceKeepsTheResults) {
  if (!IsCharDevice("/dev/full")) GTEST_SKIP() << "/dev/full is not the full device here";
  const std::string dir = TempDir("fault_devfull");
  // The snapshot's format follows its extension: a .png name that is the full device.
  fs::create_symlink("/dev/full", dir + "/full.png");
  const int rc = RunShell("env -u DISPLAY " + Binary() +
                              " run formation_traj2 --set duration=0.5 -q --out " + dir +
                              "/out --snapshot " + dir + "/full.png",
                          dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  EXPECT_EQ(rc, 4) << log;
  EXPECT_NE(log.find("full.png"), std::string::npos) << log;
  EXPECT_NE(log.find("the results were written"), std::string::npos) << log;
  EXPECT_EQ(CsvLines(dir + "/out/timeseries.csv"), 52);  // header + 51 rows
  EXPECT_NE(ReadText(dir + "/out/summary.json").find("\"status\": \"completed\""), std::string::npos);
  EXPECT_TRUE(IsCharDevice("/dev/full")) << "the device must never be replaced by a file";
}

TEST(OutputFaults, ACsvThatDoesNotFitIsNeverLeftTruncated) {
  const std::string dir = TempDir("fault_csv_full");
  // RLIMIT_FSIZE makes every write past 40 KiB fail (EFBIG), as a full disk would.
  const int rc = RunShell("bash -c \"trap '' XFSZ; ulimit -f 40; exec " + Binary() +
                              " run formation_cascade7 --set duration=30 -q --out " + dir + "/out\"",
                          dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  EXPECT_EQ(rc, 2) << log;
  EXPECT_NE(log.find("timeseries.csv"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir + "/out/timeseries.csv")) << "a truncated CSV must not be kept";
  EXPECT_FALSE(AnyTmp(dir + "/out")) << "no temporary file may be left";
  EXPECT_TRUE(fs::exists(dir + "/out/summary.json")) << "the summary still fits and is written";
}

TEST(OutputFaults, FramesOnAFullDiskStopButTheRunAndItsResultsGoOn) {
  const std::string dir = TempDir("fault_frames_full");
  const std::string mnt = dir + "/tiny";
  fs::create_directories(mnt);
  if (RunShell("mount -t tmpfs -o size=256k tmpfs " + mnt, dir + "/mount.txt") != 0)
    GTEST_SKIP() << "cannot mount a small tmpfs here: " << ReadText(dir + "/mount.txt");
  const int rc = RunShell("env -u DISPLAY " + Binary() +
                              " run formation_traj2 --set duration=3 -q --out " + dir +
                              "/out --frames " + mnt + "/frames --fps 10",
                          dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  const bool leftovers = AnyTmp(mnt);
  int frames = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(mnt + "/frames")) ++frames;
  RunShell("umount " + mnt, dir + "/umount.txt");
  EXPECT_EQ(rc, 4) << log;
  EXPECT_NE(log.find("frames stopped"), std::string::npos) << log;
  EXPECT_GT(frames, 0);
  EXPECT_LT(frames, 30);
  EXPECT_FALSE(leftovers) << "a partial PNG was left";
  EXPECT_EQ(CsvLines(dir + "/out/timeseries.csv"), 302) << "the run went on to its end";
}

TEST(OutputFaults, FfmpegDyingRemovesTheVideoAndKeepsTheResults) {
  if (FindOnPath("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg not installed";
  const std::string dir = TempDir("fault_ffmpeg");
  // A stand-in ffmpeg that takes a few frames and dies.
  fs::create_directories(dir + "/bin");
  std::ofstream(dir + "/bin/ffmpeg") << "#!/bin/sh\nhead -c 8000000 >/dev/null\n"
                                        "echo 'ffmpeg: simulated crash' >&2\nexit 1\n";
  fs::permissions(dir + "/bin/ffmpeg", fs::perms::owner_all);
  const int rc = RunShell("env -u DISPLAY PATH=" + dir + "/bin:$PATH " + Binary() +
                              " run formation_traj2 --set duration=3 -q --out " + dir +
                              "/out --video " + dir + "/out/v.mp4 --size 640x360",
                          dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  EXPECT_EQ(rc, 4) << log;
  EXPECT_NE(log.find("ffmpeg"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir + "/out/v.mp4")) << "a broken video must not be left behind";
  EXPECT_EQ(CsvLines(dir + "/out/timeseries.csv"), 302);
}

TEST(OutputFaults, SigtermWritesWhatWasSimulatedAndMarksItInterrupted) {
  const std::string dir = TempDir("fault_sigterm");
  const int rc = RunShell("env -u DISPLAY " + Binary() +
                              " run formation_cascade7 --set duration=100000 -q --out " + dir +
                              "/out & pid=$!; sleep 1.5; kill -TERM $pid; wait $pid",
                          dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  EXPECT_EQ(rc, 143) << log;
  const std::string summary = ReadText(dir + "/out/summary.json");
  EXPECT_NE(summary.find("\"status\": \"interrupted\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("SIGTERM"), std::string::npos);
  // Every recorded row is in the CSV: steps / record_every + 1 rows.
  const auto steps_pos = summary.find("\"steps\": ");
  ASSERT_NE(steps_pos, std::string::npos);
  const long steps = std::stol(summary.substr(steps_pos + 9));
  EXPECT_GT(steps, 10);
  EXPECT_EQ(CsvLines(dir + "/out/timeseries.csv"), steps + 2);
}

}  // namespace
}  // namespace formsim::app
