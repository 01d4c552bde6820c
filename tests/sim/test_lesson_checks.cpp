// Lesson checks: the `checks:` schema of a lesson block, the statistics and relations they
// measure, the evaluation over seeds (the same values for any number of jobs), and the rule
// that every paragraph of a shipped lesson stating an effect names the checks backing it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "sim/core/recorder.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/study/lesson_checks.hpp"
#include "test_kind.hpp"

namespace formsim::sim {
namespace {

namespace fs = std::filesystem;

LessonCheck ColumnCheck(LessonCheck::Stat stat, double from = 0, double to = 1e9) {
  LessonCheck c;
  c.source = LessonCheck::Source::kColumn;
  c.stat = stat;
  c.from = from;
  c.to = to;
  return c;
}

TEST(LessonChecks, ColumnStatistics) {
  std::vector<double> t, x;
  for (int i = 0; i <= 300; ++i) {
    t.push_back(0.01 * i);
    x.push_back(-0.05 * std::exp(-t.back() / 0.7));  // τ = 0.7 s
  }
  using S = LessonCheck::Stat;
  EXPECT_NEAR(ColumnStat(t, x, ColumnCheck(S::kTau, 0.1, 2.5)), 0.7, 1e-9);
  EXPECT_DOUBLE_EQ(ColumnStat(t, x, ColumnCheck(S::kMaxAbs)), 0.05);
  EXPECT_DOUBLE_EQ(ColumnStat(t, x, ColumnCheck(S::kMin)), -0.05);
  EXPECT_DOUBLE_EQ(ColumnStat(t, x, ColumnCheck(S::kFinal)), x.back());
  // Window [1, 2]: the largest magnitude is at t = 1.
  EXPECT_NEAR(ColumnStat(t, x, ColumnCheck(S::kMaxAbs, 1, 2)), 0.05 * std::exp(-1 / 0.7), 1e-12);
  LessonCheck below = ColumnCheck(S::kFirstBelow);
  below.level = 0.05 * std::exp(-1.0);  // one time constant
  EXPECT_NEAR(ColumnStat(t, x, below), 0.7, 0.0101);  // the first row at or past one τ
  below.level = 1e-9;  // never reached: +inf, so "less than" fails
  EXPECT_TRUE(std::isinf(ColumnStat(t, x, below)));
  // Jitter: RMS of the step-to-step change; NotSampled cells are skipped.
  const std::vector<double> tj = {0, 1, 2, 3, 4}, xj = {0, 1, NotSampled(), 0, 1};
  EXPECT_DOUBLE_EQ(ColumnStat(tj, xj, ColumnCheck(S::kJitter)), 1.0);
  EXPECT_DOUBLE_EQ(ColumnStat(tj, xj, ColumnCheck(S::kMean)), 0.5);
  EXPECT_DOUBLE_EQ(ColumnStat(tj, xj, ColumnCheck(S::kRms)), std::sqrt(0.5));
  // Nothing in the window: NaN, which no relation accepts.
  EXPECT_TRUE(std::isnan(ColumnStat(tj, xj, ColumnCheck(S::kMax, 10, 20))));
}

TEST(LessonChecks, Relations) {
  LessonCheck c;
  c.relation = LessonCheck::Relation::kLess;
  EXPECT_TRUE(RelationHolds(c, 1, 2));
  EXPECT_FALSE(RelationHolds(c, 2, 2));
  EXPECT_FALSE(RelationHolds(c, std::nan(""), 2));
  c.relation = LessonCheck::Relation::kGreater;
  EXPECT_TRUE(RelationHolds(c, 3, 2));
  c.relation = LessonCheck::Relation::kWithin;
  c.lo = 0.9, c.hi = 1.1;
  EXPECT_TRUE(RelationHolds(c, 1.0, 0));
  EXPECT_FALSE(RelationHolds(c, 1.2, 0));
  c.relation = LessonCheck::Relation::kEqual;
  c.tolerance = 0.01;
  EXPECT_TRUE(RelationHolds(c, 1.005, 1.0));
  EXPECT_FALSE(RelationHolds(c, 1.02, 1.0));
}

// "6.7 s" is about: 6.7 (rel 0.1): within ±10 % of the value, relative.
TEST(LessonChecks, AboutIsARelativeTolerance) {
  LessonCheck c;
  c.relation = LessonCheck::Relation::kAbout;
  c.rel = 0.1;
  EXPECT_TRUE(RelationHolds(c, 6.1, 6.7));
  EXPECT_TRUE(RelationHolds(c, 7.3, 6.7));
  EXPECT_FALSE(RelationHolds(c, 6.0, 6.7));
  EXPECT_FALSE(RelationHolds(c, 7.4, 6.7));
  EXPECT_TRUE(RelationHolds(c, -0.95, -1.0));
  EXPECT_FALSE(RelationHolds(c, std::nan(""), 6.7));
}

// Each quantity's range, which the loader holds every bound against.
TEST(LessonChecks, QuantitiesHaveRanges) {
  LessonCheck c;
  c.source = LessonCheck::Source::kEvents;
  EXPECT_EQ(QuantityRangeOf(c).lo, 0.0);
  EXPECT_TRUE(QuantityRangeOf(c).lo_reached);  // no event at all is a real outcome
  c.source = LessonCheck::Source::kMetric;
  c.name = "localisation.position_error_m.raw.rms";
  EXPECT_EQ(QuantityRangeOf(c).lo, 0.0);
  EXPECT_FALSE(QuantityRangeOf(c).lo_reached);
  c.name = "switches.list.0.recovered";
  EXPECT_EQ(QuantityRangeOf(c).hi, 1.0);
  c.name = "switches.list.0.recover_s";
  EXPECT_TRUE(QuantityRangeOf(c).lo_reached);
  c.name = "robots.R1.floors.gravel.control.v_true_mean";  // signed: no range
  EXPECT_TRUE(std::isinf(QuantityRangeOf(c).lo));
  c = ColumnCheck(LessonCheck::Stat::kMean);
  EXPECT_TRUE(std::isinf(QuantityRangeOf(c).lo));
  c = ColumnCheck(LessonCheck::Stat::kJitter);
  EXPECT_EQ(QuantityRangeOf(c).lo, 0.0);
}

// One renderer for the window, the page and `formsim lessons show`: a check's value and
// verdict, "(…)" while pending, and never a {name}, "nan" or "pending" in what a student reads,
// for every paragraph of every shipped lesson.
TEST(LessonChecks, RendererLeavesNoPlaceholder) {
  auto pending = [](const std::string&) { return ShownCheck{}; };
  EXPECT_EQ(RenderLessonParagraph("τ is 1 s {tau_l}, see {x y}.", pending), "τ is 1 s (…), see {x y}.");
  EXPECT_EQ(RenderLessonParagraph("τ {tau_l}",
                                  [](const std::string&) { return ShownCheck{true, 0.9951, true}; }),
            "τ (0.9951 √)");
  EXPECT_EQ(RenderLessonParagraph("τ {tau_l}",
                                  [](const std::string&) { return ShownCheck{true, 0.5, false}; }),
            "τ (0.5, does not hold)");
  EXPECT_EQ(RenderLessonParagraph("τ {tau_l}",
                                  [](const std::string&) { return ShownCheck{true, 0.5, false, true}; }),
            "τ (0.5, not on this seed)");
  EXPECT_EQ(RenderLessonParagraph("{a}", [](const std::string&) {
              return ShownCheck{true, std::nan(""), false};
            }),
            "(…)");
  // Over robots: the robot that decides, before the value.
  EXPECT_EQ(RenderLessonParagraph("every robot {a}", [](const std::string&) {
              return ShownCheck{true, -0.0012, true, false, "R6"};
            }),
            "every robot (R6: -0.0012 √)");
  EXPECT_EQ(RenderLessonParagraph("{a}", [](const std::string&) {
              return ShownCheck{true, std::numeric_limits<double>::infinity(), false};
            }),
            "(∞, does not hold)");
  int rendered = 0;
  for (const std::string& file : ShippedLessons()) {
    const YAML::Node root = LoadYamlFile(file);
    YamlReader r(root["lesson"], file, "lesson");
    const LessonDef l = ReadLesson(r);
    for (const bool measured : {false, true}) {
      const std::string text = RenderLessonText(l, [&](const std::string& id) {
        EXPECT_NE(l.Find(id), nullptr) << file << ": {" << id << "}";
        return measured ? ShownCheck{true, 1.25, true} : ShownCheck{};
      });
      for (const char* bad : {"{", "}", "nan", "pending"})
        EXPECT_EQ(text.find(bad), std::string::npos) << file << " shows '" << bad << "':\n" << text;
      EXPECT_NE(text.find(measured ? "(1.25 √)" : "(…)"), std::string::npos) << file;
      ++rendered;
    }
  }
  EXPECT_GE(rendered, 24);
}

TEST(LessonChecks, ReferencesAndEffects) {
  EXPECT_EQ(CheckReferences("falls to 1 s {tau_l} and {tau_phi}; [phi, alpha] {Not} {}"),
            (std::vector<std::string>{"tau_l", "tau_phi"}));
  EXPECT_TRUE(StatesAnEffect("τ doubles to 2 s"));
  EXPECT_TRUE(StatesAnEffect("the speeds grow larger than before"));
  EXPECT_FALSE(StatesAnEffect("Watch the plots and the ghost {tau_1}."));
}

// A lesson on the core test kind: x after 1 s on a circle of v = 1.2, ω = 0.5 is
// sin(0.5) / 0.5 · 1.2 ≈ 1.15 m whatever the seed (the noise is in the sensor only).
std::string WriteLesson(const std::string& name, const std::string& checks,
                        const std::string& steps = "    - {text: \"watch the speed\"}\n") {
  const fs::path dir = fs::temp_directory_path() / "formsim_test_lesson_checks";
  fs::create_directories(dir);
  const std::string file = (dir / (name + ".yaml")).string();
  std::ofstream(file) << testkind::kScenario << "lesson:\n  title: \"Circle\"\n"
                      << "  goal: \"The robot drives 1.15 m along x {x_end} {x_ratio}.\"\n"
                      << "  steps:\n" << steps << "  checks:\n"
                      << checks;
  return file;
}

TEST(LessonChecks, EvaluatesOverSeedsTheSameForAnyJobs) {
  const std::string file = WriteLesson(
      "circle_lesson",
      "    - {id: x_end, metric: x, within: [1.1, 1.2], seeds: 5}\n"
      "    - {id: x_slow, set: [\"v=0.6\"], metric: x, greater: 0, seeds: all}\n"
      "    - {id: x_ratio, set: [\"v=0.6\"], metric: x, ratio_to: x_end, within: [0.49, 0.51], seeds: 5}\n"
      "    - {id: noisy, column: measured_v, stat: rms, from: 0.5, to: 1, greater: x_slow, seeds: 6}\n"
      "    - {id: wrong, metric: x, less: 1, seeds: 5}\n"
      "    - {id: missing, metric: no_such_metric, less: 1, seeds: 5}\n");
  LessonCheckOptions one;
  one.jobs = 1;
  LessonCheckOptions two = one;
  two.jobs = 2;
  const auto a = CheckLesson(file, one), b = CheckLesson(file, two);
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), 6u);
  std::map<std::string, LessonCheckResult> by;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // Bit for bit, any number of jobs (NaN where the quantity does not exist).
    ASSERT_EQ(a[i].values.size(), b[i].values.size());
    for (std::size_t k = 0; k < a[i].values.size(); ++k)
      EXPECT_EQ(std::memcmp(&a[i].values[k], &b[i].values[k], sizeof(double)), 0) << a[i].id;
    by[a[i].id] = a[i];
  }
  EXPECT_TRUE(by["x_end"].ok()) << FormatCheckResult(by["x_end"]);
  EXPECT_EQ(by["x_end"].seeds.size(), 5u);
  EXPECT_EQ(by["x_slow"].seeds.size(), 5u);  // all: every seed asked for, 1..5 by default
  EXPECT_TRUE(by["x_ratio"].ok()) << FormatCheckResult(by["x_ratio"]);
  EXPECT_EQ(by["noisy"].seeds.size(), 6u);
  // The measured speed (about 1.2 m/s) against x of the slower run (about 0.58 m).
  EXPECT_TRUE(by["noisy"].ok()) << FormatCheckResult(by["noisy"]);
  EXPECT_FALSE(by["wrong"].ok());
  EXPECT_NE(FormatCheckResult(by["wrong"]).find("FAILS"), std::string::npos);
  EXPECT_FALSE(by["missing"].ok());
  EXPECT_NE(by["missing"].error.find("no metric 'no_such_metric'"), std::string::npos);
  // --seeds overrides every check's own.
  LessonCheckOptions seeds = one;
  seeds.seeds = {7, 8};
  seeds.only = {"x_end"};
  const auto c = CheckLesson(file, seeds);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].seeds, (std::vector<std::uint64_t>{7, 8}));
}

