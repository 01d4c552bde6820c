// formsim sweep, sweep collect and tune end to end (the built binary on shipped scenarios,
// shortened), and their figures checked on pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "app/export/study_figures.hpp"
#include "app/export/tune_figures.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "sim/core/number_format.hpp"
#include "sim/study/sweep.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;
using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

// A short sweep of the demo scenario: 3 x 2 points, 2 seeds.
const std::string kSweep =
    " sweep formation_traj2_ukf --set duration=2 --vary robots.R2.follow.k_phi=0.05,0.1,0.2"
    " --vary robots.R2.follow.estimator=raw,ukf --seeds 1..2"
    " --metric links.R1-R2.max_abs_error_after_settle.phi";
const char* kRanking = "ranking_links.R1-R2.max_abs_error_after_settle.phi.txt";
const char* kPlot = "plot_links.R1-R2.max_abs_error_after_settle.phi.png";

using testing::Formsim;

void ExpectSameStudyTables(const std::string& a, const std::string& b) {
  for (const char* f : {"runs.csv", "aggregate.csv", kRanking}) {
    const std::string ta = ReadText(a + "/" + f), tb = ReadText(b + "/" + f);
    EXPECT_FALSE(ta.empty()) << a << "/" << f;
    EXPECT_EQ(ta, tb) << f << " differs between " << a << " and " << b;
  }
}

std::size_t CountLines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',')
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

// summary.json's `results` flattened to dotted paths -> number text (a parser just big enough
// for the summaries formsim writes).
void Flatten(const std::string& j, std::size_t& i, const std::string& path,
             std::map<std::string, std::string>& out) {
  auto ws = [&] {
    while (i < j.size() && std::isspace(static_cast<unsigned char>(j[i]))) ++i;
  };
  auto str = [&] {
    std::string s;
    ++i;
    while (j[i] != '"') {
      if (j[i] == '\\') ++i;
      s += j[i++];
    }
    ++i;
    return s;
  };
  ws();
  if (j[i] == '{') {
    ++i;
    for (;;) {
      ws();
      if (j[i] == '}') {
        ++i;
        return;
      }
      const std::string k = str();
      ws();
      ++i;  // ':'
      Flatten(j, i, path.empty() ? k : path + "." + k, out);
      ws();
      if (j[i] == ',') ++i;
    }
  }
  if (j[i] == '[') {  // not in results; skipped
    int depth = 0;
    do {
      if (j[i] == '[') ++depth;
      if (j[i] == ']') --depth;
      ++i;
    } while (depth > 0);
    return;
  }
  if (j[i] == '"') {
    str();
    return;
  }
  const std::size_t start = i;
  while (i < j.size() && j[i] != ',' && j[i] != '}' &&
         !std::isspace(static_cast<unsigned char>(j[i])))
    ++i;
  out[path] = j.substr(start, i - start);
}

TEST(SweepCli, JobsOneAndTwoWriteTheSameBytesAndEveryRunIsFormsimRun) {
  const std::string a = TempDir("sweep_j1"), b = TempDir("sweep_j2");
  ASSERT_EQ(Formsim(kSweep + " --jobs 1 -q --out " + a, a + ".log"), 0) << ReadText(a + ".log");
  ASSERT_EQ(Formsim(kSweep + " --jobs 2 -q --out " + b, b + ".log"), 0) << ReadText(b + ".log");
  ExpectSameStudyTables(a, b);
  // -q prints nothing of its own (a sanitizer build may add its leak-suppression statistics).
  EXPECT_EQ(ReadText(a + ".log").find("sweep of"), std::string::npos);
  EXPECT_EQ(ReadText(a + ".log").find("wrote"), std::string::npos);
  EXPECT_GT(fs::file_size(a + "/" + kPlot), 10000u);
  const std::string runs = ReadText(a + "/runs.csv");
  EXPECT_EQ(CountLines(runs), 13u);
  EXPECT_EQ(CountLines(ReadText(a + "/aggregate.csv")), 7u);

  // Run 7 (k_phi 0.1, ukf, seed 2) is exactly `formsim run` with those values.
  const std::string r = TempDir("sweep_run7");
  ASSERT_EQ(Formsim("run formation_traj2_ukf -q --set duration=2 --set robots.R2.follow.k_phi=0.1 "
                    "--set robots.R2.follow.estimator=ukf --seed 2 --out " +
                        r,
                    r + ".log"),
            0);
  const std::string json = ReadText(r + "/summary.json");
  std::size_t at = json.find("\"results\"");
  ASSERT_NE(at, std::string::npos);
  at = json.find(':', at) + 1;
  std::map<std::string, std::string> results;
  Flatten(json, at, "", results);
  std::vector<std::string> lines;
  std::stringstream ss(runs);
  for (std::string l; std::getline(ss, l);) lines.push_back(l);
  const std::vector<std::string> head = SplitCsvLine(lines[0]), row = SplitCsvLine(lines[8]);
  ASSERT_EQ(row[0], "7");
  EXPECT_EQ(row[1] + " " + row[2] + " " + row[3], "0.1 ukf 2");
  int compared = 0, settings = 0;
  for (std::size_t c = 4; c + 2 < head.size(); ++c) {
    // Settings (control_period ...) are summary.json results under the name after "settings.".
    const bool setting = head[c].rfind("settings.", 0) == 0;
    if (setting) ++settings;
    const auto it = results.find(setting ? head[c].substr(9) : head[c]);
    ASSERT_NE(it, results.end()) << head[c];
    // summary.json writes true/false for flags, the tables 1/0.
    const std::string want = it->second == "true" ? "1" : it->second == "false" ? "0" : it->second;
    EXPECT_EQ(row[c], want) << head[c];
    ++compared;
  }
  EXPECT_GT(compared, 40);
  EXPECT_EQ(settings, 2) << "control_period and settle_time";
  EXPECT_EQ(row[head.size() - 2], "completed");
}

