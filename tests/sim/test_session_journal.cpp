// The window's crash-safe journal (sim/session/session_journal.hpp): every event appended and
// flushed as it happens reads back as the same record; a torn last entry (the process died while
// writing it) is dropped and the rest kept; a journal whose window holds its lock is not offered
// for restore, one nobody holds is; `formsim replay` reads a journal like a session file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/session/session_journal.hpp"
#include "tests/sim/test_kind.hpp"
#include "tests/support/test_files.hpp"

namespace formsim::sim {
namespace {

namespace fs = std::filesystem;

std::string JournalTestDir(const std::string& name) {
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/test_out/journal/" + name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using testing::ReadText;

// A session of the test kind with a few edits, resets and steps, recorded as the GUI records it.
struct Recorded {
  std::unique_ptr<Session> session;
  SessionRecord record;
};

Recorded Record(const std::string& dir, SessionJournal* journal) {
  const std::string file = dir + "/circle.yaml";
  std::ofstream(file) << testkind::kScenario;
  Recorded r;
  r.session = std::make_unique<Session>(file, std::vector<std::string>{}, -1);
  if (journal) r.record.SetListener([journal](const SessionEvent& e) { journal->Append(e); });
  SessionEvent load;
  load.kind = SessionEvent::Kind::kLoad;
  load.source = std::make_shared<ScenarioSource>(r.session->source());
  r.record.Add(load);
  r.session->SetObserver([&rec = r.record](const SessionEvent& e) { rec.Add(e); });
  for (int i = 0; i < 20; ++i) r.session->Step();
  EXPECT_EQ(r.session->Edit("v", "2"), "");
  for (int i = 0; i < 15; ++i) r.session->Step();
  EXPECT_EQ(r.session->Reset(7), "");
  for (int i = 0; i < 10; ++i) r.session->Step();
  EXPECT_EQ(r.session->Edit("v", "1.5"), "");
  r.session->Step();
  if (journal) journal->NoteStep(r.session->exp().steps(), 0);
  return r;
}

TEST(SessionJournal, ReadsBackTheRecordUpToTheLastStepWritten) {
  const std::string dir = JournalTestDir("back");
  SessionJournal journal(dir + "/state", "circle");
  Recorded r = Record(dir, &journal);
  const RecoveredSession back = RecoverJournal(journal.path());
  EXPECT_FALSE(back.torn);
  EXPECT_EQ(back.scenario, "circle");
  EXPECT_EQ(back.edits, 2u);
  EXPECT_EQ(back.record.end_step(), r.session->exp().steps());
  // The same YAML as the record itself, ended at the same step.
  EXPECT_EQ(back.record.ToYaml(back.record.end_step()), r.record.ToYaml(r.session->exp().steps()));
  // SessionRecord::Read (formsim replay) takes the journal as it is.
  const SessionRecord read = SessionRecord::Read(journal.path());
  EXPECT_EQ(read.events().size(), r.record.events().size());
  SessionReplay replay(read);
  while (replay.Advance()) {
  }
  EXPECT_EQ(replay.session().exp().steps(), r.session->exp().steps());
  EXPECT_EQ(replay.session().params().Find("v")->value, 1.5);
}

TEST(SessionJournal, ATornLastEntryIsDroppedAndTheRestKept) {
  const std::string dir = JournalTestDir("torn");
  std::string path;
  {
    SessionJournal journal(dir + "/state", "circle");
    Record(dir, &journal);
    path = journal.path();
  }
  const std::string whole = ReadText(path);
  const RecoveredSession full = ParseJournal(whole, path);
  // Cut the file at every byte of its last entry: the last entry goes, the rest stays.
  const std::size_t last = whole.rfind("\nJ ") + 1;
  for (std::size_t cut = last; cut < whole.size(); ++cut) {
    const RecoveredSession r = ParseJournal(whole.substr(0, cut), path);
    EXPECT_EQ(r.torn, cut > last) << "cut at " << cut;
    EXPECT_EQ(r.record.events().size(), full.record.events().size()) << "cut at " << cut;
  }
  // A flipped byte inside an entry ends the journal there (its checksum fails).
  std::string flipped = whole;
  const std::size_t edit = whole.find("1:v");
  ASSERT_NE(edit, std::string::npos);
  flipped[edit + 2] = 'w';
  const RecoveredSession r = ParseJournal(flipped, path);
  EXPECT_TRUE(r.torn);
  EXPECT_LT(r.record.events().size(), full.record.events().size());
  // No scenario yet, or not a journal: refused with the file's name.
  EXPECT_THROW(ParseJournal(whole.substr(0, 40), path), std::runtime_error);
  try {
    ParseJournal("formsim_session: 1\n", path);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
  }
}

TEST(SessionJournal, OnlyJournalsNobodyHoldsAreUnfinished) {
  const std::string dir = JournalTestDir("held");
  const std::string state = dir + "/state";
  std::string gone;
  {
    SessionJournal journal(state, "gone");
    Record(dir, &journal);
    gone = journal.path();
  }  // closed: its lock is released, as when a window dies
  SessionJournal running(state, "running");
  Record(dir, &running);
  const auto found = UnfinishedSessions(state);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].path, gone);
  EXPECT_EQ(found[0].scenario, "gone");
  running.Remove();
  EXPECT_FALSE(fs::exists(running.path()));
  EXPECT_TRUE(UnfinishedSessions(dir + "/nowhere").empty());
}

TEST(SessionJournal, JournalDirFollowsTheEnvironment) {
  ::setenv("FORMSIM_STATE_DIR", "/tmp/fs_state_test", 1);
  EXPECT_EQ(JournalDir(), "/tmp/fs_state_test");
  ::unsetenv("FORMSIM_STATE_DIR");
  const char* xdg = std::getenv("XDG_STATE_HOME");
  const std::string saved = xdg ? xdg : "";
  ::setenv("XDG_STATE_HOME", "/tmp/xdg_state", 1);
  EXPECT_EQ(JournalDir(), "/tmp/xdg_state/formsim");
  if (saved.empty())
    ::unsetenv("XDG_STATE_HOME");
  else
    ::setenv("XDG_STATE_HOME", saved.c_str(), 1);
}

}  // namespace
}  // namespace formsim::sim
