// Bounded inputs (issue 21): every file formsim reads goes through ReadBoundedFile (regular
// files of at most 4 MiB), every YAML text through the alias and depth limits, and the sweep
// definition refuses what it cannot run before building any of it. Each refusal is checked by
// its message (the file named, the line of the alias), never by a clock.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>

#include "sim/core/bounded_file.hpp"
#include "sim/core/yaml_limits.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/session/session_record.hpp"
#include "sim/study/sweep_spec.hpp"
#include "sim/study/sweep_store.hpp"
#include "sweep_test_util.hpp"
#include "test_kind.hpp"
#include "tests/support/invalid_fixtures.hpp"

namespace formsim::sim {
namespace {

namespace fs = std::filesystem;

std::string BoundedDir(const std::string& name) {
  const fs::path p = fs::path(FORMSIM_BINARY_DIR) / "test_out" / "bounded" / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

std::string Write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string RefusalOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(accepted)";
}

bool Has(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

std::string Fixture(const std::string& name) {
  return std::string(FORMSIM_SOURCE_DIR) + "/tests/fixtures/invalid/" + name;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ---- the one reader ----

TEST(BoundedFile, ReadsARegularFileWhole) {
  const std::string path = Write(BoundedDir("plain") + "/a.txt", std::string("abc\0def", 7));
  EXPECT_EQ(ReadBoundedFile(path), std::string("abc\0def", 7));
  EXPECT_EQ(ReadBoundedFile(path, 7).size(), 7u);
  EXPECT_EQ(ReadBoundedFile(Write(BoundedDir("empty") + "/e.txt", "")), "");
}

TEST(BoundedFile, RefusesDevicesFifosFoldersMissingAndLargeFiles) {
  const std::string dir = BoundedDir("refuse");
  EXPECT_EQ(RefusalOf([] { ReadBoundedFile("/dev/zero"); }),
            "/dev/zero: is not a regular file (a device)");
  EXPECT_EQ(RefusalOf([&] { ReadBoundedFile(dir); }), dir + ": is not a regular file (a folder)");
  // A FIFO with no writer: refused at once, never waited on.
  const std::string fifo = dir + "/fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(RefusalOf([&] { ReadBoundedFile(fifo); }), fifo + ": is not a regular file (a FIFO)");
  EXPECT_TRUE(Has(RefusalOf([&] { ReadBoundedFile(dir + "/missing.yaml"); }),
                  dir + "/missing.yaml: cannot open the file: No such file or directory"));
  const std::string big = Write(dir + "/big.txt", std::string(101, 'x'));
  EXPECT_EQ(RefusalOf([&] { ReadBoundedFile(big, 100); }),
            big + ": is larger than 100 bytes (101 bytes), the most formsim reads from one file");
  EXPECT_EQ(ReadBoundedFile(big, 101).size(), 101u);
  EXPECT_EQ(ByteSizeText(kMaxTextFileBytes), "4 MiB");
}

TEST(BoundedFile, ScenarioLessonSessionAndYamlReadersUseIt) {
  const std::string dir = BoundedDir("readers");
  // The scenario (and lesson) loader.
  EXPECT_EQ(RefusalOf([] { ScenarioSource::FromFile("/dev/zero"); }),
            "/dev/zero: is not a regular file (a device)");
  EXPECT_EQ(RefusalOf([&] { ScenarioSource::FromFile(dir); }),
            dir + ": is not a regular file (a folder)");
  // A scenario one byte over the limit: refused with the limit, never parsed.
  const std::string huge =
      Write(dir + "/huge.yaml", "type: x\n# " + std::string(kMaxTextFileBytes, 'x') + "\n");
  const std::string e = RefusalOf([&] { LoadExperiment(huge); });
  EXPECT_EQ(e.rfind(huge + ": is larger than 4 MiB (", 0), 0u) << e;
  EXPECT_EQ(RefusalOf([&] { LoadYamlFile(huge); }), e);
  // Session records (formsim replay) and run histories.
  EXPECT_EQ(RefusalOf([] { SessionRecord::Read("/dev/zero"); }),
            "/dev/zero: the session file is not a regular file (a device)");
  // A value of --set or of an edit is bounded too.
  const std::string long_value = "[" + std::string(70000, '1') + "]";
  const std::string v = RefusalOf([&] {
    ParseScenario(ScenarioSource::FromText(testkind::kScenario, "c.yaml", ""),
                  {{"v", long_value, "--set", -1}});
  });
  EXPECT_TRUE(Has(v,
                  "key 'v': the value is 70002 characters long; a value of --set or an edit "
                  "takes at most 65536"))
      << v.substr(0, 300);
}

// ---- YAML aliases ----

TEST(YamlLimits, InvalidFixturesNameTheLineOfTheAlias) {
  // input_billion_laughs.yaml, input_alias_cycle.yaml, input_alias_deep.yaml: each refused with
  // its "# expect:" text at file:line of the alias.
  EXPECT_GE(formsim::testing::CheckInvalidFixtures("input_"), 3);
  const std::string file = Fixture("input_billion_laughs.yaml");
  const std::string e = RefusalOf([&] { LoadExperiment(file); });
  EXPECT_EQ(e.rfind(file + ":12:8: alias '*f' makes the document expand to more than 1000000 "
                           "nodes",
                    0),
            0u)
      << e;
}

TEST(YamlLimits, CountsAliasesAsCopiesWithoutExpandingThem) {
  // The count of the billion laughs is exact (9^9 "lol"s and the lists holding them), found in
  // one pass over its events: nothing is expanded.
  const std::string text = ReadAll(Fixture("input_billion_laughs.yaml"));
  std::size_t expect = 1 + 2 * 2;  // the root map, type and duration (keys and values)
  std::size_t level = 10;          // a: the list and its nine strings
  for (int k = 0; k < 9; ++k) {
    expect += 1 + level;  // the key and the anchored list
    level = 1 + 9 * level;
  }
  EXPECT_EQ(ExpandedYamlNodes(text, std::numeric_limits<std::size_t>::max() / 2), expect);
  EXPECT_GT(expect, std::size_t{387420489});  // 9^9
  // Aliases within the limits load, and mean what they say.
  const YAML::Node ok = LoadYamlText("a: &a [1, 2]\nb: [*a, *a]\n", "ok.yaml");
  EXPECT_EQ(ok["b"][1][1].as<int>(), 2);
  EXPECT_EQ(ExpandedYamlNodes("a: &a [1, 2]\nb: [*a, *a]\n"), 1 + 2 + 3 + 1 + 2 * 3u);
  // The limit is on the expanded count: 990,003 nodes load, 1,000,003 are refused.
  std::string just = "l: &l [";
  for (int i = 0; i < 9998; ++i) just += "0,";
  just += "0]\n";  // the list and its 9999 numbers: 10,000 nodes
  just += "m: [*l";
  for (int i = 0; i < 97; ++i) just += ",*l";
  just += "]\n";  // 98 copies
  EXPECT_EQ(ExpandedYamlNodes(just), 1 + 1 + 10000 + 1 + 1 + 98 * 10000u);
  EXPECT_NO_THROW(LoadYamlText(just, "just.yaml"));
  const std::string over = just.substr(0, just.size() - 2) + ",*l]\n";
  EXPECT_TRUE(Has(RefusalOf([&] { LoadYamlText(over, "over.yaml"); }), "over.yaml:2:"));
}

TEST(YamlLimits, ABillionLaughsAppendedToASessionIsRefusedByReplay) {
  // A session file as `formsim gui --session` writes it, then the block appended.
  SessionRecord record;
  SessionEvent load;
  load.kind = SessionEvent::Kind::kLoad;
  load.source = std::make_shared<ScenarioSource>(
      ScenarioSource::FromText(testkind::kScenario, "circle.yaml", ""));
  record.Add(load);
  std::string text = record.ToYaml(10);
  const int first = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  const std::string laughs = ReadAll(Fixture("input_billion_laughs.yaml"));
  text += laughs.substr(laughs.find("\na:") + 1);  // the anchors a ... i only
  const std::string path = Write(BoundedDir("session") + "/laughs.session.yaml", text);
  const std::string e = RefusalOf([&] { SessionRecord::Read(path); });
  // Line of the '*f' alias: the 6th appended line.
  EXPECT_EQ(e.rfind(path + ":" + std::to_string(first + 6) +
                        ":8: alias '*f' makes the "
                        "document expand",
                    0),
            0u)
      << e;
}

// ---- sweeps ----

using sweeptest::Circle;

TEST(SweepLimits, TooManyRunsAreRefusedFromTheSpecsAlone) {
  // 10^18 runs: counted, not enumerated, and refused with the count.
  const std::string e = RefusalOf([] {
    DefineSweep(Circle(), {}, {"v=0.1:1:1000000", "omega=0.1:0.3:1000000", "sigma=0.1:0.3:1000000"},
                {});
  });
  EXPECT_EQ(e,
            "the sweep has 1000000000000000000 runs (points x seeds), more than 100000; vary "
            "fewer values, or allow it with --max-runs N (N <= 10000000)");
  const ParsedScenario base = ParseScenario(Circle(), {});
  EXPECT_EQ(CountSweepRuns(base.params, {"v=0.1:1:1000000"}, 1), 1000000u);
  // The count from the specs is the count of the sweep built.
  const std::vector<std::string> mixed = {"v=1,2,3", "drive.mode=all", "omega=log:0.1:1:4"};
  EXPECT_EQ(CountSweepRuns(base.params, mixed, 5),
            DefineSweep(Circle(), {}, mixed, {1, 2, 3, 4, 5}).runs());
  EXPECT_EQ(CountSweepRuns(base.params, mixed, 5),
            3u * base.params.Find("drive.mode")->choices.size() * 4u * 5u);
  EXPECT_EQ(CountSweepRuns(base.params, {"v=random:7", "omega=random:7"}, 2), 14u);
  // Saturates instead of overflowing.
  std::vector<std::string> many(4, "v=0.1:1:1000000");
  EXPECT_EQ(CountSweepRuns(base.params, many, 1000000), std::numeric_limits<std::size_t>::max());
  EXPECT_TRUE(Has(RefusalOf([&] { DefineSweep(Circle(), {}, many, {}); }),
                  "the sweep has more than 18446744073709551615 runs"));
  // 200,000 runs: refused by default, planned when allowed.
  EXPECT_TRUE(Has(RefusalOf([] { DefineSweep(Circle(), {}, {"v=0.1:1:200000"}, {}); }),
                  "the sweep has 200000 runs"));
  const SweepDefinition big = DefineSweep(Circle(), {}, {"v=0.1:1:200000"}, {}, 1, 200000);
  EXPECT_EQ(big.runs(), 200000u);
  // The hard cap stays whatever is allowed.
  EXPECT_TRUE(Has(RefusalOf([] {
                    DefineSweep(Circle(), {}, {"v=0.1:1:1000000"},
                                {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, 1, 1u << 30);
                  }),
                  "more than 10000000, the most formsim plans"));
}

TEST(SweepLimits, EmptySeedsAreRefused) {
  EXPECT_EQ(RefusalOf([] { ParseSeeds(""); }),
            "--seeds '': no seeds (write 1..20 or 1,2,5, or leave --seeds out for the scenario's "
            "seed)");
  EXPECT_TRUE(Has(RefusalOf([] { ParseSeeds(" "); }), "no seeds"));
}

TEST(SweepLimits, NonFiniteMetricsInRunFilesAreRefusedNamingTheFile) {
  const std::string dir = BoundedDir("sweep_nan");
  const SweepDefinition def = DefineSweep(Circle(), {}, {"v=1,2"}, {1});
  WriteManifest(dir, def);
  SweepRecord rec;
  rec.run = 1;
  rec.status = "ok";
  rec.metrics = {{"a", 0.5}, {"none", std::nan("")}};
  WriteRecord(dir, def, rec);
  // As written: the value the run could not compute is "-", read back as NaN.
  const std::string path = RecordPath(dir, 1);
  EXPECT_TRUE(Has(ReadAll(path), "m none -\n"));
  ASSERT_EQ(ReadRecords(dir, def).size(), 1u);
  EXPECT_TRUE(std::isnan(ReadRecords(dir, def)[0].metrics[1].second));
  // nan, inf or 1e999 edited in: refused, naming the file and line.
  for (const char* bad : {"nan", "inf", "-inf", "NaN", "1e999"}) {
    std::string text = ReadAll(path);
    text.replace(text.find("m a 0.5"), 7, std::string("m a ") + bad);
    Write(path, text);
    EXPECT_EQ(RefusalOf([&] { ReadRecords(dir, def); }),
              path + ":6: metric 'a': '" + bad +
                  "' is not a finite number (a run file holds finite numbers, or '-' for a value "
                  "the run could not compute; was it edited?)")
        << bad;
    WriteRecord(dir, def, rec);
  }
  // A run file that is not a regular file is refused by name too.
  fs::remove(path);
  fs::create_directory(path);
  EXPECT_EQ(RefusalOf([&] { ReadRecords(dir, def); }), path + ": is not a regular file (a folder)");
}

}  // namespace
}  // namespace formsim::sim