// Every shipped lesson: its block reads strictly, every paragraph that states an effect (a
// number, a comparison) names a check, every check is named by a paragraph, and there are
// at least 12 lessons, at least two per paper.
TEST(LessonChecks, ShippedLessonsBackEveryClaim) {
  std::map<std::string, int> per_paper;
  int predictions = 0;
  const auto files = ShippedLessons();
  for (const std::string& file : files) {
    const YAML::Node root = LoadYamlFile(file);
    ASSERT_TRUE(root["lesson"]) << file;
    YamlReader r(root["lesson"], file, "lesson");
    const LessonDef l = ReadLesson(r);
    ++per_paper[root["type"].as<std::string>()];
    EXPECT_FALSE(l.checks.empty()) << file;
    std::set<std::string> named;
    // Each text with the checks it names: {id}s; a step's text also by its check: keys (a
    // prediction's text poses the question, and names its check so, not the answer).
    struct Paragraph {
      std::string key, text;
      std::vector<std::string> keys;
    };
    std::vector<Paragraph> paragraphs = {{"goal", l.goal, {}}};
    for (std::size_t i = 0; i < l.steps.size(); ++i) {
      const LessonStep& s = l.steps[i];
      std::vector<std::string> keys;
      for (const std::string& k : {s.check, s.predict.check})
        if (!k.empty()) keys.push_back(k);
      paragraphs.push_back({"step " + std::to_string(i + 1), s.text, keys});
      if (!s.predict.explain.empty())
        paragraphs.push_back({"step " + std::to_string(i + 1) + "'s explanation", s.predict.explain, {}});
    }
    for (const auto& [key, text, keys] : paragraphs) {
      auto refs = CheckReferences(text);
      named.insert(refs.begin(), refs.end());
      refs.insert(refs.end(), keys.begin(), keys.end());
      if (StatesAnEffect(text)) {
        EXPECT_FALSE(refs.empty()) << file << ": " << key
                                   << " states an effect but names no check:\n  " << text;
      }
    }
    // A guided lesson: several steps; a step's action does something; predictions exist.
    EXPECT_GE(l.steps.size(), 3u) << file;
    for (const LessonStep& s : l.steps) {
      if (!s.predict.question.empty()) ++predictions;
      // The check a step shows live is one its text names (or the answer's).
      if (!s.check.empty()) {
        const auto refs = CheckReferences(s.text);
        EXPECT_TRUE(s.check == s.predict.check ||
                    std::find(refs.begin(), refs.end(), s.check) != refs.end())
            << file << ": step at line " << s.line << " shows {" << s.check << "}, not in its text";
      }
    }
    for (const LessonCheck& c : l.checks) {
      EXPECT_TRUE(named.count(c.id) || std::any_of(l.checks.begin(), l.checks.end(),
                                                   [&](const LessonCheck& o) {
                                                     return o.against == c.id || o.ratio_to == c.id;
                                                   }))
          << file << ": check " << c.id << " backs no paragraph and no other check";
      EXPECT_TRUE(c.all_seeds || c.seeds >= 5) << file << ": " << c.id;
    }
  }
  EXPECT_GE(files.size(), 12u);
  EXPECT_GE(predictions, 8);
  for (const char* paper : {"formation", "agv", "inspection", "velocity"})
    EXPECT_GE(per_paper[paper], 2) << paper;
}

