// Never lose a run: a non-finite value or state stops the run with a numerical_fault event
// naming the robot and time, everything up to it is kept and written (non-finite numbers as
// nan/inf, never as an empty "not sampled" cell); long runs keep bounded memory; writes that
// fail leave no partial file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/core/bounded_history.hpp"
#include "sim/core/json.hpp"
#include "sim/core/recorder.hpp"
#include "sim/core/run_output.hpp"
#include "sim/scenario/scenario.hpp"
#include "tests/sim/test_kind.hpp"
#include "tests/support/test_files.hpp"

namespace formsim::sim {
namespace {

using testing::ReadText;

TEST(NumericalFault, ANonFiniteValueStopsTheRunAndIsWrittenAsNan) {
  auto e = LoadExperimentFromText(testkind::kScenario, "a.yaml", {"fault=value", "fault_time=0.5"});
  while (!e->finished()) e->Step();
  EXPECT_EQ(e->status(), "numerical_fault");
  EXPECT_NEAR(e->time(), 0.5, 1e-9);
  ASSERT_EQ(e->events().Count(event::kNumericalFault), 1);
  const Event& ev = e->events().list().back();
  EXPECT_EQ(ev.kind, "numerical_fault");
  EXPECT_NE(ev.message.find("measured_v = nan"), std::string::npos) << ev.message;
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/test_out/fault_value";
  WriteRunOutputs(*e, dir);
  const std::string csv = ReadText(dir + "/timeseries.csv");
  EXPECT_NE(csv.find(",nan\n"), std::string::npos) << "a computed NaN is written as nan";
  const std::string json = ReadText(dir + "/summary.json");
  EXPECT_NE(json.find("\"status\": \"numerical_fault\""), std::string::npos);
  EXPECT_NE(json.find("\"stop_reason\""), std::string::npos);
  EXPECT_NE(e->SummaryText().find("run stopped at t = 0.5 s"), std::string::npos);
}

TEST(NumericalFault, ANonFiniteStateStopsBeforeTheSensorsSeeIt) {
  auto e = LoadExperimentFromText(testkind::kScenario, "a.yaml", {"fault=state", "fault_time=0.3"});
  while (!e->finished()) e->Step();
  EXPECT_EQ(e->status(), "numerical_fault");
  ASSERT_EQ(e->events().Count(event::kNumericalFault), 1);
  const Event& ev = e->events().list().back();
  EXPECT_EQ(ev.robots, "R1");
  EXPECT_NE(ev.message.find("R1's state became non-finite"), std::string::npos) << ev.message;
  EXPECT_NEAR(e->time(), 0.31, 1e-9);  // the step after the command that blew up
  const long steps = e->steps();
  e->Step();  // a stopped run does not step again
  EXPECT_EQ(e->steps(), steps);
}

TEST(NumericalFault, IsFoundOnEveryRowEvenWhenTheHistoryDropsIt) {
  auto e = LoadExperimentFromText(testkind::kScenario, "a.yaml",
                                  {"fault=value", "fault_time=0.77", "duration=2"});
  e->mutable_recorder().SetHistoryLimit(4);  // most rows are not kept in memory
  while (!e->finished()) e->Step();
  EXPECT_EQ(e->status(), "numerical_fault");
  EXPECT_NEAR(e->time(), 0.77, 1e-9);
}

TEST(Interrupt, MarksTheRunAndKeepsItsResults) {
  auto e = LoadExperimentFromText(testkind::kScenario, "a.yaml");
  for (int i = 0; i < 10; ++i) e->Step();
  e->Interrupt("interrupted by SIGTERM at t = 0.1 s");
  EXPECT_TRUE(e->finished());
  EXPECT_EQ(e->status(), "interrupted");
  EXPECT_NE(e->Summary().Dump().find("\"status\": \"interrupted\""), std::string::npos);
}

TEST(Recorder, StreamsEveryRowWhileKeepingABoundedHistory) {
  auto e = LoadExperimentFromText(testkind::kScenario, "a.yaml", {"duration=20"});
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/test_out/stream";
  std::filesystem::create_directories(dir);
  Recorder& rec = e->mutable_recorder();
  rec.StreamTo(CsvPath(dir));
  rec.SetHistoryLimit(100);
  while (!e->finished()) e->Step();
  EXPECT_EQ(rec.rows_sampled(), 2001u);
  EXPECT_LE(rec.rows(), 100u);
  EXPECT_GE(rec.rows(), 50u);
  EXPECT_EQ(rec.history_stride(), 32u);
  // The history covers the whole run evenly: first row t = 0, last kept near the end.
  EXPECT_EQ(rec.At(0, 0), 0.0);
  EXPECT_GT(rec.At(rec.rows() - 1, 0), 19.0);
  EXPECT_THROW(rec.WriteCsv(dir + "/x.csv"), std::logic_error) << "a thinned history is no CSV";
  WriteRunOutputs(*e, dir);
  // Every row reached the file; nothing temporary is left.
  std::ifstream in(CsvPath(dir));
  std::string line;
  std::size_t lines = 0;
  while (std::getline(in, line)) ++lines;
  EXPECT_EQ(lines, 2002u);
  EXPECT_FALSE(std::filesystem::exists(CsvPath(dir) + ".tmp"));
}

// The rows handed out by SharedRows (the Python module's views) never change, whether the
// recorder goes on into reserved room, grows past it, halves its history, or is destroyed.
TEST(Recorder, SharedRowsStayUnchangedAsTheRecordingGoesOn) {
  // Bit for bit (a not-sampled cell is a NaN, unequal to itself under ==).
  auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() <= b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  auto e = LoadExperimentFromText(testkind::kScenario, "a.yaml", {"duration=20"});
  for (int i = 0; i < 100; ++i) e->Step();
  const Recorder& rec = e->recorder();
  const std::shared_ptr<const std::vector<double>> early = rec.SharedRows();
  const std::vector<double> early_copy = *early;
  const double* early_data = early->data();
  const std::size_t cols = rec.columns();
  ASSERT_EQ(early_copy.size(), rec.rows() * cols);
  EXPECT_EQ(rec.SharedRows()->data(), early_data) << "no copy while nothing moved";
  while (!e->finished()) e->Step();  // past the reserved room? either way the rows hold
  EXPECT_EQ(early->data(), early_data);
  EXPECT_TRUE(same(early_copy, *early));
  EXPECT_GT(rec.rows(), early_copy.size() / cols);
  EXPECT_TRUE(same(early_copy, *rec.SharedRows())) << "the run went on from the same rows";

  // A history that halves itself rewrites its rows in a buffer of its own.
  auto d = LoadExperimentFromText(testkind::kScenario, "a.yaml", {"duration=20"});
  d->mutable_recorder().SetHistoryLimit(64);
  for (int i = 0; i < 600; ++i) d->Step();  // 64 rows kept, well before the next halving
  const auto before = d->recorder().SharedRows();
  const std::vector<double> before_copy = *before;
  while (!d->finished()) d->Step();
  EXPECT_GT(d->recorder().history_stride(), 1u);
  EXPECT_TRUE(same(before_copy, *before));
  EXPECT_FALSE(same(before_copy, *d->recorder().SharedRows())) << "the history was halved";
  e.reset();
  d.reset();  // the recorders are gone; their shared rows are not
  EXPECT_TRUE(same(early_copy, *early));
  EXPECT_TRUE(same(before_copy, *before));
}

TEST(Recorder, FiniteCheckSeesEveryKindOfNonFiniteValueAndSkipsNotSampled) {
  std::vector<double> row(37, 1.5);
  row[3] = -0.0;
  row[20] = NotSampled();
  EXPECT_TRUE(AllFiniteOrNotSampled(row.data(), row.size()));
  for (double bad : {std::nan(""), -std::nan(""), HUGE_VAL, -HUGE_VAL})
    for (std::size_t at : {std::size_t{0}, std::size_t{19}, std::size_t{36}}) {
      std::vector<double> r = row;
      r[at] = bad;
      EXPECT_FALSE(AllFiniteOrNotSampled(r.data(), r.size())) << bad << " at " << at;
    }
  EXPECT_TRUE(AllFiniteOrNotSampled(row.data(), 0));
}

TEST(Recorder, AFailedWriteLeavesNoFile) {
  auto e = LoadExperimentFromText(testkind::kScenario, "a.yaml");
  while (!e->finished()) e->Step();
  // /dev/full accepts the open and fails the writes with ENOSPC.
  EXPECT_THROW(WriteFileAtomic("/proc/self/nonexistent/x.json", "{}"), std::runtime_error);
  try {
    e->recorder().WriteCsv("/dev/full/x.csv");
    FAIL() << "wrote into /dev/full/";
  } catch (const std::runtime_error& err) {
    EXPECT_NE(std::string(err.what()).find("/dev/full/x.csv"), std::string::npos);
  }
}

TEST(EventLog, StoresABoundedNumberPerKindButCountsEveryOne) {
  EventLog log;
  for (int i = 0; i < 5000; ++i) log.Add(i * 0.01, "collision", "R1,R2", "R1 hit R2");
  log.Add(50, "saturation", "R1", "clamped");
  EXPECT_EQ(log.Count("collision"), 5000);
  EXPECT_EQ(log.CountForRobot("collision", "R2"), 5000);
  EXPECT_EQ(log.total(), 5001);
  EXPECT_EQ(log.list().size(), static_cast<std::size_t>(EventLog::kMaxStoredPerKind) + 1);
  EXPECT_EQ(log.recent().back().kind, "saturation");
}

TEST(BoundedHistory, ThinsEvenlyAndStaysBounded) {
  BoundedHistory<int> h(10);
  for (int i = 0; i < 1000; ++i) h.push_back(i);
  EXPECT_LE(h.size(), 10u);
  EXPECT_EQ(h[0], 0);
  for (std::size_t i = 1; i < h.size(); ++i) EXPECT_EQ(h[i] - h[i - 1], h[1] - h[0]);
}

TEST(Json, AnyBytesGiveValidJsonAndIntegersRoundTrip) {
  Json j = Json::Object();
  j["name"] = std::string("caf\xc3\xa9 \xff\xfe bad \x01");
  j["seed"] = 12345678901ULL;
  j["big"] = 18446744073709551615ULL;
  j["x"] = 0.1;
  const std::string out = j.Dump(0);
  EXPECT_NE(out.find("caf\xc3\xa9 \\u00ff\\u00fe bad \\u0001"), std::string::npos) << out;
  EXPECT_NE(out.find("\"seed\":12345678901"), std::string::npos) << out;
  EXPECT_NE(out.find("\"big\":18446744073709551615"), std::string::npos) << out;
  EXPECT_NE(out.find("\"x\":0.1"), std::string::npos) << out;
}

TEST(Loader, HostileTextGetsAClearMessage) {
  auto error = [](const std::string& text) {
    try {
      LoadExperimentFromText(text, "h.yaml");
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(error(std::string(500, '[') + std::string(500, ']')).find("nested deeper than"),
            std::string::npos);
  const std::string ctrl = error("type: test_noisy_circle\nv: \x01\x02\n");
  EXPECT_EQ(ctrl.find('\x01'), std::string::npos) << "control bytes are shown escaped";
  EXPECT_NE(ctrl.find("\\x01"), std::string::npos) << ctrl;
  EXPECT_NE(error("type: [unclosed\n").find("h.yaml:"), std::string::npos);
}

}  // namespace
}  // namespace formsim::sim
