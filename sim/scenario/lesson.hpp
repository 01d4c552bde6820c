#pragma once
/// \file A lesson: a scenario file with a `lesson:` block beside its scenario keys
/// (assets/lessons/NAME.yaml; its paper is the scenario's type). The block is text for the GUI's Lesson panel and the checks
/// that back every effect the text states; every command that runs scenarios runs a lesson
/// file as the scenario it holds (finding lesson files: scenario_files.hpp; evaluating the
/// checks: sim/study/lesson_checks.hpp, `formsim lessons check`).
///
///   lesson:
///     title: "The l-φ law and its time constant"      (required)
///     goal: "..."                                      (required)
///     equations: ["l̇ = −k_l (l − l_des)", ...]          (optional, readable text / Unicode)
///     steps:                                           (required: 1 ... 30 guided steps)
///       - text: "Halve k_l ... τ_l doubles {tau_half}" (required)
///         check: tau_half            (optional: the check "what you should see" shows live)
///         action:                    (optional: a button that performs the step's edit)
///           label: "Halve k_l and reset"
///           do: ["edit robots.R2.follow.k_l=0.5", "reset"]   (1 ... 20 script actions,
///                                    run through the window's command table like any edit)
///         predict:                   (optional: asked before the run is played)
///           question: "What happens to τ_l?"
///           options: ["It doubles", "It halves", "It stays 1 s"]   (2 ... 4, distinct)
///           answer: "It doubles"     (one of the options)
///           check: tau_half          (required: the check that backs the answer)
///           explain: "τ_l = 1/k_l doubles {tau_half}"   (optional: shown once judged)
///     checks:                                          (required when a paragraph states an effect)
///       - id: tau_l                  (required; [a-z][a-z0-9_]*, unique)
///         set: ["robots.R2.follow.k_l=0.5"]   (optional: the edits "try next" asks for)
///         duration: 4                (optional: a shorter run where the check allows)
///         # the quantity, exactly one of:
///         metric: links.R1-R2.max_abs_error.l          (a summary.json number)
///         events: saturation   robot: R2               (an event count; robot optional)
///         column: R1-R2.e_l   stat: tau   from: 0.2   to: 3   level: 0.01
///                 (stat: max_abs | max | min | mean | rms | jitter | first_below | tau | final;
///                  level only for first_below; from / to default to the whole run)
///         ratio_to: other_id         (optional: the quantity divided by that check's, same seed)
///         minus: other_id            (optional, instead: that check's value subtracted: a shift
///                                     between two runs, "R6 is 4 mm off where it was")
///         # the relation, exactly one of (a number, or the id of a check: its value, same seed):
///         less: 0.01 | greater: other_id | within: [0.9, 1.1] | equal: 0  (tolerance: 0)
///           | about: 6.7  (rel: 0.1)  (within ±rel of the value, relative: "6.7 s" is about: 6.7)
///         seeds: 5                   (at least 5: seeds 1..N; or `all`: every seed asked for)
///         share: 0.9                 (optional, default 1: it holds on at least this share of
///                                     the seeds; only for an effect that depends on the seed,
///                                     whose text then states the measured share)
///
/// What the text says, as a check:
///   "halves", "less than half of X"  ratio_to: x  less: 0.55      (a ratio to another check,
///                                                                  of this run or of another)
///   "6.7 s", "about 2 m"             about: 6.7  (rel: 0.1)        (a relative tolerance)
///   "after 1 s", "in the last 5 s"   column: ...  from: 1  (or from: 31  to: 36 on a 36 s run:
///                                    a time window, in seconds of the run)
///   "R1 is behind" (a sign)          column: ... stat: mean  less: 0   (on a signed quantity;
///                                    `greater: 0` on one that is never negative is refused)
///   "in 27 of 30 seeds"              share: 0.9  (a count over seeds; `lessons check` fails such
///                                    a check when its value is the same on every seed)
///   (not yet: "every robot" / "any robot" over one column per robot; write one check per robot)
///
/// A paragraph (goal, a step's text) names the checks backing its claims as `{id}`; the
/// loader refuses a name that is no check, and a step's or a prediction's `check` that is none.
///
/// A check that cannot fail is refused too: every quantity has a range (QuantityRangeOf:
/// an RMS, a maximum of |x|, a jitter, a count, a time constant are never negative; a flag or a
/// rate lies in [0, 1]; a ratio of two non-negative quantities is non-negative), and a bound at
/// or beyond it (`greater: 0` on an RMS, `less: 2` on a flag, `within` covering the whole range)
/// is an error at the bound's line. A bound at the edge of the range is refused only where the
/// quantity cannot sit on that edge: `greater: 0` on a count (at least one event) or on a
/// recovery time (it left the band at all) says something, on an RMS it does not.