// The sentences that state a claim yet name no check, which a shipped lesson may keep: each
// states no claim about a run, for the reason given. Keep this list short; a sentence that
// states what a run shows names the check that shows it.
const std::map<std::string, std::string> kNoClaim = {
    {"A follower R2 keeps a distance l and a bearing φ to its leader R1, measured from R1 to R2's "
     "control point M, a distance L ahead of R2's wheels.",
     "a definition of the outputs: where M sits on the robot ('ahead' is its place, not a run's)"},
};

// Every sentence of every shipped lesson (goal, steps, explanations) that states a number, a
// comparison or a direction names the check backing it; the test lists each that does not.
TEST(LessonChecks, EverySentenceThatClaimsNamesACheck) {
  std::string missing;
  int sentences = 0;
  std::set<std::string> allowed_used;
  for (const std::string& file : ShippedLessons()) {
    const YAML::Node root = LoadYamlFile(file);
    YamlReader r(root["lesson"], file, "lesson");
    const LessonDef l = ReadLesson(r);
    sentences += static_cast<int>(SplitSentences(l.goal).size());
    for (const LessonStep& s : l.steps) sentences += static_cast<int>(SplitSentences(s.text).size());
    for (const UnbackedSentence& u : SentencesWithoutCheck(l)) {
      if (kNoClaim.count(u.sentence)) {
        allowed_used.insert(u.sentence);
        continue;
      }
      missing += "  " + fs::path(file).filename().string() + (u.line ? ":" + std::to_string(u.line) : "") +
                 " " + u.where + ": " + u.sentence + "\n";
    }
  }
  EXPECT_TRUE(missing.empty()) << "sentences that state a claim and name no check {id}:\n" << missing;
  // The allow-list holds nothing stale.
  for (const auto& [sentence, why] : kNoClaim)
    EXPECT_TRUE(allowed_used.count(sentence)) << "kNoClaim holds a sentence no lesson has: " << sentence;
  EXPECT_GE(sentences, 100);
}

