// Building and reshaping a formation through the session (Session::Restructure and slot edits):
// every change goes through the loader's checks, refused changes leave the run as it was, undo /
// redo take changes back, Save writes a scenario that reproduces the run, and a session record
// replays it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "sim/formation/formation_edit.hpp"
#include "sim/formation/formation_editing.hpp"
#include "sim/formation/formation_experiment.hpp"
#include "sim/formation/formation_follow.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/session/session.hpp"
#include "sim/session/session_record.hpp"
#include "tests/support/test_files.hpp"

namespace formsim::sim::formation {
namespace {

using testing::ShippedScenario;

std::string TempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "formsim_restructure_test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

void StepTo(Session& s, long step) {
  while (s.exp().steps() < step && !s.exp().finished()) s.Step();
}

const FormationExperiment& Formation(const Session& s) {
  return dynamic_cast<const FormationExperiment&>(s.exp());
}

std::vector<std::string> RobotNames(const Experiment& e) {
  std::vector<std::string> out;
  for (const auto& r : e.world().robots()) out.push_back(r->name());
  return out;
}

// The last recorded value of a channel.
double Last(const Experiment& e, const std::string& channel) {
  const int c = e.recorder().Column(channel);
  EXPECT_GE(c, 0) << channel;
  return c < 0 ? 1e9 : e.recorder().At(e.recorder().rows() - 1, c);
}

void ExpectSamePoses(const Experiment& a, const Experiment& b) {
  ASSERT_EQ(a.world().robots().size(), b.world().robots().size());
  for (std::size_t i = 0; i < a.world().robots().size(); ++i) {
    const Pose2 p = a.world().robots()[i]->pose(), q = b.world().robots()[i]->pose();
    EXPECT_EQ(p.x, q.x) << i;
    EXPECT_EQ(p.y, q.y) << i;
    EXPECT_EQ(p.theta, q.theta) << i;
  }
}

TEST(Restructure, AddAFollowerWhileRunningKeepsTheRobotsWhereTheyAre) {
  Session s(ShippedScenario("formation_traj2_per_sample"), {}, -1);
  StepTo(s, 150);
  const Pose2 r2 = s.exp().world().robots()[1]->pose();
  // A follower of R2, placed 0.4 m behind-right of it.
  const double x = r2.x - 0.4 * std::cos(r2.theta), y = r2.y - 0.4 * std::sin(r2.theta) - 0.2;
  ASSERT_EQ(Restructure(s, "add l_phi R2 " + std::to_string(x) + " " + std::to_string(y)), "");
  EXPECT_EQ(RobotNames(s.exp()), (std::vector<std::string>{"R1", "R2", "R3", "R4"}));
  EXPECT_EQ(s.exp().steps(), 0);  // a new run from the state of the old one
  const Pose2 r2_now = s.exp().world().robots()[1]->pose();
  EXPECT_NEAR(r2_now.x, r2.x, 1e-12);
  EXPECT_NEAR(r2_now.y, r2.y, 1e-12);
  EXPECT_NE(s.params().Find("robots.R4.follow.phi_des"), nullptr);
  // Placed on its own slot: the new link starts (and stays) with a small error.
  StepTo(s, 300);
  EXPECT_LT(std::abs(Last(s.exp(), "R2-R4.e_l")), 0.02);
  EXPECT_LT(std::abs(Last(s.exp(), "R2-R4.e_phi")), 0.1);
  EXPECT_EQ(s.restructures(), 1);
}

TEST(Restructure, RefusedChangesNameTheirReasonAndLeaveTheRun) {
  Session s(ShippedScenario("formation_traj2_per_sample"), {}, -1);
  StepTo(s, 40);
  const Experiment* before = &s.exp();
  // A cycle: the root made a follower of its own follower.
  std::string err = Restructure(s, "attach R1 l_phi R2");
  EXPECT_NE(err.find("cycle"), std::string::npos) << err;
  // A missing leader: R1 removed while R2 and R3 follow it.
  err = Restructure(s, "remove R1");
  EXPECT_NE(err.find("not a robot of this scenario"), std::string::npos) << err;
  // An impossible triangle: an l-l follower on the line through its leaders, beyond R1.
  const Pose2 p1 = s.exp().world().robots()[0]->pose(), p2 = s.exp().world().robots()[1]->pose();
  const Vec2 out = p1.p() + (p1.p() - p2.p()) * 1.0;
  err = Restructure(s, "add l_l R1,R2 " + std::to_string(out.x - 0.15 * std::cos(p1.theta)) + " " +
                           std::to_string(out.y - 0.15 * std::sin(p1.theta)));
  EXPECT_NE(err.find("triangle"), std::string::npos) << err;
  // Malformed commands.
  EXPECT_NE(Restructure(s, "add l_x R1 0 0").find("law must be"), std::string::npos);
  EXPECT_NE(Restructure(s, "add l_phi R9 0 0").find("R9"), std::string::npos);
  EXPECT_NE(Restructure(s, "shape hexagon").find("shape"), std::string::npos);
  EXPECT_NE(Restructure(s, "fly R2").find("unknown formation command"), std::string::npos);
  EXPECT_NE(Restructure(s, "add l_phi R1 nan 0").find("number"), std::string::npos);
  // Nothing changed: the same experiment at the same step, and it still runs.
  EXPECT_EQ(&s.exp(), before);
  EXPECT_EQ(s.exp().steps(), 40);
  EXPECT_EQ(s.restructures(), 0);
  EXPECT_FALSE(s.rejected().empty());
  StepTo(s, 60);
  EXPECT_EQ(s.exp().steps(), 60);
}

TEST(Restructure, UndoAndRedoTakeStructuralChangesBack) {
  Session s(ShippedScenario("formation_cascade7"), {}, -1);
  StepTo(s, 20);
  ASSERT_EQ(s.Edit("robots.R2.follow.k_l", "0.2"), "");
  StepTo(s, 30);
  ASSERT_EQ(Restructure(s, "remove R7"), "");
  EXPECT_EQ(s.exp().world().robots().size(), 6u);
  EXPECT_EQ(s.UndoText(), "formation: remove R7");
  // The edit before it is in the new scenario's text.
  EXPECT_EQ(s.EffectiveValue("robots.R2.follow.k_l"), "0.2");
  StepTo(s, 10);
  ASSERT_EQ(s.Undo(), "");
  EXPECT_EQ(s.exp().world().robots().size(), 7u);
  ASSERT_EQ(s.Redo(), "");
  EXPECT_EQ(s.exp().world().robots().size(), 6u);
  ASSERT_EQ(s.Undo(), "");
  ASSERT_EQ(s.Undo(), "");  // the k_l edit
  EXPECT_EQ(s.EffectiveValue("robots.R2.follow.k_l"), "0.15");
  // Switch R4 from l-φ (to R2) to l-l (R2, R5's leader R3) and back.
  ASSERT_EQ(Restructure(s, "attach R4 l_l R2,R3"), "");
  EXPECT_EQ(Formation(s).LeadersOf("R4"), (std::vector<std::string>{"R2", "R3"}));
  EXPECT_NE(s.params().Find("robots.R4.follow.l2_des"), nullptr);
  EXPECT_EQ(s.params().Find("robots.R4.follow.phi_des"), nullptr);
  ASSERT_EQ(Restructure(s, "attach R4 l_phi R2"), "");
  EXPECT_EQ(Formation(s).LeadersOf("R4"), (std::vector<std::string>{"R2"}));
}

TEST(Restructure, EveryShapeHoldsTogetherWithoutCollisions) {
  for (const char* shape : {"column", "line_abreast", "wedge", "diamond", "v", "grid"}) {
    SCOPED_TRACE(shape);
    Session s(ShippedScenario("formation_cascade7"), {}, -1);
    StepTo(s, 50);
    ASSERT_EQ(Restructure(s, std::string("shape ") + shape + " 0.6"), "");
    StepTo(s, 400);  // 4 s
    EXPECT_EQ(s.exp().events().Count("collision"), 0);
    EXPECT_FALSE(s.exp().finished() && s.exp().status() != "completed");
    for (const auto& l : Formation(s).Links()) EXPECT_LT(std::abs(Last(s.exp(), l.name + ".e_l")), 0.02) << l.name;
  }
}

TEST(Restructure, SaveWritesAScenarioThatReproducesTheRun) {
  Session s(ShippedScenario("formation_traj2_per_sample"), {}, -1);
  StepTo(s, 100);
  ASSERT_EQ(Restructure(s, "shape diamond 0.5"), "");
  ASSERT_EQ(s.Edit("robots.R3.follow.k_l", "0.1"), "");
  StepTo(s, 30);
  // The diamond's fourth slot, 2 rows (2 · 0.5 · √3/2 m) behind R1: l-l to R2 and R3.
  const Pose2 r1 = s.exp().world().robots()[0]->pose();
  const double back = 0.5 * std::sqrt(3.0);
  ASSERT_EQ(Restructure(s, "add l_l R2,R3 " + std::to_string(r1.x - back * std::cos(r1.theta)) +
                               " " + std::to_string(r1.y - back * std::sin(r1.theta))),
            "");
  StepTo(s, 120);
  const std::string path = TempPath("saved_formation.yaml");
  ASSERT_EQ(s.Save(path, true), Session::SaveResult::kSaved);
  auto again = LoadExperiment(path);
  while (again->steps() < 120) again->Step();
  ExpectSamePoses(s.exp(), *again);
}

TEST(Restructure, ASessionRecordReplaysStructuralChanges) {
  SessionRecord record;
  Session s(ShippedScenario("formation_cascade7"), {}, -1);
  SessionEvent load;
  load.kind = SessionEvent::Kind::kLoad;
  load.source = std::make_shared<ScenarioSource>(s.source());
  record.Add(load);
  s.SetObserver([&](const SessionEvent& e) { record.Add(e); });
  StepTo(s, 25);
  ASSERT_EQ(Restructure(s, "shape v 0.6"), "");
  StepTo(s, 40);
  const auto slot = EditingOf(s.exp())->SlotEdits(
      "R3", s.exp().world().robots()[0]->pose().p() + Vec2{-0.6, -0.5});
  for (const auto& [k, v] : slot) ASSERT_EQ(s.Edit(k, v, "slot drag"), "");
  StepTo(s, 70);
  ASSERT_EQ(s.Undo(), "");  // the last slot edit
  StepTo(s, 90);
  SessionReplay replay(SessionRecord::Parse(record.ToYaml(s.exp().steps()), "record"));
  while (replay.Advance()) {
  }
  EXPECT_EQ(replay.session().exp().steps(), 90);
  ExpectSamePoses(s.exp(), replay.session().exp());
}

TEST(Restructure, DraggingASlotMovesTheFollowerThere) {
  Session s(ShippedScenario("formation_traj1_per_sample"), {}, -1);
  StepTo(s, 100);
  const Pose2 r1 = s.exp().world().robots()[0]->pose();
  // R2's slot moved from 0.3 m to 0.4 m behind-right of R1 (R3's l-l triangle with R1 and R2
  // still closes: their separation stays under 0.6 m).
  const double b = r1.theta + 5 * M_PI / 4;
  const Vec2 target = r1.p() + Vec2{std::cos(b), std::sin(b)} * 0.4;
  const auto edits = EditingOf(s.exp())->SlotEdits("R2", target);
  ASSERT_EQ(edits.size(), 2u);
  EXPECT_EQ(edits[0].first, "robots.R2.follow.l_des");
  EXPECT_EQ(edits[1].first, "robots.R2.follow.phi_des");
  for (const auto& [k, v] : edits) ASSERT_EQ(s.Edit(k, v, "slot drag", true), "");
  EXPECT_NEAR(std::stod(s.EffectiveValue("robots.R2.follow.l_des")), 0.4, 1e-12);
  EXPECT_NEAR(std::stod(s.EffectiveValue("robots.R2.follow.phi_des")), 5 * M_PI / 4, 1e-9);
  // The bearing stayed 5π/4: the drag is one undo step (of l_des).
  EXPECT_EQ(s.Undo(), "");
  EXPECT_EQ(s.EffectiveValue("robots.R2.follow.l_des"), "0.3");
  EXPECT_FALSE(s.can_undo());
  ASSERT_EQ(s.Redo(), "");
  StepTo(s, 400);
  for (const auto& l : Formation(s).Links())
    if (l.name == "R1-R2") {
      EXPECT_NEAR(l.truth.l, 0.4, 1e-2);
      EXPECT_NEAR(control::WrapTo2Pi(l.truth.phi), 5 * M_PI / 4, 2e-2);
    }
  EXPECT_THROW(EditingOf(s.exp())->SlotEdits("R1", target),
               std::runtime_error);  // the root has no slot
}

TEST(Restructure, TheTextKeepsItsHeaderAndLoadsAlone) {
  Session s(ShippedScenario("formation_cascade7"), {}, -1);
  FormationState st;
  for (const auto& r : s.exp().world().robots()) st.poses[r->name()] = r->pose();
  const std::string text = RestructureFormationText(s.source().text(), {RemoveRobot{"R7"}}, st);
  EXPECT_EQ(text.rfind("# A 7-robot cascade", 0), 0u);
  EXPECT_EQ(text.find("name: R7"), std::string::npos);
  EXPECT_EQ(LoadExperimentFromText(text, "edited")->world().robots().size(), 6u);
}

TEST(Restructure, TypedChangesAndTheirTextFormAgree) {
  // The text form is only the edge (script action, record): each typed change prints as it
  // parses back.
  const std::vector<std::string> texts = {"add l_phi R1 0.5 -0.3",
                                          "add l_l R1,R2 -1.25 2 R9",
                                          "remove R7",
                                          "attach R4 l_l R2,R3",
                                          "shape v",
                                          "shape diamond 0.6"};
  for (const std::string& t : texts) EXPECT_EQ(StructureChangeText(ParseStructureChange(t)), t);
  EXPECT_THROW(ParseStructureChange("add l_x R1 0 0"), std::runtime_error);
  EXPECT_THROW(ParseStructureChange("shape hexagon"), std::runtime_error);
  EXPECT_THROW(ParseStructureChange("attach R4"), std::runtime_error);
  // A typed change and its text give the same scenario.
  Session a(ShippedScenario("formation_cascade7"), {}, -1),
      b(ShippedScenario("formation_cascade7"), {}, -1);
  StepTo(a, 20);
  StepTo(b, 20);
  ASSERT_EQ(Restructure(a, StructureChange{AttachFollower{"R4", cf::FormationLaw::kLPhi, {"R2"}}}),
            "");
  ASSERT_EQ(Restructure(b, "attach R4 l_phi R2"), "");
  EXPECT_EQ(a.source().text(), b.source().text());
  EXPECT_EQ(a.UndoText(), b.UndoText());
}

TEST(Restructure, AFormationOffersItsCapability) {
  // (A kind without it: tests/sim/test_experiment.cpp.)
  Session s(ShippedScenario("formation_cascade7"), {}, -1);
  ASSERT_NE(EditingOf(s.exp()), nullptr);
  EXPECT_EQ(s.exp().As<StructureEditing>(), EditingOf(s.exp()));
  EXPECT_EQ(EditingOf(s.exp())->LeadersOf("R4"), Formation(s).LeadersOf("R4"));
}

TEST(FollowBlock, WrittenTheSameByEveryWriter) {
  FollowBlock b;
  b.law = cf::FormationLaw::kLL;
  b.leaders = {"R1", "R2"};
  b.l_des = 0.5;
  b.second_des = 0.25;
  b.k1 = b.k2 = 0.15;
  b.estimator = "ukf";
  b.measure = {"l", "phi", "alpha"};
  EXPECT_EQ(FollowText(b),
            "{law: l_l, leaders: [R1, R2], l_des: 0.5, l2_des: 0.25, k_l: 0.15, "
            "k_l2: 0.15, estimator: ukf, measure: [l, phi, alpha]}");
  // Over an existing block: the other law's keys go, the rest stays where it was.
  YAML::Node f =
      YAML::Load("{law: l_l, leaders: [R1, R2], l_des: 1, l2_des: 1, k_l2: 0.3, k_l: 0.2}");
  FollowBlock p;
  p.leaders = {"R1"};
  p.l_des = 0.4;
  p.second_des = 3;
  WriteFollow(f, p);
  YAML::Emitter out;
  out << f;
  EXPECT_EQ(std::string(out.c_str()),
            "{law: l_phi, leaders: [R1], l_des: 0.4, k_l: 0.2, phi_des: 3}");
}

}  // namespace
}  // namespace formsim::sim::formation
