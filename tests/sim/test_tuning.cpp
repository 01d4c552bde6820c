// Tuning on top of the session (sim::Session) with the minimal kind of test_kind.hpp: undo and
// redo of edits as edits, revert and "edited", run logs replayed bit for bit (pins, the
// timeline, branches), session records written, read and replayed, headline metrics, and the
// Monte Carlo of the GUI against the sweep engine.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sim/study/monte_carlo.hpp"
#include "sim/session/run_history.hpp"
#include "sim/session/run_log.hpp"
#include "sim/session/session.hpp"
#include "sim/session/session_record.hpp"
#include "sim/study/sweep_tables.hpp"
#include "tests/sim/test_kind.hpp"

namespace formsim::sim {
namespace {

using testkind::NoisyCircle;

std::string TuningFile(const std::string& name, const std::string& text) {
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/test_out/tuning";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

const NoisyCircle& Circle(const Experiment& e) {
  return dynamic_cast<const NoisyCircle&>(e);
}

// Every recorded value of two runs, bit for bit.
void ExpectSameRows(const Recorder& a, const Recorder& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.columns(), b.columns());
  for (std::size_t r = 0; r < a.rows(); ++r)
    for (std::size_t c = 0; c < a.columns(); ++c) {
      const double x = a.At(r, static_cast<int>(c)), y = b.At(r, static_cast<int>(c));
      ASSERT_TRUE(x == y || (std::isnan(x) && std::isnan(y))) << "row " << r << " column " << c;
    }
}

void StepTo(Session& s, long step) {
  while (s.exp().steps() < step && !s.exp().finished()) s.Step();
}

TEST(Tuning, UndoAndRedoAreEditsAndSliderDragsAreOneStep) {
  Session s(TuningFile("undo.yaml", testkind::kScenario), {}, -1);
  EXPECT_FALSE(s.can_undo());
  EXPECT_EQ(s.Undo(), "nothing to undo");
  // A drag over three frames is one undo step.
  EXPECT_EQ(s.Edit("v", "1.3"), "");
  EXPECT_EQ(s.Edit("v", "1.4", "GUI edit", true), "");
  EXPECT_EQ(s.Edit("v", "1.5", "GUI edit", true), "");
  EXPECT_EQ(s.Edit("sigma", "0.3"), "");  // waits for a reset
  EXPECT_TRUE(s.IsEdited("v"));
  EXPECT_TRUE(s.IsEdited("sigma"));
  EXPECT_FALSE(s.IsEdited("omega"));
  EXPECT_EQ(s.UndoText(), "sigma 0.3 -> 0.1");
  EXPECT_EQ(s.Undo(), "");
  EXPECT_EQ(s.EffectiveValue("sigma"), "0.1");
  EXPECT_FALSE(s.IsEdited("sigma"));
  s.Step();
  EXPECT_EQ(Circle(s.exp()).v(), 1.5);
  EXPECT_EQ(s.Undo(), "");
  s.Step();
  EXPECT_EQ(Circle(s.exp()).v(), 1.2) << "undo goes back over the whole drag";
  EXPECT_FALSE(s.can_undo());
  EXPECT_EQ(s.RedoText(), "v 1.2 -> 1.5");
  EXPECT_EQ(s.Redo(), "");
  s.Step();
  EXPECT_EQ(Circle(s.exp()).v(), 1.5);
  // Undo and redo went through the edit path: they are in the run's provenance.
  const std::string json = s.exp().Summary().Dump();
  EXPECT_NE(json.find("\"origin\": \"undo\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"origin\": \"redo\""), std::string::npos) << json;
  // A new edit clears what could be redone; an undo the loader refuses now is refused.
  EXPECT_EQ(s.Redo(), "");  // sigma 0.1 -> 0.3 again
  EXPECT_FALSE(s.can_redo());
  EXPECT_EQ(s.Edit("omega", "2"), "");
  EXPECT_EQ(s.Edit("v", "1.9"), "");  // v + |omega| = 3.9 < 4
  EXPECT_EQ(s.Edit("omega", "0.5"), "");
  EXPECT_EQ(s.Edit("v", "3.4"), "");  // fine with omega 0.5
  EXPECT_EQ(s.Undo(), "");            // v back to 1.9
  EXPECT_EQ(s.Undo(), "");            // omega back to 2
  EXPECT_EQ(s.Redo(), "");            // omega 0.5
  EXPECT_EQ(s.Redo(), "");            // v 3.4
  EXPECT_EQ(s.EffectiveValue("v"), "3.4");
  // Revert to the loaded value goes through Edit as well.
  EXPECT_EQ(s.Edit("v", s.LoadedValue("v"), "revert"), "");
  EXPECT_EQ(s.EffectiveValue("v"), "1.2");
  EXPECT_EQ(s.Reload(), "");
  EXPECT_FALSE(s.can_undo());
}

TEST(Tuning, ReplayingTheRunLogGivesTheRunBitForBit) {
  Session s(TuningFile("log.yaml", testkind::kScenario), {}, 7);
  StepTo(s, 10);
  EXPECT_EQ(s.Edit("v", "2"), "");
  StepTo(s, 40);
  s.Move("R1", 0.5, -0.25);
  EXPECT_EQ(s.Edit("omega", "1.5"), "");
  EXPECT_EQ(s.Edit("v", "1"), "");
  s.ApplyPending();  // paused: both edits apply together, then the drag
  StepTo(s, 70);
  ASSERT_EQ(s.run_log().changes.size(), 3u);
  RunReplay replay(s.source(), s.run_log());
  replay.AdvanceTo(s.exp().steps(), true);
  ExpectSameRows(s.exp().recorder(), replay.exp().recorder());
  EXPECT_EQ(s.exp().Summary().Dump(), replay.exp().Summary().Dump());
  // A replay can stop and go on (the timeline moves forward in steps).
  RunReplay partial(s.source(), s.run_log());
  int polls = 0;
  while (!partial.AdvanceTo(70, true, [&] { return ++polls % 2 == 0; })) {
  }
  ExpectSameRows(s.exp().recorder(), partial.exp().recorder());
}

TEST(Tuning, BranchStartsFromTheExactStateOfTheRunAtThatStep) {
  const std::string file = TuningFile("branch.yaml", testkind::kScenario);
  Session a(file, {}, -1);
  StepTo(a, 20);
  EXPECT_EQ(a.Edit("v", "2"), "");
  StepTo(a, 60);
  EXPECT_EQ(a.Edit("v", "0.5"), "");  // after the branch point: dropped by the branch
  StepTo(a, 80);
  const long run = a.run_id();
  EXPECT_EQ(a.Branch(50), "");
  EXPECT_NE(a.run_id(), run);
  EXPECT_EQ(a.exp().steps(), 50);
  EXPECT_EQ(Circle(a.exp()).v(), 2.0);
  EXPECT_EQ(a.Edit("omega", "1"), "");  // the new gains of the branch
  while (!a.exp().finished()) a.Step();
  // The same run made by hand: the edit at 20, the new one at 50.
  Session b(file, {}, -1);
  StepTo(b, 20);
  EXPECT_EQ(b.Edit("v", "2"), "");
  StepTo(b, 50);
  EXPECT_EQ(b.Edit("omega", "1"), "");
  while (!b.exp().finished()) b.Step();
  ExpectSameRows(a.exp().recorder(), b.exp().recorder());
  EXPECT_NE(a.Branch(100000).find("not in the run"), std::string::npos);
}

TEST(Tuning, ASessionRecordReplaysToTheSameRun) {
  const std::string file = TuningFile("record.yaml", testkind::kScenario);
  SessionRecord record;
  std::vector<Override> cli = {{"omega", "0.4", "--set", -1}};
  Session s(file, cli);
  SessionEvent load;
  load.kind = SessionEvent::Kind::kLoad;
  load.source = std::make_shared<ScenarioSource>(s.source());
  load.overrides = cli;
  record.Add(load);
  s.SetObserver([&](const SessionEvent& e) { record.Add(e); });
  StepTo(s, 12);
  EXPECT_EQ(s.Edit("v", "1.7"), "");
  StepTo(s, 30);
  EXPECT_EQ(s.Edit("sigma", "0.4"), "");  // on reset
  EXPECT_NE(s.Edit("v", "-1"), "");       // refused: not recorded
  StepTo(s, 45);
  EXPECT_EQ(s.Reset(), "");
  StepTo(s, 9);
  s.Move("R1", 0.25, 0.125);
  StepTo(s, 33);
  EXPECT_EQ(s.Reset(11), "");  // a seed change
  StepTo(s, 40);
  EXPECT_EQ(s.Edit("v", "0.9"), "");
  StepTo(s, 61);
  EXPECT_EQ(s.Branch(50), "");
  EXPECT_EQ(s.Edit("omega", "-0.7"), "");
  StepTo(s, 77);
  EXPECT_EQ(s.Undo(), "");
  StepTo(s, 88);
  const std::string yaml = record.ToYaml(s.exp().steps());
  const std::string path = TuningFile("record.session.yaml", yaml);
  SessionReplay replay(SessionRecord::Read(path));
  while (replay.Advance()) {
  }
  EXPECT_EQ(replay.session().exp().steps(), 88);
  EXPECT_EQ(replay.session().seed(), 11u);
  ExpectSameRows(s.exp().recorder(), replay.session().exp().recorder());
  EXPECT_EQ(s.exp().Summary().Dump(), replay.session().exp().Summary().Dump());
  // The text is in the record: the replay does not need the file any more.
  std::filesystem::remove(file);
  SessionReplay again(SessionRecord::Parse(yaml, "again"));
  while (again.Advance()) {
  }
  ExpectSameRows(s.exp().recorder(), again.session().exp().recorder());
}

TEST(Tuning, SessionRecordErrorsNameTheLineAndKey) {
  auto error = [](const std::string& text) {
    try {
      SessionRecord::Parse(text, "s.yaml");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("formsim_session: 2\nscenarios: []\nevents: []\n")
                .find("s.yaml:1: key 'formsim_session'"),
            std::string::npos);
  const std::string head = "formsim_session: 1\nscenarios: []\nevents:\n";
  EXPECT_NE(
      error(head + "  - {do: fly, step: 0}\n").find("s.yaml:4: key 'do': unknown event 'fly'"),
      std::string::npos)
      << error(head + "  - {do: fly, step: 0}\n");
  EXPECT_NE(
      error(head + "  - {do: load, step: 0, scenario: abc}\n").find("no text with SHA-256 abc"),
      std::string::npos);
  EXPECT_NE(error(head + "  - {do: edit, step: -3}\n").find("key 'step': must be a step"),
            std::string::npos);
  const std::string changed =
      "formsim_session: 1\nscenarios:\n  - {sha256: 00, file: a.yaml, dir: '', text: 'type: x'}\n"
      "events: []\n";
  EXPECT_NE(error(changed).find("the text was changed"), std::string::npos) << error(changed);
}

TEST(Tuning, TextsThatALiteralBlockCannotHoldAreWrittenQuoted) {
  SessionRecord record;
  SessionEvent load;
  load.kind = SessionEvent::Kind::kLoad;
  const std::string text = std::string(testkind::kScenario) + "# trailing spaces   \n\t# tab\n";
  load.source = std::make_shared<ScenarioSource>(ScenarioSource::FromText(text, "t.yaml", "/tmp"));
  record.Add(load);
  const SessionRecord back = SessionRecord::Parse(record.ToYaml(0), "back");
  EXPECT_EQ(back.events().front().source->text(), text);
  EXPECT_EQ(back.end_step(), 0);
}

TEST(Tuning, PathPatternsDirectionsAndHeadlines) {
  EXPECT_TRUE(PathMatches("links.*.rmse.*", "links.R1-R2.rmse.l"));
  EXPECT_TRUE(PathMatches("a*", "a"));
  EXPECT_FALSE(PathMatches("links.*.rmse.*", "links.R1-R2.max.l"));
  EXPECT_FALSE(PathMatches("a.b", "a.bc"));
  Metrics m;
  m.Set("links.A.err", 0.5);
  m.Set("links.B.err", 0.25);
  m.Set("links.B.count", 3);
  m.Set("progress", 10);
  m.SetBetter("links.*", Better::kLower);
  m.SetBetter("progress", Better::kHigher);
  EXPECT_EQ(m.BetterOf("links.B.count"), Better::kLower);
  EXPECT_EQ(m.BetterOf("progress"), Better::kHigher);
  EXPECT_EQ(m.BetterOf("other"), Better::kNone);
  // Without headlines: the first three numbers.
  EXPECT_EQ(m.Headlines().size(), 3u);
  m.AddHeadline({"worst err", "links.*.err", Metrics::Combine::kMax, ""});
  m.AddHeadline({"counts", "links.*.count", Metrics::Combine::kSum, ""});
  m.AddHeadline({"none", "nothing.*", Metrics::Combine::kValue, ""});
  const auto h = m.Headlines();
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[0].value, 0.5);
  EXPECT_EQ(h[0].better, Better::kLower);
  EXPECT_EQ(h[1].value, 3);
  EXPECT_TRUE(std::isnan(h[2].value));
}

TEST(Tuning, MonteCarloIsTheSweepAndItsBandsDoNotDependOnThreads) {
  const std::string file = TuningFile("mc.yaml", testkind::kScenario);
  const ScenarioSource source = ScenarioSource::FromFile(file);
  const std::vector<Override> sets = {{"v", "1.5", "GUI edit", -1},
                                      {"sigma", "0.3", "GUI edit", -1}};
  const std::vector<std::uint64_t> seeds = {1, 2, 3, 4, 5};
  auto run = [&](int threads) {
    auto mc = std::make_unique<MonteCarlo>(source, sets, seeds, threads);
    while (!mc->finished()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return mc;
  };
  const auto one = run(1), two = run(2);
  // The sweep engine, as `formsim sweep --set v=1.5 --set sigma=0.3 --seeds 1..5` runs it.
  const SweepDefinition def = DefineSweep(source, sets, {}, seeds);
  TaskPool pool(1);
  std::vector<SweepRecord> records;
  RunSweep(source, def, {0, 1, 2, 3, 4}, pool,
           [&](const SweepRecord& r, const SweepProgress&) { records.push_back(r); });
  const SweepTables want = BuildSweepTables(def, records);
  EXPECT_EQ(one->Tables().runs_csv, want.runs_csv);
  EXPECT_EQ(one->Tables().aggregate_csv, want.aggregate_csv);
  EXPECT_EQ(two->Tables().aggregate_csv, want.aggregate_csv);
  EXPECT_EQ(one->progress().done, 5u);
  const ChannelBands a = one->Bands(), b = two->Bands();
  EXPECT_EQ(a.runs, 5);
  const ChannelBands::Band* band = a.Find("measured_v");
  ASSERT_NE(band, nullptr);
  ASSERT_EQ(band->mean.size(), a.t.size());
  ASSERT_GT(a.t.size(), 50u);
  const ChannelBands::Band* band2 = b.Find("measured_v");
  for (std::size_t k = 0; k < band->mean.size(); ++k) {
    EXPECT_EQ(band->mean[k], band2->mean[k]);
    EXPECT_EQ(band->sd[k], band2->sd[k]);
    EXPECT_LE(band->lo[k], band->mean[k]);
    EXPECT_GE(band->hi[k], band->mean[k]);
  }
  // The band of a row is the statistics of the seeds' values at that row.
  std::vector<double> v;
  for (std::uint64_t seed : seeds) {
    Session s(file, {{"v", "1.5", "--set", -1},
                     {"sigma", "0.3", "--set", -1},
                     {"seed", std::to_string(seed), "--seed", -1}});
    while (!s.exp().finished()) s.Step();
    v.push_back(s.exp().recorder().At(40, s.exp().recorder().Column("measured_v")));
  }
  double mean = 0;
  for (double x : v) mean += x / 5;
  EXPECT_NEAR(band->mean[40], mean, 1e-12);
  EXPECT_EQ(band->lo[40], *std::min_element(v.begin(), v.end()));
  // Cancelled at once: nothing more starts, the object ends cleanly. (Many seeds: with a few,
  // a loaded machine could finish them all before Cancel is reached.)
  std::vector<std::uint64_t> many(2000);
  for (std::size_t i = 0; i < many.size(); ++i) many[i] = i + 1;
  MonteCarlo cancelled(source, sets, many, 1);
  cancelled.Cancel();
  while (!cancelled.finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_LT(cancelled.progress().done, many.size());
}

}  // namespace
}  // namespace formsim::sim

namespace formsim::sim {
namespace {

TEST(Tuning, HistoryRowsKeepSettingsMetricsAndReplayExactly) {
  const std::string file = TuningFile("history.yaml", testkind::kScenario);
  Session s(file, {{"omega", "0.3", "--set", -1}});
  EXPECT_EQ(s.Edit("v", "1.6"), "");
  s.ApplyPending();
  StepTo(s, 30);
  EXPECT_EQ(s.Edit("v", "1.1"), "");  // mid-run
  StepTo(s, 55);
  RunHistory h;
  h.Add(RunHistory::RowOf(s, "reset"));
  EXPECT_EQ(s.Reset(9), "");
  StepTo(s, 100);  // to the end: no changes at all
  h.Add(RunHistory::RowOf(s, s.exp().status()));
  ASSERT_EQ(h.rows().size(), 2u);
  const HistoryRow& a = h.rows()[0];
  EXPECT_EQ(a.number, 1);
  EXPECT_EQ(a.steps, 55);
  EXPECT_EQ(a.mid_run_changes(), 2);
  // Settings at the end of the run that differ from the text: omega (--set) and v.
  ASSERT_EQ(a.settings.size(), 2u);
  EXPECT_EQ(a.Value("v", ParseScenario(s.source(), {}).params), "1.1");
  EXPECT_EQ(a.Value("sigma", ParseScenario(s.source(), {}).params), "0.1");
  EXPECT_EQ(h.rows()[1].seed, 9u);
  EXPECT_EQ(h.rows()[1].status, "completed");
  // Saved and read back: the same rows, and the first replays to the run it was.
  const std::string path = RunHistory::PathFor(file);
  EXPECT_EQ(path, std::string(FORMSIM_BINARY_DIR) + "/test_out/tuning/history.history.yaml");
  h.Save(path);
  const RunHistory back = RunHistory::Load(path);
  ASSERT_EQ(back.rows().size(), 2u);
  EXPECT_EQ(back.rows()[0].settings, a.settings);
  EXPECT_EQ(back.rows()[0].log.changes.size(), 2u);
  EXPECT_EQ(back.rows()[1].log.changes.size(), 0u);
  ASSERT_EQ(back.rows()[0].metrics.size(), a.metrics.size());
  EXPECT_EQ(back.rows()[0].metrics[0].value, a.metrics[0].value);
  Session again(file, {{"omega", "0.3", "--set", -1}});
  EXPECT_EQ(again.Edit("v", "1.6"), "");
  again.ApplyPending();
  StepTo(again, 30);
  EXPECT_EQ(again.Edit("v", "1.1"), "");
  StepTo(again, 55);
  RunReplay replay(*back.rows()[0].source, back.rows()[0].log);
  replay.AdvanceTo(back.rows()[0].steps, true);
  ExpectSameRows(again.exp().recorder(), replay.exp().recorder());
}

TEST(Tuning, DifferencesNameEachTunableByItsShortestUniqueTail) {
  ParamTable params;
  for (const char* k : {"robots.R2.follow.k_l", "robots.R3.follow.k_l", "robots.R2.follow.k_phi"}) {
    Param p;
    p.key = k;
    params.Add(p);
  }
  EXPECT_EQ(ShortKey("robots.R2.follow.k_phi", params), "k_phi");
  EXPECT_EQ(ShortKey("robots.R2.follow.k_l", params), "R2.follow.k_l");
  EXPECT_EQ(DescribeDifferences({{"robots.R2.follow.k_phi", "0.08"}, {"seed", "1"}},
                                {{"robots.R2.follow.k_phi", "0.2"}, {"seed", "7"}}, params),
            "k_phi 0.08 -> 0.2, seed 1 -> 7");
  EXPECT_EQ(DescribeDifferences({{"robots.R2.follow.k_phi", "0.08"}},
                                {{"robots.R2.follow.k_phi", "0.08"}}, params),
            "");
}

}  // namespace
}  // namespace formsim::sim