// The detector itself: numbers (not a robot's name), comparisons and directions; sentences cut
// where they end, not at a decimal point; an instruction's settings are no claim.
TEST(LessonChecks, SentencesAndWhatTheyClaim) {
  EXPECT_EQ(SplitSentences("τ is 0.5 s {a}. R4..R7 follow, e.g. R5! Why? {b}"),
            (std::vector<std::string>{"τ is 0.5 s {a}.", "R4..R7 follow, e.g. R5!", "Why?", "{b}"}));
  EXPECT_TRUE(SplitSentences("  ").empty());
  for (const char* claim :
       {"It settles in 2 s.", "The error halves.", "R6 falls behind.", "odometry is best",
        "R1 is faster than R2", "a gain -3 does it", "it drifts 90° off", "four times the offset",
        "the error lags the command", "the error grows", "R2 is worse", "the same at depth 10"})
    EXPECT_TRUE(StatesAnEffect(claim)) << claim;
  for (const char* plain :
       {"R3 follows R1 and R2.", "Watch the plots and the ghost {tau_1}.", "u1 and u2 drive the wheels",
        "The links R4-R7 and R1-R2 are drawn.", "Load formation_swarm_100.", "the lesson ends",
        "regardless of it", "an unlessened moreover"})
    EXPECT_FALSE(StatesAnEffect(plain)) << plain;
  // An instruction: its settings are no claim, what follows its ':' is.
  EXPECT_EQ(ClaimPart("Set r_xy to 0.1 and reset."), "");
  EXPECT_FALSE(StatesAnEffect(ClaimPart("Set r_xy to 0.1, ten times the noise, and reset.")));
  EXPECT_TRUE(StatesAnEffect(ClaimPart("Halve k_l and reset: τ doubles.")));
  EXPECT_TRUE(StatesAnEffect(ClaimPart("The error is 2 mm.")));
  // Per sentence: one sentence with a check does not back the next one.
  LessonDef l;
  l.goal = "The error halves {a}. It falls to 2 mm. The ghost is R2's slot.";
  LessonStep s;
  s.text = "Set k to 0.5 and reset. τ doubles {b}.";
  s.predict.explain = "It doubles, as the gain halves.";
  l.steps = {s};
  const auto u = SentencesWithoutCheck(l);
  ASSERT_EQ(u.size(), 2u);
  EXPECT_EQ(u[0].where, "goal");
  EXPECT_EQ(u[0].sentence, "It falls to 2 mm.");
  EXPECT_EQ(u[1].where, "step 1's explanation");
}

