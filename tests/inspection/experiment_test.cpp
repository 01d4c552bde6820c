// The inspection experiment end to end: the U-route run, determinism, tunables and live edits
// through sim::Session, the rule base reload action, outputs and the invalid scenario fixtures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "sim/scenario/scenario.hpp"
#include "sim/session/session.hpp"
#include "sim/inspection/inspection_experiment.hpp"
#include "tests/support/invalid_fixtures.hpp"

namespace formsim::sim::inspection {
namespace {

namespace fs = std::filesystem;

const std::string kDir = std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/";
const std::string kRoute = kDir + "inspection_u_route.yaml";

InspectionExperiment& AsInspection(Experiment& e) {
  auto* p = dynamic_cast<InspectionExperiment*>(&e);
  EXPECT_NE(p, nullptr);
  return *p;
}
InspectionExperiment& AsInspection(std::unique_ptr<Experiment>& e) { return AsInspection(*e); }

void RunToEnd(Experiment& e) {
  while (!e.finished()) e.Step();
}

long CountEvents(const Experiment& e, const std::string& kind) {
  long n = 0;
  for (const auto& ev : e.events().list()) n += ev.kind == kind;
  return n;
}

std::string ReadText(const std::string& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A private folder with a copy of the U-route scenario and of its rule base (so that a test
// can break the rules), the scenario pointing at the copy.
struct PrivateScenario {
  explicit PrivateScenario(const std::string& tag) {
    dir = (fs::temp_directory_path() / ("formsim_inspection_" + tag)).string();
    fs::create_directories(dir);
    fll = dir + "/rules.fll";
    fs::copy_file(std::string(FORMSIM_SOURCE_DIR) + "/assets/fuzzy/inspection.fll", fll,
                  fs::copy_options::overwrite_existing);
    std::string text = ReadText(kRoute);
    const std::string from = "fuzzy: {file: ../fuzzy/inspection.fll}";
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos);
    text.replace(at, from.size(), "fuzzy: {file: rules.fll}");
    file = dir + "/route.yaml";
    std::ofstream(file) << text;
  }
  ~PrivateScenario() { fs::remove_all(dir); }
  std::string dir, fll, file;
};

// The acceptance run: the robot starts 0.4 m off the centre line, converges, drives the
// whole U and stays within the lateral bound; the Kalman estimate beats the raw fixes.
TEST(InspectionExperiment, CompletesTheURouteWithinTheLateralBound) {
  auto e = LoadExperiment(kRoute);
  auto& x = AsInspection(e);
  RunToEnd(*e);
  EXPECT_TRUE(x.completed());
  EXPECT_LT(x.completion_time(), e->setup().duration);
  ASSERT_GT(x.lateral_tracking().n, 1000);
  EXPECT_LT(x.lateral_tracking().max_abs, x.config().lateral_bound);
  EXPECT_LT(x.lateral_tracking().max_abs, 0.1);
  EXPECT_LT(x.lateral_tracking().rms(), 0.03);
  // The paper's controller alone steers the 2.5 m turn from a steady offset (no feed-forward):
  // the rule base keeps it within centimetres (19 cm with the former gentle table).
  ASSERT_GT(x.lateral_turn().n, 1000);
  EXPECT_LT(x.lateral_turn().rms(), 0.04);
  EXPECT_LT(x.lateral_turn().max_abs, 0.08);
  EXPECT_EQ(*e->Results().Find("control.feedforward"), 0.0);
  EXPECT_GT(x.fixes(), 0.95 * x.scans());
  EXPECT_LT(x.error_kalman().rms(), 0.05);
  EXPECT_LT(x.error_kalman().rms(), x.error_raw().rms());
  EXPECT_LT(x.error_kalman().max_abs, x.error_raw().max_abs);
  EXPECT_GT(x.error_dead_reckoning().max_abs, 0.5);  // what the laser fixes are there for
  EXPECT_NEAR(static_cast<double>(x.control_updates()) / e->time(), 5.0, 0.05);
  EXPECT_EQ(CountEvents(*e, "filter_fault"), 0);
  EXPECT_EQ(CountEvents(*e, "fuzzy_no_rule"), 0);
  EXPECT_EQ(CountEvents(*e, "route_end"), 1);
  const Json s = e->Summary();
  ASSERT_NE(s.Get("results"), nullptr);
  ASSERT_NE(s.Get("results")->Get("tracking"), nullptr);
  const Metrics m = e->Results();
  ASSERT_NE(m.Find("tracking.within_bound"), nullptr);
  EXPECT_EQ(*m.Find("tracking.within_bound"), 1.0);
  EXPECT_EQ(*m.Find("route.completed"), 1.0);
  EXPECT_EQ(*m.Find("localisation.fixes"), static_cast<double>(x.fixes()));
  EXPECT_NE(e->SummaryText().find("per-axis Kalman"), std::string::npos);
  EXPECT_NE(e->SummaryText().find("controller uses the kalman estimate"), std::string::npos);
}

// Our addition: the arc's steering angle fed forward on the turn, so the rules only correct.
// Up to the end of the turn (65 s) the same seed tracks the turn closer than the paper's
// controller alone (seed 5: 0.8 vs 1.5 cm RMS).
TEST(InspectionExperiment, FeedForwardScenarioTracksTheTurnCloser) {
  auto paper = LoadExperiment(kRoute, {"duration=65"});
  auto ff = LoadExperiment(kDir + "inspection_u_route_feedforward.yaml", {"duration=65"});
  RunToEnd(*paper);
  RunToEnd(*ff);
  const auto& a = AsInspection(paper).lateral_turn();
  const auto& b = AsInspection(ff).lateral_turn();
  ASSERT_GT(a.n, 1000);
  ASSERT_GT(b.n, 1000);
  EXPECT_EQ(*ff->Results().Find("control.feedforward"), 1.0);
  EXPECT_LT(b.rms(), 0.75 * a.rms());
}

TEST(InspectionExperiment, WithoutKalmanTheClassicalChainDrives) {
  auto e = LoadExperiment(kDir + "inspection_no_kalman.yaml");
  auto& x = AsInspection(e);
  RunToEnd(*e);
  EXPECT_TRUE(x.completed());
  EXPECT_LT(x.lateral_tracking().max_abs, x.config().lateral_bound);
  // The classical filter smooths the raw fixes, the Kalman filter (running alongside) more.
  EXPECT_LT(x.error_classical().rms(), x.error_raw().rms());
  EXPECT_LT(x.error_kalman().rms(), x.error_classical().rms());
}

// The paper's claim for its Kalman filter (section 3): it localises better than the limit and
// mean filters. On the first straight of every seed tried the Kalman error is well under the
// classical one (measured ratios 0.38-0.59, mean 0.48 on seeds 1-4; a fixed-gain 0.1 "filter"
// gives 0.68-0.86, mean 0.74).
TEST(InspectionExperiment, KalmanFixesBeatLimitAndMeanByAClearMarginOnEverySeed) {
  double sum = 0.0;
  const int seeds[] = {1, 2, 3, 4};
  for (int seed : seeds) {
    auto e = LoadExperiment(kRoute, {"duration=30"}, seed);
    auto& x = AsInspection(e);
    RunToEnd(*e);
    ASSERT_GT(x.error_kalman().n, 1000) << seed;
    ASSERT_EQ(x.error_kalman().n, x.error_classical().n) << seed;
    const double ratio = x.error_kalman().rms() / x.error_classical().rms();
    EXPECT_LT(ratio, 0.65) << "seed " << seed;
    EXPECT_LT(x.error_kalman().max_abs, x.error_classical().max_abs) << "seed " << seed;
    sum += ratio;
  }
  EXPECT_LT(sum / 4.0, 0.55);
}

std::vector<double> AllValues(const Recorder& r) {
  std::vector<double> v;
  for (std::size_t i = 0; i < r.rows(); ++i)
    for (std::size_t c = 0; c < r.columns(); ++c) v.push_back(r.At(i, static_cast<int>(c)));
  return v;
}

bool BitIdentical(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  return true;
}

TEST(InspectionExperiment, SameSeedSameRunOtherSeedOtherNoise) {
  const std::vector<std::string> short_run = {"duration=4"};
  auto a = LoadExperiment(kRoute, short_run), b = LoadExperiment(kRoute, short_run);
  auto c = LoadExperiment(kRoute, short_run, 99);
  RunToEnd(*a);
  RunToEnd(*b);
  RunToEnd(*c);
  EXPECT_TRUE(BitIdentical(AllValues(a->recorder()), AllValues(b->recorder())));
  EXPECT_FALSE(BitIdentical(AllValues(a->recorder()), AllValues(c->recorder())));
  EXPECT_EQ(a->recorder().names().front(), "t");
}

TEST(InspectionExperiment, WithoutPostsInRangeThereIsNoFixAndNoNaN) {
  auto e = LoadExperiment(kRoute, {"duration=3", "localisation.max_range=0.5"});
  auto& x = AsInspection(e);
  RunToEnd(*e);
  EXPECT_EQ(x.fixes(), 0);
  EXPECT_GT(x.scans(), 100);
  const auto nav = x.NavPose();
  EXPECT_TRUE(std::isfinite(nav.x) && std::isfinite(nav.y) && std::isfinite(nav.theta));
  // The robot still drives, on dead reckoning.
  EXPECT_GT(x.TruePose().y, x.config().route_start.y + 0.5);
  // No fix: the raw columns are empty (not sampled) in every row, never a computed NaN.
  const Recorder& r = e->recorder();
  const int raw_x = r.Column("raw_x");
  for (std::size_t i = 0; i < r.rows(); ++i) EXPECT_TRUE(IsNotSampled(r.At(i, raw_x)));
  for (std::size_t i = 0; i < r.rows(); ++i)
    for (std::size_t c = 0; c < r.columns(); ++c) {
      const double v = r.At(i, static_cast<int>(c));
      EXPECT_TRUE(std::isfinite(v) || IsNotSampled(v)) << r.names()[c] << " row " << i;
    }
}

// Every tunable of the kind, as the port declares it: the same key, label, unit, group, slider
// and live/reset as before the port, and a validity that contains the slider.
TEST(InspectionExperiment, TunablesKeepTheirKeysLabelsGroupsAndSliders) {
  struct Old {
    const char* key;
    const char* group;
    const char* label;
    const char* unit;
    double lo, hi;
    bool log, live;
  };
  const std::vector<Old> old = {
      {"robot.drive.speed_per_level", "Gains/vehicle scales", "speed per level", "m/s", 0.02, 0.4, false, true},
      {"robot.drive.steer_per_unit_deg", "Gains/vehicle scales", "steer per servo unit", "deg", 0.05, 0.5, false, true},
      {"robot.drive.servo_center", "Gains/vehicle scales", "servo centre", "", 300, 420, false, true},
      {"robot.drive.steer_rate_deg_s", "Gains/vehicle scales", "servo slew rate", "deg/s", 10, 360, false, true},
      {"robot.drive.motor_force_max", "Gains/vehicle scales", "motor force limit", "N", 5, 200, false, true},
      {"control.feedforward", "Gains/fuzzy", "turn feed-forward", "", NAN, NAN, false, true},
      {"control.rate_hz", "Gains/fuzzy", "control rate", "Hz", 1, 50, false, true},
      {"laser.range_sigma", "Noise/laser", "range noise σ", "m", 0, 0.2, false, true},
      {"laser.angle_sigma_deg", "Noise/laser", "beam jitter σ", "deg", 0, 1, false, true},
      {"laser.outlier_prob", "Noise/laser", "outlier probability", "", 0, 0.05, false, true},
      {"laser.outlier_sigma", "Noise/laser", "outlier σ", "m", 0, 2, false, true},
      {"laser.resolution_deg", "Noise/laser", "angular resolution", "deg", 0.1, 2, false, true},
      {"laser.range_max", "Noise/laser", "max range", "m", 2, 30, false, true},
      {"laser.rate_hz", "Noise/laser", "scan rate", "Hz", 1, 100, false, true},
      {"odometry.sigma_per_sqrt_m", "Noise/odometry", "encoder noise", "m/√m", 0, 0.05, false, true},
      {"odometry.scale_error_left", "Noise/odometry", "left scale error", "", -0.1, 0.1, false, true},
      {"odometry.scale_error_right", "Noise/odometry", "right scale error", "", -0.1, 0.1, false, true},
      {"posts.survey_sigma", "Noise/survey", "post survey error σ", "m", 0, 0.2, false, false},
      {"localisation.gate", "Localisation/laser", "identification gate", "m", 0.05, 1.4, false, true},
      {"localisation.fit_tolerance", "Localisation/laser", "circle fit tolerance", "m", 0.005, 0.2, false, true},
      {"localisation.min_beams", "Localisation/laser", "min beams per post", "", 1, 10, false, true},
      {"localisation.max_range", "Localisation/laser", "max post range", "m", 1, 30, false, true},
      {"localisation.min_subtended_deg", "Localisation/laser", "min angle between posts", "deg", 1, 89, false, true},
      {"localisation.angle_tolerance_deg", "Localisation/laser", "angle consistency", "deg", 0.1, 20, false, true},
      {"localisation.range_tolerance", "Localisation/laser", "circle miss tolerance", "m", 0, 0.5, false, true},
      {"estimation.controller_source", "Estimation/source", "controller uses", "", NAN, NAN, false, true},
      {"estimation.kalman.q_per_m", "Estimation/Kalman", "Q per metre", "m²/m", 1e-7, 1e-1, true, true},
      {"estimation.kalman.q_per_s", "Estimation/Kalman", "Q per second", "m²/s", 1e-8, 1e-1, true, true},
      {"estimation.kalman.r", "Estimation/Kalman", "R (fix variance)", "m²", 1e-6, 1.0, true, true},
      {"estimation.kalman.nis_gate", "Estimation/Kalman", "innovation gate (≤0 off)", "", 0, 100, false, true},
      {"estimation.kalman.reacquire_after", "Estimation/Kalman", "re-init after gated", "", 1, 200, false, true},
      {"estimation.classical.limit_step", "Estimation/classical", "limit step", "m", 0.01, 2, false, true},
      {"estimation.classical.limit_rate", "Estimation/classical", "limit rate", "m/s", 0, 5, false, true},
      {"estimation.classical.mean_window", "Estimation/classical", "mean window", "", 1, 50, false, true},
      {"estimation.heading.limit_deg", "Estimation/heading", "heading limit", "deg", 0.5, 45, false, true},
      {"estimation.heading.mean_window", "Estimation/heading", "heading mean window", "", 1, 50, false, true},
      // Added for the lessons: the post layout (on reset), the pair a fix uses, the fuzzy
      // input scales.
      {"posts.spacing", "Localisation/posts", "post spacing", "m", 1, 18, false, false},
      {"posts.side_offset", "Localisation/posts", "post side offset", "m", 0.5, 6, false, false},
      {"localisation.pair", "Localisation/laser", "fix from the pair", "", NAN, NAN, false, true},
      {"fuzzy.s_scale", "Gains/fuzzy", "offset term scale", "", 0.1, 10, true, true},
      {"fuzzy.dphi_scale", "Gains/fuzzy", "heading term scale", "", 0.1, 10, true, true},
  };
  const ParsedScenario parsed = ParseScenario(ScenarioSource::FromFile(kRoute), {});
  // Beyond the kind's own: the floor's μ and each patch's μ, declared by the shared readers.
  std::size_t shared = 0;
  for (const Param& p : parsed.params.all())
    shared += p.key == "world.floor_friction" ||
              (p.key.rfind("patches.", 0) == 0 && p.key.size() > 9 &&
               p.key.substr(p.key.size() - 9) == ".friction");
  EXPECT_EQ(shared, 2u);
  EXPECT_EQ(parsed.params.size(), old.size() + shared);
  for (const Old& o : old) {
    const Param* p = parsed.params.Find(o.key);
    ASSERT_NE(p, nullptr) << o.key;
    EXPECT_EQ(p->tune.group, o.group) << o.key;
    EXPECT_EQ(p->tune.label, o.label) << o.key;
    EXPECT_EQ(p->tune.unit, o.unit) << o.key;
    EXPECT_EQ(p->tune.live, o.live) << o.key;
    if (std::isfinite(o.lo)) {
      EXPECT_EQ(p->tune.slider_lo, o.lo) << o.key;
      EXPECT_EQ(p->tune.slider_hi, o.hi) << o.key;
      EXPECT_EQ(p->tune.log_scale, o.log) << o.key;
    }
    // Every key is a YAML path the reader accepts with its current value.
    EXPECT_NO_THROW(ParseScenario(ScenarioSource::FromFile(kRoute), {{o.key, p->Text(), "--set", -1}}))
        << o.key;
  }
  // The reload is an action now, not a tunable.
  EXPECT_EQ(parsed.params.Find("fuzzy.reload"), nullptr);
  EXPECT_THROW(LoadExperiment(kRoute, {"fuzzy.reload=true"}), ScenarioError);
}

TEST(InspectionExperiment, LiveEditsApplyBetweenStepsAndTheSurveyWaitsForAReset) {
  Session s(kRoute, {"duration=6"}, -1);
  for (int k = 0; k < 100; ++k) s.Step();
  const long before = AsInspection(s.exp()).control_updates();
  EXPECT_EQ(s.Edit("control.rate_hz", "10"), "");
  EXPECT_EQ(s.Edit("robot.drive.speed_per_level", "0.2"), "");
  for (int k = 0; k < 100; ++k) s.Step();
  auto& x = AsInspection(s.exp());
  EXPECT_EQ(x.control_updates() - before, 10);  // 1 s at 10 Hz
  EXPECT_EQ(x.config().drive.speed_per_level, 0.2);
  EXPECT_EQ(x.drive().def().speed_per_level, 0.2);
  // A rate above 1/dt is refused by the reader (the period would be shorter than a step).
  EXPECT_NE(s.Edit("control.rate_hz", "150").find("at least one world step"), std::string::npos);
  EXPECT_NE(s.Edit("laser.range_max", "1e9").find("must be in (0.001, 1000]"), std::string::npos);
  // The survey error applies on reset only.
  EXPECT_EQ(s.Edit("posts.survey_sigma", "0.1"), "");
  s.Step();
  EXPECT_EQ(x.config().survey_sigma, 0.03);
  EXPECT_EQ(s.waiting_for_reset().count("posts.survey_sigma"), 1u);
  EXPECT_EQ(s.Reset(), "");
  EXPECT_EQ(AsInspection(s.exp()).config().survey_sigma, 0.1);
  EXPECT_EQ(AsInspection(s.exp()).config().control_rate_hz, 10.0);
}

// The post layout waits for a reset (the posts are bodies) and is checked as the loader checks
// it; the fuzzy input scales and the pair choice apply between two steps.
TEST(InspectionExperiment, PostLayoutOnResetFuzzyScalesAndPairLive) {
  Session s(kRoute, {"duration=6", "posts.omit=[]"}, -1);
  for (int k = 0; k < 50; ++k) s.Step();
  const std::size_t posts = AsInspection(s.exp()).config().posts.size();
  EXPECT_EQ(s.Edit("posts.spacing", "6"), "");
  EXPECT_EQ(s.Edit("posts.side_offset", "2.5"), "");
  s.Step();
  EXPECT_EQ(AsInspection(s.exp()).config().posts.size(), posts);
  EXPECT_EQ(s.waiting_for_reset().count("posts.spacing"), 1u);
  EXPECT_EQ(s.Reset(), "");
  const auto& c = AsInspection(s.exp()).config();
  EXPECT_LT(c.posts.size(), posts);
  EXPECT_EQ(c.post_spacing, 6.0);
  EXPECT_DOUBLE_EQ(c.posts.front().position.x, c.route_start.x - 2.5);
  // The identification gate must stay below half the spacing; a post must not touch the path.
  EXPECT_NE(s.Edit("posts.spacing", "1").find("below half the post spacing"), std::string::npos);
  EXPECT_NE(s.Edit("posts.side_offset", "0.05").find("must exceed the post radius"), std::string::npos);
  EXPECT_NE(s.Edit("fuzzy.s_scale", "0").find("must be in [0.001, 1000]"), std::string::npos);
  EXPECT_NE(s.Edit("localisation.pair", "farthest").find("nearest"), std::string::npos);
  // Live: the controller's rule base sees the stretched terms from the next decision on.
  EXPECT_EQ(s.Edit("fuzzy.s_scale", "4"), "");
  EXPECT_EQ(s.Edit("localisation.pair", "nearest"), "");
  s.Step();
  auto& x = AsInspection(s.exp());
  EXPECT_EQ(x.fuzzy().s_scale(), 4.0);
  EXPECT_EQ(x.config().Trilateration().pair, formsim::control::inspection::PairChoice::kNearest);
}

// The controller's source is a live choice: every estimator runs and is recorded from the start,
// so after a switch mid-run the columns of the new source are sampled, the controller follows it
// and the summary names it with its error entries.
TEST(InspectionExperiment, SwitchingTheControllerSourceMidRunKeepsColumnsAndSummary) {
  const std::map<std::string, std::vector<std::string>> columns = {
      {"kalman", {"kf_x", "kf_y", "kf_sd_x", "err_kf", "kf_ex"}},
      {"classical", {"classic_x", "classic_y", "err_classic", "classic_ex"}},
      {"raw", {"raw_x", "raw_y", "raw_heading_deg", "err_raw", "raw_ex"}},
      {"dead_reckoning", {"dr_x", "dr_y", "err_dr"}},
      {"truth", {"true_x", "true_y", "true_heading_deg"}}};
  const std::map<std::string, std::string> summary = {
      {"kalman", "localisation.position_error_m.kalman.rms"},
      {"classical", "localisation.position_error_m.classical.rms"},
      {"raw", "localisation.position_error_m.raw.rms"},
      {"dead_reckoning", "localisation.position_error_m.dead_reckoning.rms"},
      {"truth", "tracking.lateral_offset_m.rms"}};
  Session s(kRoute, {"duration=20"}, -1);
  for (int k = 0; k < 50; ++k) s.Step();
  for (const std::string source : {"classical", "raw", "dead_reckoning", "truth", "kalman"}) {
    ASSERT_EQ(s.Edit("estimation.controller_source", source), "") << source;
    const std::size_t first_row = s.exp().recorder().rows();
    for (int k = 0; k < 100; ++k) s.Step();
    auto& x = AsInspection(s.exp());
    EXPECT_EQ(NavSourceNames()[x.config().source], source);
    const Recorder& r = x.recorder();
    ASSERT_GT(r.rows(), first_row + 10);
    for (const std::string& name : columns.at(source)) {
      const int c = r.Column(name);
      ASSERT_GE(c, 0) << name;
      int sampled = 0;
      for (std::size_t i = first_row; i < r.rows(); ++i) sampled += !IsNotSampled(r.At(i, c));
      EXPECT_GT(sampled, 10) << source << ": " << name;
    }
    for (const char* name : {"s_ctrl", "dphi_ctrl_deg", "fz_u3"}) {
      const int c = r.Column(name);
      EXPECT_FALSE(IsNotSampled(r.At(r.rows() - 1, c))) << source << ": " << name;
    }
    // The controller follows the new source.
    const control::inspection::PaperPose nav = x.NavPose(), truth = x.TruePose();
    if (source == "truth") {
      EXPECT_EQ(nav.x, truth.x);
    } else {
      EXPECT_NE(nav.x, truth.x) << source;
      EXPECT_LT(std::hypot(nav.x - truth.x, nav.y - truth.y), 0.5) << source;
    }
    const Metrics m = x.Results();
    EXPECT_EQ(m.Cell("tracking.controller_source", ""), source);
    ASSERT_NE(m.Find(summary.at(source)), nullptr) << source;
    EXPECT_TRUE(std::isfinite(*m.Find(summary.at(source)))) << source;
    const Json j = x.Summary();
    EXPECT_EQ(j.Get("results")->Get("tracking")->Get("controller_source")->str(), source);
    for (const FigureSpec& f : x.Figures())
      for (const SeriesSpec& series : f.series)
        if (!series.column.empty()) {
          EXPECT_GE(r.Column(series.column), 0) << f.id;
        }
  }
  // The edits are part of the run's provenance.
  EXPECT_GE(s.exp().setup().provenance.overrides.size(), 5u);
}

TEST(InspectionExperiment, ReloadActionReloadsOrKeepsTheOldRules) {
  PrivateScenario p("reload");
  Session s(p.file, {"duration=2"}, -1);
  auto& x = AsInspection(s.exp());
  const auto actions = x.Actions();
  ASSERT_EQ(actions.size(), 1u);
  EXPECT_EQ(actions[0].id, "reload_rules");
  EXPECT_EQ(actions[0].label, "Reload rule base (FLL)");
  EXPECT_EQ(actions[0].group, "Gains/fuzzy");
  EXPECT_NE(s.Action("reload_now"), "");  // no such action
  EXPECT_EQ(s.Action("reload_rules"), "");
  s.Step();
  EXPECT_EQ(CountEvents(x, "fuzzy_reloaded"), 1);
  // Break the file: the reload fails, is reported (event and refusal), and the 45 rules stay.
  std::ofstream(p.fll) << "Engine: broken\nInputVariable: s\n";
  EXPECT_EQ(s.Action("reload_rules"), "");  // queued; it fails when run
  s.Step();
  EXPECT_EQ(CountEvents(x, "fuzzy_reload_failed"), 1);
  ASSERT_FALSE(s.rejected().empty());
  EXPECT_NE(s.rejected().back().find("reload_rules"), std::string::npos);
  EXPECT_EQ(x.fuzzy().rules().size(), 45u);
  EXPECT_NE(x.RunAction("reload_rules"), "");  // directly: the reason
  EXPECT_EQ(x.fuzzy().rules().size(), 45u);
  // A reset reads the scenario again and refuses the broken rule base; the run goes on.
  EXPECT_NE(s.Reset().find("fuzzy.file"), std::string::npos);
  while (!s.exp().finished()) s.Step();
  EXPECT_GT(AsInspection(s.exp()).control_updates(), 5);
}

// fuzzy.file is a path relative to the scenario: saved into another folder, it is rewritten so
// that the saved scenario still finds the rule base.
TEST(InspectionExperiment, SavingIntoAnotherFolderRewritesTheRuleBasePath) {
  Session s(kRoute, {}, -1);
  const fs::path out = fs::temp_directory_path() / "formsim_inspection_save" / "deeper" / "u.yaml";
  fs::create_directories(out.parent_path());
  ASSERT_EQ(s.Save(out.string(), true), Session::SaveResult::kSaved);
  const std::string text = ReadText(out.string());
  EXPECT_EQ(text.find("file: ../fuzzy/inspection.fll"), std::string::npos);
  auto e = LoadExperiment(out.string());
  EXPECT_EQ(fs::canonical(AsInspection(e).config().fuzzy_file),
            fs::canonical(std::string(FORMSIM_SOURCE_DIR) + "/assets/fuzzy/inspection.fll"));
  fs::remove_all(out.parent_path().parent_path());
}

// Counts what the scene draws.
class CountingSink : public DrawSink {
 public:
  void Polygon(const std::vector<Vec2>&, Color, Color) override { ++shapes; }
  void Circle(Vec2, double, Color, Color) override { ++shapes; }
  void Segment(Vec2, Vec2, Color, float) override { ++segments; }
  void Polyline(const std::vector<Vec2>&, Color, float, bool) override { ++shapes; }
  void CovarianceEllipse(Vec2, double, double, double, double, Color) override { ++ellipses; }
  void Cross(Vec2, double, Color) override { ++shapes; }
  void Text(Vec2, const std::string&, Color, float, float) override { ++texts; }
  void Flash(Vec2, double, Color, float) override {}
  int shapes = 0, segments = 0, ellipses = 0, texts = 0;
};

TEST(InspectionExperiment, DrawsRaysFiguresAndTheRuleTable) {
  auto e = LoadExperiment(kRoute, {"duration=1"});
  RunToEnd(*e);
  CountingSink sink;
  e->Draw(sink);
  EXPECT_GT(sink.segments, 50);  // laser rays
  EXPECT_EQ(sink.ellipses, 1);   // Kalman covariance
  EXPECT_GE(sink.texts, 2);      // robot name and the two posts used for the fix
  int membership = 0;
  for (const FigureSpec& f : e->Figures()) {
    EXPECT_FALSE(f.series.empty()) << f.id;
    for (const SeriesSpec& s : f.series) {
      if (s.column.empty()) {
        EXPECT_EQ(s.x.size(), s.y.size()) << f.id;
      } else {
        EXPECT_GE(e->recorder().Column(s.column), 0) << f.id << ": " << s.column;
      }
      if (!s.x_column.empty()) {
        EXPECT_GE(e->recorder().Column(s.x_column), 0) << s.x_column;
      }
    }
    if (f.id.rfind("mf_", 0) == 0) {
      ++membership;
      // The zoom on s near the path marks the input only while it is within 0.35 m.
      if (f.id != "mf_s_near") {
        EXPECT_TRUE(std::isfinite(f.marker_x)) << f.id;
      }
    }
  }
  EXPECT_EQ(membership, 6);  // s, s near the path, Δφ, u1, u2, u3
  const auto tables = e->Tables();
  ASSERT_EQ(tables.size(), 1u);  // the rules; the counts are metrics now
  ASSERT_EQ(tables[0].rows.size(), 45u);
  ASSERT_EQ(tables[0].row_strength.size(), 45u);
  const double strongest =
      *std::max_element(tables[0].row_strength.begin(), tables[0].row_strength.end());
  EXPECT_GT(strongest, 0.0);
  // The u3 figure shows the fired set: clipped at the rules' strengths, so its peak is the
  // strongest rule's (every u3 term reaches 1 inside the range).
  bool shown = false;
  for (const FigureSpec& f : e->Figures())
    for (const SeriesSpec& s : f.series)
      if (f.id == "mf_u3" && s.label == "fired set") {
        shown = true;
        EXPECT_NEAR(*std::max_element(s.y.begin(), s.y.end()), strongest, 1e-12);
      }
  EXPECT_TRUE(shown);
  // The results' tables cover what the GUI's localisation table showed.
  const auto gui = e->Results().GuiTables();
  ASSERT_EQ(gui.size(), 3u);
  for (const auto& t : gui)
    for (const auto& row : t.rows)
      for (const auto& cell : row) EXPECT_NE(cell, "-") << t.title;
  Vec2 lo, hi;
  e->Bounds(lo, hi);
  EXPECT_LT(lo.x, 2.0);
  EXPECT_GT(hi.y, 22.0);
}

// Every tests/fixtures/invalid/inspection_*.yaml starts with "# expect: <text>"; loading it
// must throw a ScenarioError containing the text and pointing at the offending key's line.
TEST(InspectionExperiment, InvalidFixturesAreRejectedWithTheRightMessage) {
  const int checked = formsim::testing::CheckInvalidFixtures("inspection_");
  EXPECT_GE(checked, 14);
}

}  // namespace
}  // namespace formsim::sim::inspection