TEST(SweepCli, ShardsCollectToTheSameBytesAndMissingRunsAreNamed) {
  const std::string whole = TempDir("sweep_whole"), s1 = TempDir("sweep_s1"),
                    s2 = TempDir("sweep_s2"), merged = TempDir("sweep_merged");
  ASSERT_EQ(Formsim(kSweep + " -q --out " + whole, whole + ".log"), 0);
  ASSERT_EQ(Formsim(kSweep + " -q --shard 1/2 --out " + s1, s1 + ".log"), 0);
  EXPECT_EQ(Formsim("sweep collect " + s1 + " --out " + merged, merged + ".log"), 2);
  EXPECT_NE(
      ReadText(merged + ".log").find("the folders hold 6 of 12 runs (missing: 1, 3, 5, 7, 9, 11)"),
      std::string::npos)
      << ReadText(merged + ".log");
  ASSERT_EQ(Formsim(kSweep + " -q --shard 2/2 --out " + s2, s2 + ".log"), 0);
  ASSERT_EQ(Formsim("sweep collect " + s1 + " " + s2 + " --out " + merged +
                        " --metric links.R1-R2.max_abs_error_after_settle.phi -q",
                    merged + ".log"),
            0)
      << ReadText(merged + ".log");
  ExpectSameStudyTables(whole, merged);
  // Shards of another sweep are refused.
  const std::string other = TempDir("sweep_other");
  ASSERT_EQ(Formsim("sweep formation_traj2_ukf --set duration=1 -q --out " + other, other + ".log"),
            0);
  EXPECT_EQ(Formsim("sweep collect " + s1 + " " + other + " --out " + TempDir("sweep_bad"),
                    other + ".log2"),
            2);
  EXPECT_NE(ReadText(other + ".log2").find("holds another sweep"), std::string::npos);
}

TEST(SweepCli, ResumeRunsOnlyWhatIsMissingAndJobLinesRecordOnce) {
  const std::string whole = TempDir("sweep_ref"), d = TempDir("sweep_resume");
  ASSERT_EQ(Formsim(kSweep + " -q --out " + whole, whole + ".log"), 0);
  ASSERT_EQ(Formsim(kSweep + " -q --out " + d, d + ".log"), 0);
  for (const char* r : {"000000.run", "000005.run"}) fs::remove(d + "/runs/" + r);
  // What a power cut can leave of a record written but not yet synced: it runs again.
  const std::string cut = ReadText(d + "/runs/000011.run");
  std::ofstream(d + "/runs/000011.run", std::ios::binary | std::ios::trunc)
      << cut.substr(0, cut.size() / 2);
  fs::remove(d + "/runs.csv");
  EXPECT_EQ(Formsim(kSweep + " --out " + d, d + ".log"), 2);
  EXPECT_NE(ReadText(d + ".log").find("holds a sweep already (10 runs recorded); add --resume"),
            std::string::npos)
      << ReadText(d + ".log");
  EXPECT_EQ(Formsim("sweep formation_traj2_ukf --vary robots.R2.follow.k_l=0.1,0.2 --out " + d,
                    d + ".log"),
            2);
  EXPECT_NE(ReadText(d + ".log").find("holds another sweep: the varied keys differ"),
            std::string::npos);
  ASSERT_EQ(Formsim(kSweep + " --resume --out " + d, d + ".log"), 0);
  EXPECT_NE(ReadText(d + ".log").find("12 runs, 9 recorded already"), std::string::npos)
      << ReadText(d + ".log");
  EXPECT_NE(ReadText(d + ".log").find("000011.run was cut short (a power cut?); it runs again"),
            std::string::npos);
  EXPECT_NE(ReadText(d + ".log").find("\n3 runs in "), std::string::npos) << ReadText(d + ".log");
  ExpectSameStudyTables(whole, d);

  // Job lines: one per run not yet recorded; each records its run once.
  const std::string j = TempDir("sweep_jobs");
  ASSERT_EQ(Formsim(kSweep + " --print-jobs --out " + j, j + ".txt"), 0);
  const std::string jobs = ReadText(j + ".txt");
  ASSERT_EQ(CountLines(jobs), 12u);
  EXPECT_EQ(jobs.find(Binary() + " sweep " +
                      fs::canonical(testing::Scenario("formation_traj2_ukf")).string()),
            0u)
      << jobs;
  const std::string first = jobs.substr(0, jobs.find('\n'));
  ASSERT_EQ(RunShell(first, j + ".log"), 0) << ReadText(j + ".log");
  ASSERT_EQ(RunShell(first + " --quiet=false", j + ".log"), 0);
  EXPECT_NE(ReadText(j + ".log").find("run 0 is recorded already"), std::string::npos)
      << ReadText(j + ".log");
  ASSERT_EQ(Formsim(kSweep + " --print-jobs --out " + j, j + ".txt"), 0);
  EXPECT_EQ(CountLines(ReadText(j + ".txt")), 11u);
}

TEST(SweepCli, InterruptedSweepsKeepEveryFinishedRunAndResume) {
  const std::string ref = TempDir("sweep_int_ref"), d = TempDir("sweep_int");
  const std::string big =
      " sweep formation_traj2_ukf --set duration=3 --vary robots.R2.follow.k_phi=0.02:0.4:12 "
      "--seeds 1..4 -j2 --no-figures";
  ASSERT_EQ(Formsim(big + " -q --out " + ref, ref + ".log"), 0);
  // SIGINT once two records are on disk (a fixed sleep could outlast the sweep on a loaded machine).
  const int rc =
      RunShell(testing::SignalOnceRecorded(Binary() + big + " -q --out " + d, d, 2, "-INT"),
               d + ".log");
  EXPECT_EQ(rc, 130) << ReadText(d + ".log");
  EXPECT_NE(ReadText(d + ".log").find("add --resume to finish it"), std::string::npos);
  for (const auto& e : fs::directory_iterator(d + "/runs"))
    EXPECT_EQ(e.path().extension(), ".run") << "no half-written record";
  ASSERT_EQ(Formsim(big + " -q --resume --out " + d, d + ".log"), 0) << ReadText(d + ".log");
  EXPECT_EQ(ReadText(ref + "/runs.csv"), ReadText(d + "/runs.csv"));
  EXPECT_EQ(ReadText(ref + "/aggregate.csv"), ReadText(d + "/aggregate.csv"));
}