// "Every robot" and "any robot": the quantity once per robot (`*` in its name), the relation
// for every one of them or for one at least; the value shown is the robot that decides. Here the
// "robots" are the test kind's two columns x and y (x ≈ 1.15 m, y ≈ 0.29 m after 1 s).
TEST(LessonChecks, EveryAndAnyRobot) {
  const std::string file = WriteLesson(
      "circle_every",
      "    - {id: x_end, metric: x, within: [1.1, 1.2], seeds: 5}\n"
      "    - {id: x_ratio, set: [\"v=0.6\"], metric: x, ratio_to: x_end, within: [0.49, 0.51], seeds: 5}\n"
      "    - {id: both_out, every: [x, y], column: \"*\", stat: final, greater: 0.2, seeds: 5}\n"
      "    - {id: both_far, every: [x, y], column: \"*\", stat: final, greater: 1, seeds: 5}\n"
      "    - {id: one_far, any: [x, y], column: \"*\", stat: final, greater: 1, seeds: 5}\n"
      "    - {id: none_far, any: [x, y], column: \"*\", stat: final, greater: 2, seeds: 5}\n"
      "    - {id: slow_half, every: [x, y], set: [\"v=0.6\"], column: \"*\", stat: final, ratio_to: both_out, within: [0.49, 0.51], seeds: 5}\n"
      "    - {id: slow_scalar, every: [x, y], set: [\"v=0.6\"], column: \"*\", stat: final, ratio_to: x_end, within: [0.1, 0.51], seeds: 5}\n"
      "    - {id: typo, every: [x, z], column: \"*\", stat: final, greater: 0.2, seeds: 5}\n",
      "    - {text: \"{both_out} {both_far} {one_far} {none_far} {slow_half} {slow_scalar} {typo}\"}\n");
  LessonCheckOptions opt;
  opt.jobs = 2;
  std::map<std::string, LessonCheckResult> by;
  for (const auto& r : CheckLesson(file, opt)) by[r.id] = r;
  // Every: y (0.29) is the robot nearest to failing > 0.2.
  EXPECT_TRUE(by["both_out"].ok()) << FormatCheckResult(by["both_out"]);
  EXPECT_EQ(by["both_out"].deciders, std::vector<std::string>(5, "y"));
  EXPECT_NEAR(by["both_out"].values[0], 0.2938, 5e-3);  // the last row, on the discrete circle
  // Every fails when one robot fails, and shows the failing one.
  EXPECT_FALSE(by["both_far"].ok());
  EXPECT_EQ(by["both_far"].deciders.front(), "y");
  EXPECT_NE(FormatCheckResult(by["both_far"]).find("(y on every seed)"), std::string::npos)
      << FormatCheckResult(by["both_far"]);
  EXPECT_NE(by["both_far"].relation.find("for each of [x y]"), std::string::npos);
  EXPECT_NE(by["one_far"].relation.find("for one of [x y] at least"), std::string::npos);
  // Any holds when one robot holds, and shows it.
  EXPECT_TRUE(by["one_far"].ok()) << FormatCheckResult(by["one_far"]);
  EXPECT_EQ(by["one_far"].deciders.front(), "x");
  EXPECT_FALSE(by["none_far"].ok());
  // Robot by robot against a check over the same robots; against one value for every robot.
  EXPECT_TRUE(by["slow_half"].ok()) << FormatCheckResult(by["slow_half"]);
  EXPECT_TRUE(by["slow_scalar"].ok()) << FormatCheckResult(by["slow_scalar"]);
  // A robot whose quantity does not exist is named.
  EXPECT_FALSE(by["typo"].ok());
  EXPECT_NE(by["typo"].error.find("no column 'z'"), std::string::npos) << by["typo"].error;

  // Measured live, on one run, the same way.
  const ParsedScenario p = ParseScenario(ScenarioSource::FromFile(file), {});
  auto exp = BuildExperiment(p);
  while (!exp->finished()) exp->Step();
  const LiveCheck live = MeasureOnRun(p.lesson, *p.lesson.Find("both_out"), *exp);
  EXPECT_TRUE(live.ready && live.holds && live.error.empty()) << live.error;
  EXPECT_EQ(live.robot, "y");
  EXPECT_NEAR(live.value, by["both_out"].values[0], 1e-3);
  const LiveCheck any = MeasureOnRun(p.lesson, *p.lesson.Find("one_far"), *exp);
  EXPECT_TRUE(any.holds);
  EXPECT_EQ(any.robot, "x");
}

