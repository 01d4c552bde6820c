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