TEST(SweepCli, FailedRunsAreRecordedAndTheSweepGoesOn) {
  // l2_des = 0.9 cannot close the triangle with l_des = 0.3 and R1-R2 at 0.3: a scenario error.
  const std::string d = TempDir("sweep_fail");
  ASSERT_EQ(Formsim("sweep formation_traj2_ukf --set duration=1 --vary "
                    "robots.R3.follow.l2_des=0.3,0.9 -q --out " +
                        d,
                    d + ".log"),
            0)
      << ReadText(d + ".log");
  const std::string runs = ReadText(d + "/runs.csv");
  EXPECT_NE(runs.find("\n0,0.3,1,"), std::string::npos);
  EXPECT_NE(runs.find(",completed,\n"), std::string::npos);
  const std::size_t row = runs.find("\n1,0.9,1,");
  ASSERT_NE(row, std::string::npos) << runs;
  EXPECT_NE(runs.find(",error,", row), std::string::npos) << runs;
  EXPECT_NE(runs.find("robots.R3.follow.l2_des=0.9", row), std::string::npos) << runs;
  EXPECT_NE(ReadText(d + "/aggregate.csv").find("\n1,0.9,1,1,"), std::string::npos)
      << "runs 1, failed 1";
}

TEST(SweepCli, ProgressBarOnATerminalOnly) {
  const std::string d = TempDir("sweep_bar");
  const std::string cmd =
      Binary() + " sweep formation_traj2_ukf --set duration=1 --seeds 1..4 --no-figures --out ";
  // `script` gives the command a terminal.
  ASSERT_EQ(RunShell("script -qec '" + cmd + d + "/tty' /dev/null", d + "/tty.log"), 0);
  EXPECT_NE(ReadText(d + "/tty.log").find("4/4 runs, 0 failed, 0:00 left"), std::string::npos)
      << ReadText(d + "/tty.log");
  ASSERT_EQ(RunShell(cmd + d + "/pipe", d + "/pipe.log"), 0);
  EXPECT_EQ(ReadText(d + "/pipe.log").find('\r'), std::string::npos)
      << "no bar when not a terminal";
  ASSERT_EQ(RunShell("script -qec '" + cmd + d + "/quiet -q' /dev/null", d + "/quiet.log"), 0);
  EXPECT_EQ(ReadText(d + "/quiet.log").find("runs,"), std::string::npos) << "no bar under -q";
}

TEST(SweepCli, BadInputNamesTheFlag) {
  const std::string d = TempDir("sweep_bad_input");
  EXPECT_EQ(Formsim("sweep formation_traj2_ukf --vary robots.R2.follow.k_l=-1,0.2 --out " + d,
                    d + ".log"),
            2);
  EXPECT_NE(ReadText(d + ".log")
                .find("--vary robots.R2.follow.k_l=-1,0.2: key 'robots.R2.follow.k_l': value '-1': "
                      "must be > 0"),
            std::string::npos)
      << ReadText(d + ".log");
  EXPECT_EQ(Formsim("sweep formation_traj2_ukf --seeds 5..1 --out " + d, d + ".log"), 2);
  EXPECT_NE(ReadText(d + ".log").find("--seeds '5..1'"), std::string::npos);
  EXPECT_EQ(Formsim("sweep formation_traj2_ukf --shard 3/2 --out " + d, d + ".log"), 2);
  EXPECT_NE(ReadText(d + ".log").find("--shard '3/2'"), std::string::npos);
  EXPECT_EQ(
      Formsim("sweep formation_traj2_ukf --set duration=1 --metric links.R1-R2.nope -q --out " + d +
                  "/m",
              d + ".log"),
      2);
  EXPECT_NE(ReadText(d + ".log").find("--metric 'links.R1-R2.nope': no such metric"),
            std::string::npos);
  EXPECT_FALSE(ReadText(d + "/m/runs.csv").empty())
      << "the tables are written before the metric is looked up";
  // --band: refused before anything runs, naming the flag and what it accepts.
  for (const std::string& cmd : {"sweep formation_traj2_ukf --band 2sigma --out " + d + "/b",
                                "sweep collect " + d + "/m --band 2sigma --out " + d + "/b"}) {
    EXPECT_EQ(Formsim(cmd, d + ".log"), 2) << cmd;
    EXPECT_NE(ReadText(d + ".log").find("--band '2sigma': expected sd"), std::string::npos)
        << ReadText(d + ".log");
    EXPECT_NE(ReadText(d + ".log").find("ci95"), std::string::npos);
    EXPECT_NE(ReadText(d + ".log").find("minmax"), std::string::npos);
    EXPECT_FALSE(fs::exists(d + "/b")) << cmd << ": nothing is written before --band is checked";
  }
}

double Number(const std::string& s) {
  double v = NAN;
  sim::ParseFiniteDouble(s, &v);
  return v;
}