// The checks WriteLesson's goal names.
const std::string kCircleChecks =
    "    - {id: x_end, metric: x, within: [1.1, 1.2], seeds: 5}\n"
    "    - {id: x_ratio, set: [\"v=0.6\"], metric: x, ratio_to: x_end, within: [0.49, 0.51], seeds: 5}\n";

// The loader is as strict with every / any as with the other forms: each mistake is an error
// naming the file, the line and the key.
TEST(LessonChecks, EveryAndAnyAreReadStrictly) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"{id: a, every: [x, y], any: [x, y], column: \"*\", stat: final, greater: 0.2, seeds: 5}", "any"},
      {"{id: a, every: [x, y], column: x, stat: final, greater: 0.2, seeds: 5}", "column"},
      {"{id: a, column: \"*\", stat: final, greater: 0.2, seeds: 5}", "column"},
      {"{id: a, every: [x], column: \"*\", stat: final, greater: 0.2, seeds: 5}", "every"},
      {"{id: a, every: [x, x], column: \"*\", stat: final, greater: 0.2, seeds: 5}", "every"},
      {"{id: a, every: [x, \"y z\"], column: \"*\", stat: final, greater: 0.2, seeds: 5}", "every"},
      {"{id: a, any: [x, y], events: saturation, greater: 0, seeds: 5}", "events"},
      {"{id: a, every: [x, y], every: [x, y], column: \"*\", stat: final, greater: 0.2, seeds: 5}", "every"},
  };
  for (const auto& [check, key] : bad) {
    const std::string file = WriteLesson("circle_bad_every", kCircleChecks + "    - " + check + "\n",
                                         "    - {text: \"{a}\"}\n");
    try {
      ParseScenario(ScenarioSource::FromFile(file), {});
      ADD_FAILURE() << "accepted: " << check;
    } catch (const std::exception& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(file), std::string::npos) << m;
      EXPECT_NE(m.find(key), std::string::npos) << check << "\n  " << m;
    }
  }
  // References: a check of one value cannot refer to one over robots; over robots, the same ones.
  const std::vector<std::string> bad_refs = {
      "    - {id: a, every: [x, y], column: \"*\", stat: final, greater: 0.2, seeds: 5}\n"
      "    - {id: b, metric: x, ratio_to: a, less: 3, seeds: 5}\n",
      "    - {id: a, every: [x, y], column: \"*\", stat: final, greater: 0.2, seeds: 5}\n"
      "    - {id: b, metric: x, greater: a, seeds: 5}\n",
      "    - {id: a, every: [x, y], column: \"*\", stat: final, greater: 0.2, seeds: 5}\n"
      "    - {id: b, every: [y, x], column: \"*\", stat: final, minus: a, less: 3, seeds: 5}\n"};
  for (const std::string& checks : bad_refs) {
    const std::string file = WriteLesson("circle_bad_ref", kCircleChecks + checks, "    - {text: \"{a} {b}\"}\n");
    EXPECT_THROW(ParseScenario(ScenarioSource::FromFile(file), {}), std::exception) << checks;
  }
  // A per-robot check is one check per robot.
  LessonCheck c;
  c.source = LessonCheck::Source::kEvents;
  c.name = "links.*.e_l";
  c.robot = "*";
  c.over = LessonCheck::Over::kEvery;
  c.robots = {"R3", "R6"};
  const LessonCheck one = c.ForRobot("R6");
  EXPECT_EQ(one.name, "links.R6.e_l");
  EXPECT_EQ(one.robot, "R6");
  EXPECT_EQ(one.over, LessonCheck::Over::kOne);
}