#include <limits>
#include <string>
#include <vector>

#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

/// One claim of a lesson, as a measurement on a run and a relation it must satisfy.
struct LessonCheck {
  enum class Source { kMetric, kEvents, kColumn };
  enum class Stat { kMaxAbs, kMax, kMin, kMean, kRms, kJitter, kFirstBelow, kTau, kFinal };
  enum class Relation { kLess, kGreater, kWithin, kEqual, kAbout };

  std::string id;
  int line = 0;                   ///< line of the check in its file (for messages)
  std::vector<std::string> sets;  ///< "path=value" edits applied to the lesson's scenario
  double duration = 0.0;          ///< > 0: the run is cut to this length, s

  Source source = Source::kMetric;
  std::string name;   ///< metric path, event kind or column
  std::string robot;  ///< events: only those involving this robot ("" = all)
  Stat stat = Stat::kMaxAbs;
  double from = 0.0, to = std::numeric_limits<double>::infinity(), level = 0.0;
  std::string ratio_to;  ///< "" or the check whose value divides this one
  bool minus = false;    ///< ratio_to's value is subtracted instead (`minus: id`)

  Relation relation = Relation::kLess;
  double value = 0.0;      ///< the number compared with (less, greater, equal)
  std::string against;     ///< or the check whose value is compared with
  double lo = 0.0, hi = 0.0;  ///< within [lo, hi]
  double tolerance = 0.0;     ///< equal: |x − value| <= tolerance
  double rel = 0.1;           ///< about: |x − value| <= rel · |value|

  int seeds = 5;            ///< holds on seeds 1..seeds
  bool all_seeds = false;   ///< holds on every seed asked for
  /// The share of the seeds it must hold on (1: every seed). Below 1 only where the effect
  /// really depends on the seed, and then the text states the share measured.
  double share = 1.0;
};

/// The values a check's quantity can take: [lo, hi]; `lo_reached` / `hi_reached`: the
/// quantity can equal that end in a real run (a count can be 0, an RMS is 0 only for a run
/// without any error, which no lesson measures).
struct LessonQuantityRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_reached = true, hi_reached = true;
};

/// The range of a check's quantity before ratio_to (from its source: the stat of a column, the
/// kind of metric by its name, a count of events).
LessonQuantityRange QuantityRangeOf(const LessonCheck& check);

/// Names of the stats and relations as written in lesson files.
const char* LessonStatName(LessonCheck::Stat s);
const char* LessonRelationName(LessonCheck::Relation r);

/// A button of a lesson step: script actions run through the window's command table.
struct LessonAction {
  std::string label;                ///< the button's text ("" = the step has no action)
  std::vector<std::string> script;  ///< "edit KEY=VALUE", "reset", "pin", ... in order
};

/// A question asked before the run is played; the answer is backed by a check.
struct LessonPrediction {
  std::string question;              ///< "" = the step asks nothing
  std::vector<std::string> options;  ///< 2 ... 4
  int answer = 0;                    ///< index into options
  std::string check;                 ///< the check that backs the answer
  /// Shown once the prediction is judged (it may state the answer; its checks as {id}).
  std::string explain;
};

/// One guided step of a lesson.
struct LessonStep {
  int line = 0;  ///< line of the step in its file (for messages)
  std::string text;
  std::string check;  ///< "" or the check "what you should see" shows first
  LessonAction action;
  LessonPrediction predict;
  /// The checks the step shows: `check`, then those its text and its prediction's explanation
  /// name, each once.
  std::vector<std::string> Checks() const;
};

struct LessonDef {
  bool present = false;  ///< the scenario had a lesson: block
  std::string title, goal;
  std::vector<std::string> equations;
  std::vector<LessonStep> steps;
  std::vector<LessonCheck> checks;
  /// The check named `id`, or nullptr.
  const LessonCheck* Find(const std::string& id) const;
};

/// The check ids a paragraph names (`{id}`), in order.
std::vector<std::string> CheckReferences(const std::string& paragraph);

/// True when a paragraph states an effect: a number (a digit) or a comparison word (faster,
/// slower, larger, smaller, more, less, grows, falls, twice, half, ...). Such a paragraph must
/// name a check.
bool StatesAnEffect(const std::string& paragraph);

/// Reads a `lesson:` block strictly (unknown or duplicate keys and empty texts are errors; a
/// paragraph or step naming a missing check, a relation against a missing check, fewer than 5
/// seeds, a prediction whose answer is not one of its 2 ... 4 options are errors). Throws ScenarioError naming file:line:key.
LessonDef ReadLesson(YamlReader& block);

}  // namespace formsim::sim