TEST(TuneCli, DeterministicAndBestYamlReproducesTheBestObjective) {
  const std::string tune =
      " tune formation_traj2_ukf --set duration=3 --param robots.R2.follow.k_l --param "
      "robots.R2.follow.k_phi:0.02:0.5"
      " --metric 'links.R1-R2.max_abs_error_after_settle.phi + "
      "0.5*links.R1-R2.max_abs_error_after_settle.l'"
      " --seeds 1..2 --budget 8 -q";
  const std::string a = TempDir("tune_a"), b = TempDir("tune_b");
  // --algorithm is the older name of --method.
  ASSERT_EQ(Formsim(tune + " -j1 --method bobyqa --out " + a, a + ".log"), 0)
      << ReadText(a + ".log");
  ASSERT_EQ(Formsim(tune + " -j2 --algorithm bobyqa --out " + b, b + ".log"), 0)
      << ReadText(b + ".log");
  for (const char* f : {"history.csv", "best.yaml"})
    EXPECT_EQ(ReadText(a + "/" + f), ReadText(b + "/" + f)) << f;
  EXPECT_GT(fs::file_size(a + "/convergence.png"), 5000u);
  const std::string history = ReadText(a + "/history.csv");
  EXPECT_EQ(CountLines(history), 9u);
  EXPECT_EQ(history.substr(0, history.find('\n')),
            "eval,stage,robots.R2.follow.k_l,robots.R2.follow.k_phi,objective,mean.links.R1-R2."
            "max_abs_error_after_settle.phi,"
            "mean.links.R1-R2.max_abs_error_after_settle.l,feasible,failed_runs,best_so_far,"
            "message");
  // The first evaluation is the scenario's own gains.
  EXPECT_NE(history.find("\n1,bobyqa,0.15,0.08,"), std::string::npos) << history;
  // The best objective: the last best_so_far.
  std::stringstream ss(history);
  std::string line, last;
  while (std::getline(ss, line)) last = line;
  const std::vector<std::string> f = SplitCsvLine(last);
  const double best = Number(f[9]);
  ASSERT_TRUE(std::isfinite(best));

  // best.yaml keeps the file's comments, loads, and gives that objective again on the same seeds.
  const std::string yaml = ReadText(a + "/best.yaml");
  EXPECT_EQ(yaml.rfind("# formsim tune: ", 0), 0u);
  EXPECT_NE(yaml.find("# Paper 000 (Han, Sun, Zhi 2015)"), std::string::npos);
  const std::string check = TempDir("tune_check");
  ASSERT_EQ(Formsim("sweep " + a + "/best.yaml --seeds 1..2 -q --no-figures --out " + check,
                    check + ".log"),
            0)
      << ReadText(check + ".log");
  std::stringstream agg(ReadText(check + "/aggregate.csv"));
  std::string h, row;
  std::getline(agg, h);
  std::getline(agg, row);
  const std::vector<std::string> head = SplitCsvLine(h), vals = SplitCsvLine(row);
  double phi = NAN, l = NAN;
  for (std::size_t c = 0; c < head.size(); ++c) {
    if (head[c] == "links.R1-R2.max_abs_error_after_settle.phi.mean") phi = Number(vals[c]);
    if (head[c] == "links.R1-R2.max_abs_error_after_settle.l.mean") l = Number(vals[c]);
  }
  EXPECT_EQ(1.0 * phi + 0.5 * l, best) << "best.yaml reproduces the best objective exactly";
}

TEST(TuneCli, BadInputNamesTheFlag) {
  const std::string d = TempDir("tune_bad");
  EXPECT_EQ(Formsim("tune formation_traj2_ukf --param robots.R2.follow.estimator --metric x "
                    "--method bobyqa --out " + d,
                    d + ".log"),
            2);
  EXPECT_NE(ReadText(d + ".log").find("--method bobyqa: integer and choice keys are searched by "
                                      "a global stage"),
            std::string::npos)
      << ReadText(d + ".log");
  EXPECT_EQ(
      Formsim("tune formation_traj2_ukf --param robots.R2.follow.k_l --metric 'a +' --out " + d,
              d + ".log"),
      2);
  EXPECT_NE(ReadText(d + ".log").find("--metric 'a +'"), std::string::npos);
  EXPECT_EQ(Formsim("tune formation_traj2_ukf --set duration=1 --param robots.R2.follow.k_l "
                    "--metric links.nope --method bobyqa --budget 3 --out " +
                        d,
                    d + ".log"),
            2);
  EXPECT_NE(ReadText(d + ".log").find("no metric 'links.nope'"), std::string::npos)
      << ReadText(d + ".log");
  EXPECT_EQ(Formsim("tune formation_traj2_ukf --param robots.R2.follow.k_l --metric x --algorithm "
                    "newton --out " +
                        d,
                    d + ".log"),
            2);
  EXPECT_NE(ReadText(d + ".log").find("--method 'newton': unknown method"), std::string::npos);
  // Refused before anything runs: a budget too small for the plan, held-out seeds that were
  // searched, a constraint on a setting rather than a result, a malformed constraint.
  const std::string base = "tune formation_traj2_ukf --set duration=1 --param robots.R2.follow.k_l ";
  EXPECT_EQ(Formsim(base + "--metric x --budget 5 --out " + d, d + ".log"), 2);
  EXPECT_NE(ReadText(d + ".log").find("--budget 5: too small for --method direct-l+bobyqa with 1 "
                                      "tunable (needs at least 7: 4 for direct-l, 3 for bobyqa)"),
            std::string::npos)
      << ReadText(d + ".log");
  EXPECT_EQ(Formsim(base + "--metric x --seeds 1..5 --holdout 4..9 --out " + d, d + ".log"), 2);
  EXPECT_NE(ReadText(d + ".log").find("--holdout: seeds 4, 5 are also in --seeds"),
            std::string::npos)
      << ReadText(d + ".log");
  EXPECT_EQ(Formsim(base + "--metric x --constraint 'links.R1-R2.rmse<0.1' --out " + d,
                    d + ".log"),
            2);
  EXPECT_NE(ReadText(d + ".log").find("--constraint 'links.R1-R2.rmse<0.1': no <= or >="),
            std::string::npos)
      << ReadText(d + ".log");
  EXPECT_EQ(Formsim("tune velocity_constant --set duration=2 --param "
                    "control.kp --metric robots.R_fused.control.linear_error "
                    "--constraint 'settle_time<=1' --method bobyqa --budget 3 --out " +
                        d,
                    d + ".log"),
            2);
  EXPECT_NE(ReadText(d + ".log").find(
                "--constraint: 'settle_time' is a setting the run ran with, not a result of it"),
            std::string::npos)
      << ReadText(d + ".log");
}