// `lessons check` flags a check whose value is the same on every seed checked while the
// lesson's text says it depends on the seed: x after 1 s does not depend on the seed (the noise
// is in the speed sensor only), the measured speed's RMS does.
TEST(LessonChecks, FlagsASeedEffectTheRunsDoNotShow) {
  const std::string file = WriteLesson(
      "circle_seed_claim",
      "    - {id: x_end, metric: x, within: [1.1, 1.2], seeds: 5}\n"
      "    - {id: x_ratio, set: [\"v=0.6\"], metric: x, ratio_to: x_end, within: [0.49, 0.51], seeds: 5}\n"
      "    - {id: noisy, column: measured_v, stat: rms, from: 0.5, to: 1, within: [1, 1.5], seeds: 5}\n",
      "    - {text: \"Where it ends varies from seed to seed {x_end}. The measured speed depends on the noise {noisy}.\"}\n");
  const ParsedScenario p = ParseScenario(ScenarioSource::FromFile(file), {});
  EXPECT_TRUE(ClaimsASeedEffect("on 24 of the first 30 seeds"));
  EXPECT_TRUE(ClaimsASeedEffect("in 27 of 30 runs"));
  EXPECT_FALSE(ClaimsASeedEffect("one of the robots"));
  EXPECT_FALSE(ClaimsASeedEffect("R2 keeps 2 of its 3 links"));
  LessonCheckOptions opt;
  opt.jobs = 2;
  const auto results = CheckLesson(file, opt);
  const auto w = SeedEffectWarnings(p.lesson, results);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].id, "x_end");
  EXPECT_EQ(w[0].seeds, 5u);
  const std::string line = FormatSeedEffectWarning(w[0]);
  EXPECT_EQ(line.rfind("warning: circle_seed_claim: check x_end is ", 0), 0u) << line;
  EXPECT_NE(line.find("varies from seed to seed"), std::string::npos) << line;
  // One seed shows no seed effect either way: nothing to flag.
  opt.seeds = {4};
  EXPECT_TRUE(SeedEffectWarnings(p.lesson, CheckLesson(file, opt)).empty());
}

