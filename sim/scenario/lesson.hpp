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
///     checks:                                          (required when a sentence states an effect)
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
///   "every robot below R2 ..."       every: [R3, R4, R5, R6, R7]  column: "*.x" ...
///   "some robot ..."                 any: [R2, R3]  metric: "robots.*.rms" ...
///        (the quantity once per robot: `*` in the metric, the column or an event's robot
///         stands for each robot named, or each link: every: [R1-R2, R2-R3]  column: "*.e_l"; the relation must hold for every robot / for at least
///         one. The value shown is the robot that decides: for every, the one nearest to failing
///         (or failing); for any, the one holding best. A ratio_to / minus / relation against
///         another check over the same robots pairs them robot by robot; against a check of one
///         quantity, every robot is compared with its value. A check of one quantity cannot
///         refer to a check over robots.)
///
/// Every sentence of a lesson's text (the goal, a step's text, a prediction's explanation)
/// that states a claim, a number or a comparison (StatesAnEffect), names the checks backing it
/// as `{id}` (SentencesWithoutCheck lists those that do not; the shipped lessons have none).
/// An instruction (a sentence that starts with a verb of LessonInstructionVerbs: "Set r_xy to
/// 0.1 and reset") states a setting, not a claim; only what follows its first ':' is a claim.
/// A prediction's question and options are backed by its `check`.
/// The loader refuses a `{name}` that is no check, and a step's or a prediction's `check` that is
/// none.
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
#include <utility>
#include <vector>

#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

/// One claim of a lesson, as a measurement on a run and a relation it must satisfy.
struct LessonCheck {
  enum class Source { kMetric, kEvents, kColumn };
  enum class Stat { kMaxAbs, kMax, kMin, kMean, kRms, kJitter, kFirstBelow, kTau, kFinal };
  enum class Relation { kLess, kGreater, kWithin, kEqual, kAbout };

  /// One quantity, or one per robot (`every:` / `any:` a list of robots; `*` in the name).
  enum class Over { kOne, kEvery, kAny };

  std::string id;
  int line = 0;                   ///< line of the check in its file (for messages)
  std::vector<std::string> sets;  ///< "path=value" edits applied to the lesson's scenario
  double duration = 0.0;          ///< > 0: the run is cut to this length, s

  Source source = Source::kMetric;
  std::string name;   ///< metric path, event kind or column
  std::string robot;  ///< events: only those involving this robot ("" = all)
  Stat stat = Stat::kMaxAbs;
  double from = 0.0, to = std::numeric_limits<double>::infinity(), level = 0.0;
  Over over = Over::kOne;
  std::vector<std::string> robots;  ///< every / any: the robots `*` stands for, in order
  /// The check for one robot: `*` in the name (and an event's robot) replaced by `robot`, and
  /// one quantity (over = kOne).
  LessonCheck ForRobot(const std::string& robot) const;

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

/// True when a text states an effect: a number (a digit that starts a token: "2 s", "0.5",
/// "90°", not the "3" of "R3" or "u1") or a comparison or direction word (faster, slower,
/// larger, smaller, more, less, grows, falls, twice, half, best, worse, behind, ...). Such a
/// sentence must name a check.
bool StatesAnEffect(const std::string& text);

/// A paragraph cut into sentences: at '.', '!' or '?' followed by a blank or the end ("0.5",
/// "R4..R7" and "e.g." stay whole). A `{id}` stays with the sentence it is written in.
std::vector<std::string> SplitSentences(const std::string& paragraph);

/// The verbs an instruction starts with ("Set", "Halve", "Load", ...): such a sentence states a
/// setting the student makes, not a claim about a run; only the part after its first ':' can
/// state one.
const std::vector<std::string>& LessonInstructionVerbs();

/// The part of a sentence that can state a claim: all of it, or for an instruction what
/// follows its first ':' ("" when nothing does).
std::string ClaimPart(const std::string& sentence);

/// A sentence of a lesson that states a claim (StatesAnEffect of its ClaimPart) without naming
/// a check.
struct UnbackedSentence {
  std::string where;     ///< "goal", "step 3", "step 3's explanation"
  int line = 0;          ///< the step's line (0 for the goal)
  std::string sentence;
};
/// Every sentence of the goal, the steps' texts and the explanations that states a claim and
/// names no check `{id}`.
std::vector<UnbackedSentence> SentencesWithoutCheck(const LessonDef& lesson);

/// True when a sentence says its effect depends on the seed ("seed", "varies", "depends on
/// the noise", "on some seeds", "in 27 of 30 ...").
bool ClaimsASeedEffect(const std::string& sentence);

/// The checks the lesson's text says depend on the seed: those named in a sentence that
/// ClaimsASeedEffect, and those with a share < 1; each with the sentence (or "share: 0.9").
std::vector<std::pair<std::string, std::string>> ChecksClaimingASeedEffect(const LessonDef& lesson);

/// Reads a `lesson:` block strictly (unknown or duplicate keys and empty texts are errors; a
/// paragraph or step naming a missing check, a relation against a missing check, fewer than 5
/// seeds, a prediction whose answer is not one of its 2 ... 4 options are errors). Throws ScenarioError naming file:line:key.
LessonDef ReadLesson(YamlReader& block);

}  // namespace formsim::sim