TEST(TuneCli, ConstraintsHoldoutAndNoFeasiblePoint) {
  // The scenario's k_l against the after-settle l error, with the phi error held at most at
  // its start value: best.yaml meets it, history.csv marks each point, the holdout is written.
  const std::string base =
      "tune formation_traj2_ukf --set duration=3 --param robots.R2.follow.k_l "
      "--metric links.R1-R2.max_abs_error_after_settle.l --seeds 1..2 --budget 10 -q ";
  const std::string a = TempDir("tune_constrained");
  ASSERT_EQ(Formsim(base + "--constraint 'links.R1-R2.max_abs_error_after_settle.phi<=0.05' "
                           "--holdout 3..5 --out " + a,
                    a + ".log"),
            0)
      << ReadText(a + ".log");
  const std::string history = ReadText(a + "/history.csv");
  EXPECT_NE(history.find(",feasible,"), std::string::npos);
  EXPECT_NE(history.find("\n1,direct-l,"), std::string::npos) << "the default plan" << history;
  EXPECT_NE(history.find(",bobyqa,"), std::string::npos) << "the polish" << history;
  EXPECT_NE(ReadText(a + "/best.yaml").find("subject to links.R1-R2.max_abs_error_after_settle."
                                            "phi<=0.05"),
            std::string::npos);
  const std::string validation = ReadText(a + "/validation.csv");
  EXPECT_EQ(validation.rfind("scenario,seed,objective_start,objective_best,difference,best_feasible"
                             "\nformation_traj2_ukf,3,",
                             0),
            0u)
      << validation;
  EXPECT_EQ(CountLines(validation), 7u) << "header, three seeds, mean and the interval";
  EXPECT_GT(fs::file_size(a + "/validation.png"), 5000u);
  EXPECT_FALSE(fs::exists(a + "/landscape.png")) << "one tuned key: no landscape";
  // A bound no point meets: no best.yaml, exit status 3, the closest point named.
  const std::string b = TempDir("tune_infeasible");
  EXPECT_EQ(Formsim(base + "--constraint 'links.R1-R2.max_abs_error_after_settle.phi<=0' --out " + b,
                    b + ".log"),
            3);
  EXPECT_FALSE(fs::exists(b + "/best.yaml"));
  EXPECT_NE(ReadText(b + ".log").find("no evaluation meets every --constraint"), std::string::npos)
      << ReadText(b + ".log");
  EXPECT_NE(ReadText(b + "/history.csv").find(",0,0,inf,"), std::string::npos)
      << "infeasible rows, no best so far";
}

TEST(TuneCli, KilledMidwayResumesToTheSameHistoryAndBestPoint) {
  const std::string tune =
      " tune formation_traj2_ukf --set duration=8 --param robots.R2.follow.k_l --param "
      "robots.R2.follow.k_phi --metric links.R1-R2.max_abs_error_after_settle.l --seeds 1..2 "
      "--method crs2+bobyqa --budget 40 -q -j1 --out ";
  const std::string a = TempDir("tune_whole"), b = TempDir("tune_killed");
  ASSERT_EQ(Formsim(tune + a, a + ".log"), 0) << ReadText(a + ".log");
  // kill -9 once history.csv holds 10 evaluations (header + 10 lines).
  const std::string h = b + "/history.csv";
  RunShell("(" + Binary() + tune + b + " & pid=$!; for i in $(seq 1 2400); do [ -f " + h +
               " ] && [ $(wc -l < " + h + ") -ge 11 ] && break; sleep 0.05; done; kill -KILL $pid; "
               "wait $pid)",
           b + ".log");
  const std::size_t kept = CountLines(ReadText(h));
  ASSERT_GE(kept, 11u) << ReadText(b + ".log");
  ASSERT_LT(kept, 41u) << "killed midway";
  EXPECT_FALSE(fs::exists(b + "/best.yaml"));
  // Without --resume the folder is refused; with it the tune ends as the whole one did.
  EXPECT_EQ(Formsim(tune + b, b + ".log"), 2);
  EXPECT_NE(ReadText(b + ".log").find("holds a tune already; add --resume"), std::string::npos);
  ASSERT_EQ(Formsim(tune + b + " --resume", b + ".log"), 0) << ReadText(b + ".log");
  for (const char* f : {"history.csv", "best.yaml", "tune.manifest"})
    EXPECT_EQ(ReadText(a + "/" + f), ReadText(b + "/" + f)) << f;
  EXPECT_GT(fs::file_size(a + "/landscape.png"), 5000u) << "two tuned keys: a landscape";
  // A resume with other settings is refused, naming what differs.
  EXPECT_EQ(Formsim(tune + b + " --resume --search-seed 2", b + ".log"), 2);
  EXPECT_NE(ReadText(b + ".log").find("holds another tune (it has 'search_seed 1', this one "
                                      "'search_seed 2')"),
            std::string::npos)
      << ReadText(b + ".log");
}