// Steps: each step's checks (its `check`, then those its text names, once each); a prediction's
// answer is the index of its option.
TEST(LessonChecks, StepsReadWithTheirChecksAndPredictions) {
  const std::string file = WriteLesson(
      "circle_steps", "    - {id: x_end, metric: x, within: [1.1, 1.2], seeds: 5}\n"
                      "    - {id: x_ratio, set: [\"v=0.6\"], metric: x, ratio_to: x_end, within: [0.49, 0.51], seeds: 5}\n",
      "    - text: \"x grows to 1.15 m {x_end}, then {x_ratio} {x_end}\"\n"
      "      check: x_ratio\n"
      "      action: {label: \"Halve v\", do: [\"edit v=0.6\", reset]}\n"
      "      predict: {question: \"x?\", options: [same, half, twice], answer: half, check: x_ratio}\n"
      "    - {text: \"that is all\"}\n");
  const ParsedScenario p = ParseScenario(ScenarioSource::FromFile(file), {});
  ASSERT_EQ(p.lesson.steps.size(), 2u);
  const LessonStep& s = p.lesson.steps[0];
  EXPECT_EQ(s.Checks(), (std::vector<std::string>{"x_ratio", "x_end"}));
  EXPECT_EQ(s.action.label, "Halve v");
  EXPECT_EQ(s.action.script, (std::vector<std::string>{"edit v=0.6", "reset"}));
  EXPECT_EQ(s.predict.answer, 1);
  EXPECT_EQ(s.predict.check, "x_ratio");
  EXPECT_GT(s.line, 0);
  EXPECT_TRUE(p.lesson.steps[1].Checks().empty());
  EXPECT_TRUE(p.lesson.steps[1].predict.question.empty());
}

// A check measured live: only once the run has reached the time it needs, only on its own run
// (the check's edits, nothing changed while running), with what it needs named otherwise.
TEST(LessonChecks, LiveMeasurementWaitsForTheTimeAndTheRun) {
  const std::string file = WriteLesson(
      "circle_live",
      "    - {id: x_end, metric: x, within: [1.1, 1.2], seeds: 5}\n"
      "    - {id: x_ratio, set: [\"v=0.6\"], metric: x, ratio_to: x_end, within: [0.49, 0.51], seeds: 5}\n"
      "    - {id: v_slow, set: [\"v=0.60\"], column: measured_v, stat: mean, from: 0, to: 0.5, within: [0.4, 0.8], seeds: 5}\n");
  auto run = [&](const std::vector<Override>& o, double until) {
    auto exp = BuildExperiment(ParseScenario(ScenarioSource::FromFile(file), o));
    while (exp->time() < until - 1e-9 && !exp->finished()) exp->Step();
    return exp;
  };
  const ParsedScenario p = ParseScenario(ScenarioSource::FromFile(file), {});
  const LessonDef& l = p.lesson;
  EXPECT_TRUE(std::isinf(CheckNeedsTime(l, *l.Find("x_end"))));
  EXPECT_DOUBLE_EQ(CheckNeedsTime(l, *l.Find("v_slow")), 0.5);

  const auto own = run({}, 2);
  const LiveCheck x = MeasureOnRun(l, *l.Find("x_end"), *own);
  EXPECT_TRUE(x.ready && x.holds) << x.error << " " << x.value;
  // The slow check on the lesson's own run: it names the edits it needs.
  const LiveCheck wrong = MeasureOnRun(l, *l.Find("v_slow"), *own);
  EXPECT_TRUE(wrong.ready);
  EXPECT_NE(wrong.error.find("started with v=0.60"), std::string::npos) << wrong.error;

  RunEdits slow;
  slow.edits["v"] = "0.6";  // "0.6" is "0.60": compared by value
  const auto half = run({{"v", "0.6", "--set", -1}}, 0.3);
  EXPECT_FALSE(MeasureOnRun(l, *l.Find("v_slow"), *half, slow).ready);  // t = 0.3 < 0.5
  const auto later = run({{"v", "0.6", "--set", -1}}, 0.5);
  const LiveCheck v = MeasureOnRun(l, *l.Find("v_slow"), *later, slow);
  EXPECT_TRUE(v.ready && v.error.empty() && v.holds) << v.error << " " << v.value;
  // A ratio to another run cannot be measured on one run.
  const auto done = run({{"v", "0.6", "--set", -1}}, 2);
  EXPECT_NE(MeasureOnRun(l, *l.Find("x_ratio"), *done, slow).error.find("compares two runs"),
            std::string::npos);
  slow.changed_while_running = true;
  EXPECT_NE(MeasureOnRun(l, *l.Find("v_slow"), *later, slow).error.find("changed while it ran"),
            std::string::npos);
}

}  // namespace
}  // namespace formsim::sim
