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
///     watch: "..."                                     (required: what to watch)
///     try_next: "..."                                  (required: what to try next)
///     equations: ["l̇ = −k_l (l − l_des)", ...]          (optional, readable text / Unicode)
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
///         # the relation, exactly one of (a number, or the id of a check: its value, same seed):
///         less: 0.01 | greater: other_id | within: [0.9, 1.1] | equal: 0  (tolerance: 0)
///         seeds: 5                   (at least 5: seeds 1..N; or `all`: every seed asked for)
///
/// A paragraph (goal, watch, try_next) names the checks backing its claims as `{id}`; the
/// loader refuses a name that is no check.

#include <limits>
#include <string>
#include <vector>

#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

/// One claim of a lesson, as a measurement on a run and a relation it must satisfy.
struct LessonCheck {
  enum class Source { kMetric, kEvents, kColumn };
  enum class Stat { kMaxAbs, kMax, kMin, kMean, kRms, kJitter, kFirstBelow, kTau, kFinal };
  enum class Relation { kLess, kGreater, kWithin, kEqual };

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

  Relation relation = Relation::kLess;
  double value = 0.0;      ///< the number compared with (less, greater, equal)
  std::string against;     ///< or the check whose value is compared with
  double lo = 0.0, hi = 0.0;  ///< within [lo, hi]
  double tolerance = 0.0;     ///< equal: |x − value| <= tolerance

  int seeds = 5;            ///< holds on seeds 1..seeds
  bool all_seeds = false;   ///< holds on every seed asked for
};

/// Names of the stats and relations as written in lesson files.
const char* LessonStatName(LessonCheck::Stat s);
const char* LessonRelationName(LessonCheck::Relation r);

struct LessonDef {
  bool present = false;  ///< the scenario had a lesson: block
  std::string title, goal, watch, try_next;
  std::vector<std::string> equations;
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
/// paragraph naming a missing check, a relation against a missing check, fewer than 5 seeds
/// are errors). Throws ScenarioError naming file:line:key.
LessonDef ReadLesson(YamlReader& block);

}  // namespace formsim::sim