TEST(StudyCli, TitlesApplyToSweepTuneAndReproduceFiguresAndBadValuesAreRefused) {
  // A tune's figures with and without titles: the same data, other pixels.
  const std::string tune =
      "tune formation_traj2_ukf --set duration=2 --param robots.R2.follow.k_l "
      "--metric links.R1-R2.max_abs_error_after_settle.l --method bobyqa --budget 3 -q ";
  const std::string full = TempDir("titles_full"), none = TempDir("titles_none");
  ASSERT_EQ(Formsim(tune + "--titles full --out " + full, full + ".log"), 0)
      << ReadText(full + ".log");
  ASSERT_EQ(Formsim(tune + "--titles none --out " + none, none + ".log"), 0)
      << ReadText(none + ".log");
  EXPECT_EQ(ReadText(full + "/history.csv"), ReadText(none + "/history.csv"));
  EXPECT_NE(ReadText(full + "/convergence.png"), ReadText(none + "/convergence.png"));
  // The sweep's figure likewise.
  const std::string sweep =
      "sweep formation_traj2_ukf --set duration=2 --vary robots.R2.follow.k_l=0.1,0.3 "
      "--seeds 1 -q ";
  const std::string sf = TempDir("titles_sweep_full"), sn = TempDir("titles_sweep_none");
  ASSERT_EQ(Formsim(sweep + "--out " + sf, sf + ".log"), 0) << ReadText(sf + ".log");
  ASSERT_EQ(Formsim(sweep + "--titles none --out " + sn, sn + ".log"), 0) << ReadText(sn + ".log");
  std::size_t differing = 0;
  for (const auto& f : fs::directory_iterator(sf))
    if (f.path().extension() == ".png")
      differing += ReadText(f.path().string()) != ReadText(sn + "/" + f.path().filename().string());
  EXPECT_GT(differing, 0u);
  // A value not among full, short and none is refused before anything runs, by every command.
  const std::string bad = TempDir("titles_bad");
  for (const std::string& cmd :
       {tune + "--out " + bad, sweep + "--out " + bad, std::string("reproduce formation --out ") + bad}) {
    EXPECT_EQ(Formsim(cmd + " --titles long", bad + ".log"), 2) << cmd;
    EXPECT_NE(ReadText(bad + ".log").find("--titles 'long'"), std::string::npos)
        << cmd << ": " << ReadText(bad + ".log");
  }
}

TEST(TuneCli, SeveralScenariosFoldIntoOneObjectiveAndEachGetsItsBestYaml) {
  const std::string list = TempDir("tune_list") + ".txt";
  {
    std::ofstream f(list);
    f << "# the paper's trajectories\nformation_traj2\n  formation_traj3  # the third\n";
  }
  const std::string a = TempDir("tune_multi");
  ASSERT_EQ(Formsim("tune formation_traj1 --scenario @" + list +
                        " --set duration=2 --param robots.R2.follow.k_l "
                        "--metric links.R1-R2.max_abs_error.l --over max --seeds 1..2 "
                        "--method bobyqa --budget 4 -q --out " + a,
                    a + ".log"),
            0)
      << ReadText(a + ".log");
  for (const char* f : {"best.yaml", "best_formation_traj2.yaml", "best_formation_traj3.yaml"})
    EXPECT_NE(ReadText(a + "/" + f).find("(max over seeds 1..2 of 3 scenarios)"),
              std::string::npos)
        << f;
  // A scenario without a tuned key is refused before anything runs, naming it and the key.
  const std::string b = TempDir("tune_multi_bad");
  EXPECT_EQ(Formsim("tune formation_traj1 --scenario agv_fused --param robots.R2.follow.k_l "
                    "--metric x --out " + b,
                    b + ".log"),
            2);
  EXPECT_NE(ReadText(b + ".log").find("agv_fused.yaml"), std::string::npos) << ReadText(b + ".log");
  EXPECT_NE(ReadText(b + ".log").find("robots.R2.follow.k_l"), std::string::npos);
  EXPECT_FALSE(fs::exists(b + "/history.csv"));
  // A list that is a device, a folder, missing or empty is refused before anything runs.
  const std::string empty = TempDir("tune_list_empty") + ".txt";
  { std::ofstream f(empty); f << "# nothing\n"; }
  for (const std::string& bad : {std::string("/dev/zero"), TempDir("tune_list_dir"),
                                 std::string("/no/such/list"), empty}) {
    EXPECT_EQ(Formsim("tune formation_traj1 --scenario @" + bad +
                          " --param robots.R2.follow.k_l --metric x --out " + b,
                      b + ".log"),
              2)
        << bad;
    EXPECT_NE(ReadText(b + ".log").find("--scenario @" + bad), std::string::npos)
        << bad << ": " << ReadText(b + ".log");
  }
}

TEST(TuneFigures, LandscapeIsExactAtTheEvaluationsAndValidationShowsThePairs) {
  // Two keys on [0, 1] x [0, 1]; three evaluations, the second breaking a constraint.
  sim::TuneSettings s;
  for (const char* k : {"a", "b"}) {
    sim::TuneParam p;
    p.key = k;
    p.lo = 0;
    p.hi = 1;
    s.params.push_back(p);
  }
  s.constraints = {sim::ParseTuneConstraint("c<=1")};
  sim::TuneResult r;
  const double pts[3][3] = {{1.0 / 8, 1.0 / 8, 3}, {5.0 / 8, 1.0 / 8, 2}, {7.0 / 8, 7.0 / 8, 1}};
  for (int i = 0; i < 3; ++i) {
    sim::TuneEvaluation e;
    e.index = static_cast<std::size_t>(i + 1);
    e.values = {pts[i][0], pts[i][1]};
    e.objective = pts[i][2];
    e.violation = i == 1 ? 0.5 : 0;
    r.history.push_back(e);
  }
  r.best = 2;
  const PlotData d = TuneLandscapeFigure(s, r, "m", 4);
  ASSERT_EQ(d.heatmap.columns, 4);
  ASSERT_EQ(d.heatmap.rows, 4);
  EXPECT_EQ(d.heatmap.values[0], 3) << "cell (0, 0) holds evaluation 1 exactly";
  EXPECT_EQ(d.heatmap.values[2], 2) << "an infeasible evaluation still tells the objective";
  EXPECT_EQ(d.heatmap.values[15], 1);
  EXPECT_GT(d.heatmap.values[1], 2);
  EXPECT_LT(d.heatmap.values[1], 3) << "between the points: a weighted mean";
  ASSERT_EQ(d.series.size(), 4u);
  EXPECT_EQ(d.series[0].x.size(), 2u) << "two feasible points";
  EXPECT_EQ(d.series[1].label, "breaks a constraint");
  EXPECT_EQ(d.series[3].label, "best");
  for (const PlotSeries& c : d.series)
    for (double x : c.x) EXPECT_TRUE(std::isnan(x) || x <= 3.5) << "crosses stay inside the map";
  EXPECT_EQ(d.x_tick_labels.front(), "0.125");

  sim::TuneValidation v;
  v.seeds = {6, 7};
  v.scenarios = {"x"};
  v.start = {2, 3};
  v.best = {1, 3.5};
  v.best_feasible = {true, true};
  v.difference = sim::StatsOf({-1, 0.5});
  v.compared = 2;
  v.best_better = 1;
  const PlotData f = TuneValidationFigure(v, s, r, "m");
  EXPECT_EQ(f.series[0].y, (std::vector<double>{-1, 0.5}));
  EXPECT_EQ(f.x_tick_labels, (std::vector<std::string>{"6", "7"})) << "labelled by seed";
  EXPECT_EQ(f.reference_lines, (std::vector<double>{0.0}));
  EXPECT_NE(f.title.find("better on 1 of 2 runs"), std::string::npos);
}

