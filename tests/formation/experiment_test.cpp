// The formation experiment end to end: scenarios, closed-loop convergence, estimation, events,
// determinism and the rejection of invalid scenario files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/formation/formation_experiment.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/session/session.hpp"
#include "tests/support/invalid_fixtures.hpp"
#include "tests/support/test_files.hpp"

namespace formsim::sim::formation {
namespace {

using testing::ShippedScenario;

std::unique_ptr<Experiment> RunScenario(const std::string& file,
                                        const std::vector<std::string>& sets = {}) {
  auto exp = LoadExperiment(file, sets);
  while (!exp->finished()) exp->Step();
  return exp;
}

const FormationExperiment& Formation(const std::unique_ptr<Experiment>& e) {
  return dynamic_cast<const FormationExperiment&>(*e);
}

// Noise-free, ideal drive, per-sample gains: the controlled outputs stay within 1e-3 after the
// initial transient (1 s) on the paper's trajectories 1 and 2.
TEST(FormationExperiment, ConvergesOnPaperTrajectoriesWithPerSampleGains) {
  for (const char* name : {"formation_traj1_per_sample", "formation_traj2_per_sample"}) {
    auto exp = RunScenario(ShippedScenario(name));
    const auto links = Formation(exp).Links();
    ASSERT_EQ(links.size(), 3u);
    for (const auto& l : links) {
      EXPECT_LT(l.e_l.max_abs_settled(), 1e-3) << name << " " << l.name;
      if (l.has_phi_target) {
        EXPECT_LT(l.e_phi.max_abs_settled(), 1e-3) << name << " " << l.name;
      }
      // The transient really happened: the paper's initial poses are far from s_des.
      EXPECT_GT(l.e_l.max_abs, 0.05) << name << " " << l.name;
      // α is not controlled; it stays bounded (|α| < π/2) as Theorem 1 predicts.
      EXPECT_LT(l.e_alpha.max_abs_settled(), 1.5707963267948966) << name << " " << l.name;
    }
  }
}

TEST(FormationExperiment, PrintedGainsAreTooSlowForThePapersErrors) {
  // k as printed gives time constants of 7-12 s: after 1 s the errors are still centimetres.
  auto exp = RunScenario(ShippedScenario("formation_traj2"));
  for (const auto& l : Formation(exp).Links()) {
    EXPECT_GT(l.e_l.max_abs_settled(), 0.05) << l.name;
    EXPECT_LT(l.e_l.max_abs_settled(), 0.2) << l.name;  // but it does converge slowly, not diverge
  }
}

TEST(FormationExperiment, PrintedBearingConventionDestabilisesTheFormation) {
  // The paper's printed eq. 4 fed to the controller: its derivative has the wrong sign, the
  // linearisation is wrong and the formation falls apart (distance errors of metres).
  auto exp =
      RunScenario(ShippedScenario("formation_traj2_per_sample"), {"formation.bearing=printed"});
  double worst = 0.0;
  for (const auto& l : Formation(exp).Links()) worst = std::max(worst, l.e_l.max_abs_settled());
  EXPECT_GT(worst, 1.0);
}

TEST(FormationExperiment, SevenRobotCascadeConverges) {
  auto exp = RunScenario(ShippedScenario("formation_cascade7"));
  const auto links = Formation(exp).Links();
  ASSERT_EQ(links.size(), 9u);  // 3 l-φ followers + 3 l-l followers × 2
  for (const auto& l : links) {
    EXPECT_LT(l.e_l.max_abs_settled(), 1e-3) << l.name;
    if (l.has_phi_target) {
      EXPECT_LT(l.e_phi.max_abs_settled(), 1e-3) << l.name;
    }
  }
  for (const auto& e : exp->events().list()) EXPECT_NE(e.kind, "singular") << e.message;
}

TEST(FormationExperiment, UkfFiltersThePapersAngleNoise) {
  auto ukf = RunScenario(ShippedScenario("formation_traj2_ukf"));
  auto raw = RunScenario(ShippedScenario("formation_traj2_noisy_raw"));
  const double sigma = std::sqrt(0.9186e-4);
  const auto lu = Formation(ukf).Links(), lr = Formation(raw).Links();
  for (std::size_t k = 0; k < lu.size(); ++k) {
    // Raw measurements are off by the sensor's σ; the filter's φ and α estimates are far better.
    EXPECT_NEAR(lr[k].est_phi.rms(), sigma, 0.15 * sigma) << lr[k].name;
    EXPECT_LT(lu[k].est_phi.rms(), 0.45 * sigma) << lu[k].name;
    EXPECT_LT(lu[k].est_alpha.rms(), 0.45 * sigma) << lu[k].name;
    // l is only weakly observable from angles: millimetres, not the noise-free 1e-4.
    EXPECT_LT(lu[k].est_l.rms(), 0.01) << lu[k].name;
    EXPECT_LT(lu[k].e_l.max_abs_settled(), 0.02) << lu[k].name;
    ASSERT_NE(lu[k].filter, nullptr);
  }
  for (const auto& e : ukf->events().list()) EXPECT_NE(e.kind, "filter_fault") << e.message;
}

TEST(FormationExperiment, UkfEstimateStaysInsideItsCovarianceMostOfTheTime) {
  // Consistency in the closed loop: the recorded φ and α errors lie within ±2σ of the filter's
  // own standard deviation most of the time after the transient.
  auto exp = RunScenario(ShippedScenario("formation_traj2_ukf"));
  const Recorder& rec = exp->recorder();
  for (const std::string link : {"R1-R2", "R1-R3", "R2-R3"}) {
    for (const std::string q : {"phi", "alpha"}) {
      const int ce = rec.Column(link + "." + q + "_est_err"),
                cs = rec.Column(link + "." + q + "_sd");
      ASSERT_GE(ce, 0);
      ASSERT_GE(cs, 0);
      int inside = 0, n = 0;
      for (std::size_t r = 0; r < rec.rows(); ++r) {
        if (rec.At(r, 0) < 1.0) continue;
        inside += std::abs(rec.At(r, ce)) <= 2.0 * rec.At(r, cs);
        ++n;
      }
      EXPECT_GT(static_cast<double>(inside) / n, 0.9) << link << " " << q;
    }
  }
}

TEST(FormationExperiment, FilterFaultsAreReportedNotPropagated) {
  // A negative centre weight (κ = −2.5: W0 = −5) with a wide initial spread of the angles makes
  // the predicted covariance indefinite: every fault must become a counted step and an event
  // (on entry), never a NaN in the outputs.
  auto exp = RunScenario(ShippedScenario("formation_traj2_ukf"),
                         {"ukf.kappa=-2.5", "ukf.p0_phi=3", "ukf.p0_alpha=3", "duration=1"});
  int events = 0;
  for (const auto& e : exp->events().list())
    if (e.kind == "filter_fault") {
      ++events;
      EXPECT_TRUE(e.robots == "R2" || e.robots == "R3") << e.robots;
      EXPECT_NE(e.message.find("at t = "), std::string::npos) << e.message;
      EXPECT_NE(e.message.find("not positive definite"), std::string::npos) << e.message;
    }
  int steps = 0;
  for (const auto& l : Formation(exp).Links()) steps += l.filter_faults;
  EXPECT_GT(events, 0);
  EXPECT_GE(steps, events);
  EXPECT_LE(events, 3);  // one per link: the restarts keep faulting, which is one long episode
  const Recorder& rec = exp->recorder();
  for (std::size_t r = 0; r < rec.rows(); ++r)
    for (std::size_t c = 0; c < rec.columns(); ++c)
      ASSERT_TRUE(std::isfinite(rec.At(r, static_cast<int>(c))))
          << rec.names()[c] << " at row " << r;
  EXPECT_NE(exp->Summary().Dump().find("\"filter_fault_steps\""), std::string::npos);
}

TEST(FormationExperiment, SingularLLFollowerIsReportedOnce) {
  // R3's control point starts on the line through its leaders R1 and R2 (both ahead, in a
  // line along x): the l-l law is singular there.
  const std::string yaml = R"(
type: formation
dt: 0.01
duration: 4
formation: {gain_reading: per_sample}
robots:
  - name: R1
    pose: [0, 0, 0]
    schedule: {kind: segments, segments: [{until: 100, v: 1.0, w: 0.0}]}
  - name: R2
    pose: [-0.75, 0, 0]
    follow: {law: l_phi, leaders: [R1], l_des: 0.6, phi_des: 3.141592653589793}
  - name: R3
    pose: [-0.45, -0.04432801011886646, 0.3]
    follow: {law: l_l, leaders: [R1, R2], l_des: 0.4, l2_des: 0.4}
)";
  auto exp = LoadExperimentFromText(yaml, "singular.yaml");
  while (!exp->finished()) exp->Step();
  std::vector<Event> singular;
  for (const auto& e : exp->events().list())
    if (e.kind == "singular") singular.push_back(e);
  ASSERT_EQ(singular.size(), 1u);
  EXPECT_EQ(singular[0].robots, "R1,R2,R3");
  EXPECT_DOUBLE_EQ(singular[0].time, 0.0);
  // The regularised law leaves the line and the formation converges.
  const Recorder& rec = exp->recorder();
  const int cs = rec.Column("R3.sin_ll");
  ASSERT_GE(cs, 0);
  EXPECT_LT(std::abs(rec.At(0, cs)), 0.1);
  EXPECT_GT(std::abs(rec.At(rec.rows() - 1, cs)), 0.5);
  for (const auto& l : Formation(exp).Links())
    EXPECT_LT(std::abs(l.truth.l - (l.name == "R1-R2" ? 0.6 : 0.4)), 1e-3) << l.name;
}

TEST(FormationExperiment, SaturationIsReportedOnEntry) {
  auto exp =
      RunScenario(ShippedScenario("formation_traj2_per_sample"), {"robots.R2.drive.omega_max=2"});
  int sat = 0;
  for (const auto& e : exp->events().list()) sat += e.kind == "saturation" && e.robots == "R2";
  EXPECT_GE(sat, 1);
  EXPECT_LT(sat, 20);  // once per entry, not once per step
  const Recorder& rec = exp->recorder();
  EXPECT_EQ(rec.At(1, rec.Column("R2.sat")), 1.0);
}

TEST(FormationExperiment, SameSeedSameCsv) {
  auto csv = [](const std::string& dir) {
    auto exp = RunScenario(ShippedScenario("formation_traj2_ukf"), {"duration=3"});
    std::filesystem::create_directories(dir);
    exp->recorder().WriteCsv(dir + "/t.csv");
    std::ifstream f(dir + "/t.csv");
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  };
  const std::string tmp = std::string(FORMSIM_BINARY_DIR) + "/test_out/formation_det";
  const std::string a = csv(tmp + "_a"), b = csv(tmp + "_b");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
  // A different seed changes the noise.
  auto c = LoadExperiment(ShippedScenario("formation_traj2_ukf"), {"duration=3"}, 12345);
  while (!c->finished()) c->Step();
  std::filesystem::create_directories(tmp + "_c");
  c->recorder().WriteCsv(tmp + "_c/t.csv");
  std::ifstream f(tmp + "_c/t.csv");
  std::stringstream s;
  s << f.rdbuf();
  EXPECT_NE(a, s.str());
}

TEST(FormationExperiment, EveryShippedScenarioLoadsAndHasADescription) {
  for (const char* name :
       {"formation_traj1", "formation_traj2", "formation_traj3", "formation_traj1_per_sample",
        "formation_traj2_per_sample", "formation_traj3_per_sample", "formation_traj2_noisy_raw",
        "formation_traj2_ukf", "formation_cascade7"}) {
    auto exp = LoadExperiment(ShippedScenario(name));
    EXPECT_FALSE(exp->setup().description.empty()) << name;
    EXPECT_EQ(exp->setup().type, "formation");
    EXPECT_FALSE(exp->Figures().empty());
  }
}

TEST(FormationExperiment, ParamsAreYamlPathsThatSetAccepts) {
  Session s(ShippedScenario("formation_traj2_ukf"), {}, -1);
  for (const char* key :
       {"robots.R2.follow.k_l", "robots.R2.follow.phi_des", "robots.R3.follow.l2_des",
        "noise.phi_variance", "ukf.q_phi", "robots.R1.schedule.omega", "robots.R2.follow.estimator",
        "robots.R3.drive.v_max", "formation.gain_reading"}) {
    ASSERT_NE(s.params().Find(key), nullptr) << key;
  }
  // Each key also works through --set (same YAML path).
  Session edited(ShippedScenario("formation_traj2_ukf"), {"robots.R2.follow.k_l=0.2"}, -1);
  EXPECT_EQ(edited.params().Find("robots.R2.follow.k_l")->value, 0.2);
  // A live edit takes effect between two steps.
  EXPECT_EQ(s.Edit("robots.R2.follow.estimator", "truth"), "");
  s.Step();
  EXPECT_EQ(dynamic_cast<const FormationExperiment&>(s.exp()).config().robots[1].follow.estimator,
            EstimatorMode::kTruth);
}

// Every tests/fixtures/invalid/formation_*.yaml starts with "# expect: <text>"; loading it must
// throw a ScenarioError that contains the text and points at a line holding the offending key.
TEST(FormationExperiment, InvalidFixturesAreRejectedWithTheRightMessage) {
  const int checked = formsim::testing::CheckInvalidFixtures("formation_");
  EXPECT_GE(checked, 12);
}

}  // namespace
}  // namespace formsim::sim::formation

namespace formsim::sim::formation {
namespace {

// One contact is one collision everywhere: the results' headline (the GUI's Tables tab, the
// history, Monte Carlo) equals summary.json's event count, though the contact involves robots of
// several links (formation_traj2_ukf: one contact, and each of its three links saw it).
TEST(FormationExperiment, ACollisionIsCountedOncePerContact) {
  auto exp = RunScenario(ShippedScenario("formation_traj2_ukf"));
  const long contacts = exp->events().Count(event::kCollision);
  ASSERT_GT(contacts, 0) << "the scenario has a contact";
  double per_link = 0;
  for (const char* l : {"R1-R2", "R1-R3", "R2-R3"})
    per_link += *exp->Results().Find(std::string("links.") + l + ".events.collision");
  EXPECT_GT(per_link, static_cast<double>(contacts)) << "links share the contact";
  bool found = false;
  for (const Metrics::HeadlineValue& h : exp->Results().Headlines())
    if (h.label == "collisions") {
      found = true;
      EXPECT_EQ(h.value, static_cast<double>(contacts));
    }
  EXPECT_TRUE(found);
  EXPECT_EQ(*exp->Results().Find("events.collision"), static_cast<double>(contacts));
}

}  // namespace
}  // namespace formsim::sim::formation
