// The tuning session behind the GUI: edits apply between steps, bad edits are refused with a
// reason, requires_reset edits wait for a reset, and a saved tuned scenario loads back the same.
#include "app/session.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Scenario;
using testing::TempDir;

// First parameter of a kind that is live (or not), for tests that must not hard-code keys.
const sim::Param* FindParam(sim::Experiment& exp, sim::Param::Kind kind, bool requires_reset) {
  for (const auto& p : exp.params().all())
    if (p.kind == kind && p.requires_reset == requires_reset) return &p;
  return nullptr;
}

TEST(Session, LiveEditAppliesBeforeTheNextStepOnly) {
  Session s(Scenario("formation_traj2"), {}, -1);
  const sim::Param* p = FindParam(s.exp(), sim::Param::Kind::kDouble, false);
  ASSERT_NE(p, nullptr);
  const double before = *p->d, target = 0.5 * (p->min + p->max);
  ASSERT_NE(before, target);
  s.Edit(p->key, ExactDouble(target));
  EXPECT_EQ(*p->d, before) << "an edit must not touch the experiment until it is applied";
  s.Step();
  EXPECT_EQ(*p->d, target);
  EXPECT_TRUE(s.rejected().empty());
  EXPECT_EQ(s.accepted_edits(), 1);
}

TEST(Session, MalformedEditsAreRejectedWithTheKey) {
  Session s(Scenario("formation_traj2"), {}, -1);
  const sim::Param* p = FindParam(s.exp(), sim::Param::Kind::kDouble, false);
  ASSERT_NE(p, nullptr);
  const double before = *p->d;
  s.Edit(p->key, "abc");
  s.Edit(p->key, "nan");
  s.Edit("no.such.key", "1");
  s.Step();
  EXPECT_EQ(*p->d, before);
  ASSERT_EQ(s.rejected().size(), 3u);
  EXPECT_NE(s.rejected()[0].find(p->key), std::string::npos);
  EXPECT_NE(s.rejected()[2].find("no.such.key"), std::string::npos);
  for (int i = 0; i < 10; ++i) s.Step();
  EXPECT_TRUE(std::isfinite(s.exp().time()));
}

TEST(Session, ResetParametersWaitForReset) {
  Session s(Scenario("formation_traj2_ukf"), {}, -1);
  const sim::Param* p = FindParam(s.exp(), sim::Param::Kind::kDouble, true);
  if (p == nullptr) GTEST_SKIP() << "scenario has no requires_reset parameter";
  const std::string key = p->key;
  const double before = *p->d, target = p->min + 0.25 * (p->max - p->min);
  s.Edit(key, ExactDouble(target));
  s.Step();
  EXPECT_EQ(*s.exp().params().Find(key)->d, before) << "requires_reset must not apply live";
  EXPECT_EQ(s.waiting_for_reset().count(key), 1u);
  s.Reset();
  EXPECT_EQ(*s.exp().params().Find(key)->d, target);
  EXPECT_EQ(s.exp().time(), 0.0);
  EXPECT_TRUE(s.waiting_for_reset().empty());
}

TEST(Session, SavedTunedScenarioLoadsBackTheSame) {
  const std::string dir = TempDir("session_save");
  Session s(Scenario("formation_traj2_ukf"), {}, -1);
  // Tune one parameter of every kind we find (live ones through steps, reset ones in the tree).
  int tuned = 0;
  for (const auto& p : s.exp().params().all()) {
    std::string v;
    switch (p.kind) {
      case sim::Param::Kind::kDouble:
        v = ExactDouble(p.min + 0.37 * (p.max - p.min));
        break;
      case sim::Param::Kind::kInt:
        v = std::to_string(static_cast<int>(p.max));
        break;
      case sim::Param::Kind::kBool:
        v = *p.b ? "false" : "true";
        break;
      case sim::Param::Kind::kChoice:
        v = p.choices.back();
        break;
    }
    s.Edit(p.key, v);
    ++tuned;
  }
  ASSERT_GT(tuned, 3);
  s.Step();
  ASSERT_TRUE(s.rejected().empty()) << s.rejected().front();

  const std::string file = dir + "/tuned.yaml";
  ASSERT_EQ(s.Save(file), Session::SaveResult::kSaved);
  EXPECT_EQ(s.Save(file), Session::SaveResult::kNeedsConfirmation) << "must not overwrite silently";
  EXPECT_FALSE(Session::IsShipped(file));
  EXPECT_TRUE(Session::IsShipped(Scenario("formation_traj2")));

  s.Reset();  // the tuned run, from t = 0
  Session back(file, {}, -1);
  const auto& a = s.exp().params().all();
  const auto& b = back.exp().params().all();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].key, b[i].key);
    EXPECT_EQ(sim::ParamTable::ToString(a[i]), sim::ParamTable::ToString(b[i])) << a[i].key;
  }
  // Same scenario: the same steps give the same recorded numbers, bit for bit.
  for (int i = 0; i < 150; ++i) {
    s.Step();
    back.Step();
  }
  const auto& ra = s.exp().recorder();
  const auto& rb = back.exp().recorder();
  ASSERT_EQ(ra.rows(), rb.rows());
  for (std::size_t r = 0; r < ra.rows(); ++r)
    for (std::size_t c = 0; c < ra.columns(); ++c) {
      const double x = ra.At(r, static_cast<int>(c)), y = rb.At(r, static_cast<int>(c));
      ASSERT_TRUE((std::isnan(x) && std::isnan(y)) || x == y) << ra.names()[c] << " row " << r;
    }
}

}  // namespace
}  // namespace formsim::app