// --- figures, on pixels -------------------------------------------------------------------

using testing::At;
using testing::Distance;
using testing::Rgb;

// Records with metric m = a given function of the point, for figure tests.
std::vector<sim::SweepRecord> FakeRecords(
    const sim::SweepDefinition& d, const std::function<double(std::size_t, std::size_t)>& f) {
  std::vector<sim::SweepRecord> out;
  for (std::size_t r = 0; r < d.runs(); ++r) {
    sim::SweepRecord rec;
    rec.run = r;
    rec.status = "completed";
    rec.metrics = {{"m", f(d.PointOf(r), r % d.seeds.size())}};
    out.push_back(rec);
  }
  return out;
}

TEST(SweepFigures, HeatmapCellsAndColourBarFollowTheMeans) {
  const sim::ScenarioSource src =
      sim::ScenarioSource::FromFile(testing::Scenario("formation_traj2_ukf"));
  const sim::SweepDefinition d = sim::DefineSweep(
      src, {}, {"robots.R2.follow.k_phi=log:0.01:1:4", "robots.R2.follow.estimator=truth,raw,ukf"},
      {1, 2});
  // Mean = point index (0 ... 11): bottom-left lowest, top-right highest.
  const auto recs = FakeRecords(
      d, [](std::size_t p, std::size_t s) { return static_cast<double>(p) + (s ? 0.5 : -0.5); });
  const sim::SweepTables t = sim::BuildSweepTables(d, recs);
  PlotData fig;
  ASSERT_TRUE(SweepFigure(d, t, recs, 0, &fig));
  // Each cell: mean ± the half-width of its 95% interval (seeds ±0.5: std 0.707, t(1) 12.71).
  ASSERT_EQ(fig.heatmap.cell_labels.size(), 12u);
  EXPECT_EQ(fig.heatmap.cell_labels[0], "0 ± 6.4");
  EXPECT_EQ(fig.heatmap.cell_labels[1 * 4 + 2], "7 ± 6.4");  // k_phi index 2, estimator raw
  ASSERT_EQ(fig.heatmap.columns, 4);
  ASSERT_EQ(fig.heatmap.rows, 3);
  EXPECT_EQ(fig.x_tick_labels, (std::vector<std::string>{"0.01", "0.04642", "0.2154", "1"}));
  EXPECT_EQ(fig.y_tick_labels, (std::vector<std::string>{"truth", "raw", "ukf"}));
  const int w = 800, h = 500;
  OffscreenRenderer r(w, h);
  const auto& px = r.RenderFigure(fig, w, h);
  const PlotLayout& L = r.last_plot_layout();
  auto sx = [&](double x) {
    return L.area_min.x + (x - L.x0) / (L.x1 - L.x0) * (L.area_max.x - L.area_min.x);
  };
  auto sy = [&](double y) {
    return L.area_max.y - (y - L.y0) / (L.y1 - L.y0) * (L.area_max.y - L.area_min.y);
  };
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) {
      const double mean = col * 3 + row;  // point = k_phi index * 3 + estimator index
      // A corner of the cell (the centre holds the value as text).
      const Rgb c = At(px, w, static_cast<float>(sx(col - 0.4)), static_cast<float>(sy(row + 0.4)));
      EXPECT_LT(Distance(c, Viridis(mean / 11.0)), 12.0) << "cell " << col << "," << row;
    }
  // The colour bar right of the axes: yellow at the top, dark violet at the bottom.
  const float bar_x = L.area_max.x + 20;
  EXPECT_LT(Distance(At(px, w, bar_x, L.area_min.y + 2), Viridis(1.0)), 25.0);
  EXPECT_LT(Distance(At(px, w, bar_x, L.area_max.y - 2), Viridis(0.0)), 25.0);
}

