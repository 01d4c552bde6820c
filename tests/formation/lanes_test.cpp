// The link filters' time and measurement updates in SIMD lanes
// (control/formation/link_predict_lanes.hpp, link_update_lanes.hpp) give the same bits as each
// filter's own Predict and Update: link by link on states that cover every branch
// of the scalar code (all four quadrants of the sines, both cosine forms, angles at and across
// ±π, spreads beyond the small-angle polynomials, non-finite inputs, substeps), and run by run
// on the shipped formation scenarios, CSV and summary byte for byte, with one and two threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <utility>

#include "control/formation/link_predict_lanes.hpp"
#include "control/formation/link_update_lanes.hpp"
#include "sim/core/run_output.hpp"
#include "sim/formation/formation_experiment.hpp"
#include "sim/scenario/scenario.hpp"
#include "tests/support/test_files.hpp"

namespace formsim::sim::formation {
namespace {

namespace cf = control::formation;
using control::UkfStatus;

// Sets the process-wide path for one scope.
struct PathScope {
  explicit PathScope(cf::LanePath p) : saved(cf::CurrentLanePath()) { cf::SetLanePath(p); }
  ~PathScope() { cf::SetLanePath(saved); }
  cf::LanePath saved;
};

std::vector<cf::LanePath> LanePaths() {
  std::vector<cf::LanePath> paths{cf::LanePath::kPortable};
  if (formsim::control::CpuHasAvx2()) paths.push_back(cf::LanePath::kAvx2);
  return paths;
}

bool SameBytes(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 9) == 0;
}
bool SameBytes(const cf::LinkState& a, const cf::LinkState& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// One link's filter state before a prediction, and its inputs.
struct Case {
  cf::LinkState x0;
  Eigen::Vector3d p0;  // P0's diagonal
  double p_phi_alpha;  // P0's (φ, α) covariance
  bool update_first;   // an update before the prediction (a Cholesky factor kept), else a
                       // prediction (P only checked: the batch factors it first)
  cf::Twist leader, follower;
  int substeps = 1;
  cf::MeasurementSet measure = cf::MeasurementSet::kPhiAlpha;
};

std::vector<Case> MakeCases() {
  std::vector<Case> cases;
  std::mt19937_64 rng(28);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double pi = control::kPi;
  // Angles at the edges: exactly 0 and −0 (SinCosOf keeps the sign), ±π and next to them (the
  // sigma points cross ±π: wrapped deviations), and the quadrants' borders.
  const double edges[] = {0.0,         -0.0,    pi,     -pi + 1e-12, pi - 1e-9,
                          pi / 4,      -pi / 4, pi / 2, -pi / 2,     3 * pi / 4,
                          -3 * pi / 4, 0.3,     -0.3,   0.78125,     1e-300};
  for (double phi : edges)
    for (double alpha : edges)
      cases.push_back({{0.5 + 0.1 * u(rng), phi, alpha},
                       {1e-4, 1e-4, 1e-4},
                       0.0,
                       cases.size() % 2 == 0,
                       {0.3, 0.2},
                       {0.31, -0.1}});
  for (int k = 0; k < 3000; ++k) {
    Case c;
    c.x0 = {0.05 + 2.0 * std::abs(u(rng)), pi * u(rng), pi * u(rng)};
    // Spreads from tiny to beyond the small-angle polynomials' 1/8 (those lanes fall back).
    const double spread = std::pow(10.0, -6.0 + 5.5 * std::abs(u(rng)));
    c.p0 = {spread * (0.5 + std::abs(u(rng))), spread * (0.5 + std::abs(u(rng))),
            spread * (0.5 + std::abs(u(rng)))};
    c.p_phi_alpha = 0.3 * u(rng) * std::sqrt(c.p0(1) * c.p0(2));
    c.update_first = k % 3 != 0;
    c.leader = {u(rng), 2.0 * u(rng)};
    c.follower = {u(rng), 2.0 * u(rng)};
    c.measure = static_cast<cf::MeasurementSet>(k % 3);
    if (k % 97 == 0) c.substeps = 3;  // not a lane's model: Predict runs it
    if (k % 89 == 0) c.follower.v = std::nan("");
    if (k % 83 == 0) c.follower.w = 1e300;  // overflows to infinity in the lanes too
    cases.push_back(c);
  }
  return cases;
}

std::unique_ptr<cf::LinkFilter> Prepared(const Case& c) {
  cf::LinkFilterDef d;
  d.measure = c.measure;
  d.substeps = c.substeps;
  auto f = cf::LinkFilter::Make(d);
  Eigen::Matrix3d P0 = c.p0.asDiagonal();
  P0(1, 2) = P0(2, 1) = c.p_phi_alpha;
  f->Reset(c.x0, P0);
  // A first prediction (from Reset: the sigma points of P0 itself) leaves P checked only.
  f->Predict(c.leader, c.follower);
  if (c.update_first) f->Update(c.x0);
  return f;
}

// The same state and covariance, bit for bit.
::testing::AssertionResult SameFilter(const cf::LinkFilter& a, const cf::LinkFilter& b) {
  if (SameBytes(a.state(), b.state()) && SameBytes(a.cov(), b.cov()))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "state or covariance differs";
}

// Calls `add(batch, i)` for every i < n on one batch, flushes it, and returns how many links ran
// in lanes and how many off them.
template <class Batch, class Add>
std::pair<std::size_t, std::size_t> RunBatch(std::size_t n, Add add) {
  Batch batch;
  for (std::size_t i = 0; i < n; ++i) add(batch, i);
  batch.Flush();
  return {batch.laned(), batch.fell_back()};
}

// Most links of a batch ran in lanes and over a hundred off their common path.
void ExpectBothKinds(std::size_t laned, std::size_t fell_back, std::size_t n, cf::LanePath path) {
  EXPECT_GT(laned, n / 2) << cf::LanePathName(path);
  EXPECT_GT(fell_back, 100u) << cf::LanePathName(path);
}

// Two filters in the same state for every case: one run alone, one batched. `predicted`: each
// after one more prediction (what a measurement update follows).
struct Twins {
  std::vector<std::unique_ptr<cf::LinkFilter>> reference, batched;
  Twins(const std::vector<Case>& cases, bool predicted) {
    for (const Case& c : cases)
      for (auto* v : {&reference, &batched}) {
        v->push_back(Prepared(c));
        if (predicted) v->back()->Predict(c.leader, c.follower);
      }
  }
};

TEST(PredictLanes, EachLinkGetsTheBitsOfItsOwnPredict) {
  const std::vector<Case> cases = MakeCases();
  for (cf::LanePath path : LanePaths()) {
    PathScope scope(path);
    Twins twins(cases, false);
    auto& reference = twins.reference;
    auto& batched = twins.batched;
    std::vector<UkfStatus> want(cases.size()), got(cases.size(), UkfStatus::kOk);
    for (std::size_t i = 0; i < cases.size(); ++i)
      want[i] = reference[i]->Predict(cases[i].leader, cases[i].follower);
    const auto ran = RunBatch<cf::LinkPredictBatch>(cases.size(), [&](auto& batch, std::size_t i) {
      batch.Add(*batched[i], cases[i].leader, cases[i].follower, &got[i]);
    });
    for (std::size_t i = 0; i < cases.size(); ++i) {
      SCOPED_TRACE(std::string(cf::LanePathName(path)) + " case " + std::to_string(i));
      ASSERT_EQ(got[i], want[i]);
      ASSERT_TRUE(SameFilter(*batched[i], *reference[i]));
      // And the next step from there (the factor the lanes made current, the update after).
      ASSERT_EQ(batched[i]->Update(cases[i].x0), reference[i]->Update(cases[i].x0));
      ASSERT_TRUE(SameFilter(*batched[i], *reference[i]));
    }
    ExpectBothKinds(ran.first, ran.second, cases.size(), path);
  }
}

// The measurement update in lanes: each link the bits of its own Update (state, covariance,
// NIS, status), then the next step from there, on the same states; measurements near the
// estimate and a turn or more away, and non-finite ones.
TEST(UpdateLanes, EachLinkGetsTheBitsOfItsOwnUpdate) {
  const std::vector<Case> cases = MakeCases();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<cf::LinkState> measured;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    cf::LinkState z = cases[i].x0;
    const double s = i % 7 == 0 ? 1.0 : 0.01;
    z.l += 0.01 * n01(rng), z.phi += s * n01(rng), z.alpha += s * n01(rng);
    if (i % 101 == 0) z.alpha += 8 * control::kPi;  // more than a turn out: Update wraps it
    if (i % 103 == 0) z.phi = std::nan("");
    measured.push_back(z);
  }
  for (cf::LanePath path : LanePaths()) {
    PathScope scope(path);
    Twins twins(cases, true);
    auto& reference = twins.reference;
    auto& batched = twins.batched;
    std::vector<UkfStatus> want(cases.size()), got(cases.size(), UkfStatus::kOk);
    for (std::size_t i = 0; i < cases.size(); ++i) want[i] = reference[i]->Update(measured[i]);
    const auto ran = RunBatch<cf::LinkUpdateBatch>(
        cases.size(), [&](auto& batch, std::size_t i) { batch.Add(*batched[i], measured[i], &got[i]); });
    for (std::size_t i = 0; i < cases.size(); ++i) {
      SCOPED_TRACE(std::string(cf::LanePathName(path)) + " case " + std::to_string(i));
      ASSERT_EQ(got[i], want[i]);
      ASSERT_TRUE(SameFilter(*batched[i], *reference[i]));
      const double nis_b = batched[i]->nis(), nis_r = reference[i]->nis();
      ASSERT_EQ(std::memcmp(&nis_b, &nis_r, sizeof nis_b), 0);
      // And the next step from there (the factor the lanes kept, the prediction after).
      ASSERT_EQ(batched[i]->Predict(cases[i].leader, cases[i].follower),
                reference[i]->Predict(cases[i].leader, cases[i].follower));
      ASSERT_TRUE(SameFilter(*batched[i], *reference[i]));
    }
    ExpectBothKinds(ran.first, ran.second, cases.size(), path);
  }
}

TEST(PredictLanes, PathsResolveOnThisCpu) {
  EXPECT_EQ(cf::ResolveLanePath(cf::LanePath::kScalar), cf::LanePath::kScalar);
  EXPECT_EQ(cf::ResolveLanePath(cf::LanePath::kPortable), cf::LanePath::kPortable);
  const cf::LanePath best =
      formsim::control::CpuHasAvx2() ? cf::LanePath::kAvx2 : cf::LanePath::kPortable;
  EXPECT_EQ(cf::ResolveLanePath(cf::LanePath::kAuto), best);
  EXPECT_EQ(cf::ResolveLanePath(cf::LanePath::kAvx2), best);
}

using testing::ReadText;

// CSV + summary of a shipped scenario run on `path` with `threads` threads.
std::string RunBytes(const std::string& name, const std::vector<std::string>& sets,
                     cf::LanePath path, int threads) {
  PathScope scope(path);
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/lanes/" + name + "_" +
                          cf::LanePathName(path) + "_" + std::to_string(threads);
  std::filesystem::create_directories(dir);
  auto exp =
      LoadExperiment(std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/" + name + ".yaml", sets);
  exp->SetThreads(threads);
  exp->mutable_recorder().StreamTo(CsvPath(dir));
  while (!exp->finished()) exp->Step();
  WriteRunOutputs(*exp, dir);
  return ReadText(CsvPath(dir)) + "\n--- summary ---\n" + ReadText(dir + "/summary.json");
}

TEST(PredictLanes, ShippedFormationScenariosAreTheSameBytesOnEveryPath) {
  struct Run {
    const char* name;
    std::vector<std::string> sets;
  };
  const Run runs[] = {
      {"formation_swarm_100", {"duration=3"}},  // 99 links: beside Box2D, lanes full
      {"formation_traj2_ukf", {}},              // the paper's UKF run: three links in Sense
      {"formation_traj1", {"robots.R2.follow.estimator=ukf", "robots.R3.follow.estimator=ukf"}},
      {"formation_traj3", {"robots.R2.follow.estimator=ukf", "robots.R3.follow.estimator=ukf"}},
      {"formation_switching", {}},
      {"formation_obstacle_field", {}},
  };
  for (const Run& r : runs) {
    const std::string reference = RunBytes(r.name, r.sets, cf::LanePath::kScalar, 1);
    ASSERT_GT(reference.size(), 1000u) << r.name;
    for (cf::LanePath path : LanePaths())
      for (int threads : {1, 2})
        EXPECT_TRUE(RunBytes(r.name, r.sets, path, threads) == reference)
            << r.name << " differs on " << cf::LanePathName(path) << " with " << threads
            << " thread(s)";
  }
}

}  // namespace
}  // namespace formsim::sim::formation