TEST(SweepFigures, OneKeyGivesMeanBandAndSeeds) {
  const sim::ScenarioSource src =
      sim::ScenarioSource::FromFile(testing::Scenario("formation_traj2_ukf"));
  const sim::SweepDefinition d =
      sim::DefineSweep(src, {}, {"robots.R2.follow.k_l=0.4,0.1,0.2"}, {1, 2, 3});
  const auto recs = FakeRecords(d, [](std::size_t p, std::size_t s) {
    return 10.0 * static_cast<double>(p) + static_cast<double>(s);
  });
  const sim::SweepTables t = sim::BuildSweepTables(d, recs);
  PlotData fig;
  // --band: ± 1σ, min-max, and the default, the 95% interval of the mean; the legend says which.
  ASSERT_TRUE(SweepFigure(d, t, recs, 0, &fig, SweepBand::kSd));
  EXPECT_EQ(fig.series[0].band_hi[0], 12.0);  // mean + sample std (1)
  EXPECT_EQ(fig.series[0].label, "mean ± 1σ over 3 seeds");
  ASSERT_TRUE(SweepFigure(d, t, recs, 0, &fig, SweepBand::kMinMax));
  EXPECT_EQ(fig.series[0].band_lo[0], 10.0);
  EXPECT_EQ(fig.series[0].band_hi[0], 12.0);
  EXPECT_EQ(fig.series[0].label, "mean, band min–max over 3 seeds");
  ASSERT_TRUE(SweepFigure(d, t, recs, 0, &fig));
  EXPECT_EQ(fig.series[0].label, "mean ± 95% CI of the mean over 3 seeds");
  EXPECT_NEAR(fig.series[0].band_hi[0], 11.0 + 4.302653 / std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(fig.series[0].band_lo[0], 11.0 - 4.302653 / std::sqrt(3.0), 1e-6);
  ASSERT_EQ(fig.series.size(), 2u);
  // Sorted by the key: 0.1 (point 1), 0.2 (point 2), 0.4 (point 0).
  EXPECT_EQ(fig.series[0].x, (std::vector<double>{0.1, 0.2, 0.4}));
  EXPECT_EQ(fig.series[0].y, (std::vector<double>{11, 21, 1}));
  ASSERT_TRUE(SweepFigure(d, t, recs, 0, &fig, SweepBand::kSd));  // the pixels below: ± 1σ
  EXPECT_EQ(fig.series[1].x.size(), 9u);
  EXPECT_TRUE(fig.series[1].markers_only);
  OffscreenRenderer r(800, 500);
  const auto& px = r.RenderFigure(fig, 800, 500);
  const PlotLayout& L = r.last_plot_layout();
  // Inside the band, off the line and the grid: the series colour, faded.
  const float x = static_cast<float>(L.area_min.x +
                                     (0.13 - L.x0) / (L.x1 - L.x0) * (L.area_max.x - L.area_min.x));
  const float y = static_cast<float>(L.area_max.y -
                                     (14.3 - L.y0) / (L.y1 - L.y0) * (L.area_max.y - L.area_min.y));
  const Rgb band = At(px, 800, x, y);
  const sim::Color c = sim::PaletteColor(0);
  const sim::Color faded{1 - 0.22f * (1 - c.r), 1 - 0.22f * (1 - c.g), 1 - 0.22f * (1 - c.b), 1};
  EXPECT_LT(Distance(band, faded), 20.0) << band.r << "," << band.g << "," << band.b;
  EXPECT_TRUE(SweepPanels(d, t, 0).empty()) << "one key: the single figure";
}

TEST(SweepFigures, ThreeKeysGiveSmallMultiplesAndRandomSamplesAScatter) {
  const sim::ScenarioSource src =
      sim::ScenarioSource::FromFile(testing::Scenario("formation_traj2_ukf"));
  // Three grid keys: no single figure; one panel per key, each point's mean coloured by its
  // class, and the mean over the other keys (with its band) at each value.
  const sim::SweepDefinition d3 =
      sim::DefineSweep(src, {},
                       {"robots.R2.follow.k_l=0.1,0.2", "robots.R2.follow.k_phi=0.1,0.2",
                        "robots.R3.follow.k_l=0.1,0.2"},
                       {1, 2});
  const auto recs3 = FakeRecords(
      d3, [](std::size_t p, std::size_t s) { return static_cast<double>(p) + 0.1 * s; });
  const sim::SweepTables t3 = sim::BuildSweepTables(d3, recs3);
  PlotData fig;
  EXPECT_FALSE(SweepFigure(d3, t3, recs3, 0, &fig));
  const std::vector<PlotData> panels = SweepPanels(d3, t3, 0);
  ASSERT_EQ(panels.size(), 3u);
  std::size_t points = 0;
  for (std::size_t k = 0; k + 1 < panels[0].series.size(); ++k) {
    EXPECT_TRUE(panels[0].series[k].markers_only);
    points += panels[0].series[k].x.size();
  }
  EXPECT_EQ(points, 8u) << "every point once per panel";
  const PlotSeries& marginal = panels[0].series.back();
  EXPECT_EQ(marginal.x, (std::vector<double>{0.1, 0.2}));
  // The first key is the slowest index: points 0-3 at k_l 0.1 (means 0.05 ... 3.05).
  EXPECT_DOUBLE_EQ(marginal.y[0], 1.55);
  EXPECT_DOUBLE_EQ(marginal.y[1], 5.55);
  EXPECT_EQ(marginal.band_lo.size(), 2u);
  EXPECT_EQ(panels[2].title, "small multiples: robots.R3.follow.k_l");
  EXPECT_NE(panels[2].x_label.find("robots.R3.follow.k_l"), std::string::npos);
  // The lowest class is viridis' dark end, the highest its yellow end.
  const sim::Color low = panels[0].series.front().color, dark = Viridis(0.1);
  EXPECT_EQ(low.r, dark.r);
  EXPECT_EQ(low.g, dark.g);
  EXPECT_EQ(low.b, dark.b);

  // Random samples of two keys: a scatter against each key, no marginal line.
  const sim::SweepDefinition dr = sim::DefineSweep(
      src, {}, {"robots.R2.follow.k_l=random:12", "robots.R2.follow.k_phi=random:12"}, {1});
  const auto recr = FakeRecords(dr, [](std::size_t p, std::size_t) { return p * p * 0.5; });
  const sim::SweepTables tr = sim::BuildSweepTables(dr, recr);
  EXPECT_FALSE(SweepFigure(dr, tr, recr, 0, &fig));
  const std::vector<PlotData> scatter = SweepPanels(dr, tr, 0);
  ASSERT_EQ(scatter.size(), 2u);
  std::size_t dots = 0;
  for (const PlotSeries& s : scatter[1].series) {
    EXPECT_TRUE(s.markers_only);
    EXPECT_TRUE(s.band_lo.empty());
    dots += s.x.size();
  }
  EXPECT_EQ(dots, 12u);
  EXPECT_EQ(scatter[1].series.size(), 5u) << "five colour classes of the metric";
  EXPECT_NE(scatter[0].title.find("random samples"), std::string::npos);
  // Written side by side into one PNG.
  const std::string png = TempDir("sweep_panels") + ".png";
  WritePanelsPng(scatter, png, 320, 220, 2);
  EXPECT_GT(fs::file_size(png), 5000u);
}

}  // namespace
}  // namespace formsim::app
