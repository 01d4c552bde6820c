#pragma once
/// \file Evaluating a lesson's checks (lesson.hpp): every run a check needs (the lesson's
/// scenario with the check's edits, duration and a seed) is run once, through the path sweeps
/// use (RunScenarioOnce), on a TaskPool; each check's quantity is measured on its runs and its
/// relation tested seed by seed. Results depend on the lesson and the seeds alone, never on the
/// number of jobs.
///
/// The check language (each form documented in sim/scenario/lesson.hpp's header): a quantity
/// (metric, events [of one robot], column stat over a time window from/to), optionally divided
/// by another check's value (ratio_to: "halves" is `ratio_to: base  less: 0.55`) or shifted by it
/// (minus: a displacement between two runs); a relation: less / greater (a sign: less: 0 on a
/// signed quantity), within, equal (± tolerance), about (± rel, relative: "6.7 s" is `about: 6.7`),
/// against a number or another check; seeds, and a share of them for an effect that depends on
/// the seed ("in 27 of 30 seeds": share: 0.9). The loader refuses a bound at or beyond the
/// quantity's range (QuantityRangeOf): a check that cannot fail.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sim/core/experiment.hpp"
#include "sim/scenario/lesson.hpp"

namespace formsim::sim {

/// One check's outcome over its seeds.
struct LessonCheckResult {
  std::string lesson;  ///< the lesson's file stem
  std::string id;
  std::vector<std::uint64_t> seeds;
  std::vector<double> values;    ///< the measured quantity per seed (after ratio_to)
  std::vector<double> operands;  ///< what it was compared with per seed (a number or a check's value)
  std::vector<bool> holds;       ///< per seed
  /// Over robots (every / any): per seed, the robot whose value `values` holds, the one that
  /// decides (every: nearest to failing; any: holding best). Empty for a check of one value.
  std::vector<std::string> deciders;
  std::string relation;          ///< "< 0.01", "within [0.9, 1.1]", "< base", ...
  bool against_check = false;    ///< compared with another check's values (operands)
  std::string error;             ///< a run failed or the quantity does not exist ("" when measured)
  double share = 1.0;            ///< the share of the seeds it must hold on (the check's share)
  /// measured and holding on every seed (or on its share of them); a check with a share < 1
  /// whose value is the same on every seed fails: its text claims a seed effect there is not.
  bool ok() const;
  bool SeedChangesNothing() const;  ///< share < 1, yet the same value on every seed (2 or more)
};

struct LessonCheckOptions {
  /// Seeds every check runs on; empty: each check's own (1..seeds, or 1..5 for `all`).
  std::vector<std::uint64_t> seeds;
  int jobs = 1;  ///< runs at once
  /// Only these check ids (empty: all).
  std::vector<std::string> only;
  /// Edits ("path=value") applied to every run before each check's own `set` (a deliberate error
  /// in the scenario: the mutation test expects some check to fail).
  std::vector<std::string> extra_sets;
};

/// Measures a column over [from, to] (rows whose time lies in it; NotSampled and NaN cells are
/// skipped). Returns NaN when no value lies in the window (tau: fewer than 3 non-zero values;
/// first_below: +inf when the level is never crossed).
double ColumnStat(const std::vector<double>& t, const std::vector<double>& x,
                  const LessonCheck& check);

/// True when `value` satisfies the check's relation against `operand` (the relation's number
/// or the other check's value).
bool RelationHolds(const LessonCheck& check, double value, double operand);

/// Evaluates the checks of the lesson in `file` (a scenario file with a lesson: block). Throws
/// ScenarioError / std::runtime_error when the file cannot be read.
std::vector<LessonCheckResult> CheckLesson(const std::string& file, const LessonCheckOptions& opt);

/// A check measured on one run (the window's current run).
struct LiveCheck {
  bool ready = false;  ///< the run has reached the time the check needs (else nothing measured)
  double value = 0.0;
  bool holds = false;
  std::string error;  ///< the run is not the check's (it needs other edits or another duration),
                      ///< or the quantity does not exist; "" when measured
  std::string robot = std::string();  ///< over robots: the robot that decides (whose value `value` is)
};

/// How the run measured live came about.
struct RunEdits {
  /// What it started with beside the lesson's file: key -> value text (--set and the window's
  /// edits; the seed left out).
  std::map<std::string, std::string> edits;
  bool changed_while_running = false;  ///< edited, dragged or acted on after its start
};

/// The run time a live run must reach before `check` (with the checks it is compared with or
/// divided by) can be measured on it: the end of its column windows; +inf: the whole run.
double CheckNeedsTime(const LessonDef& lesson, const LessonCheck& check);

/// Measures `check` of `lesson` on the run `exp` with the relation tested, once the run has
/// reached CheckNeedsTime (or ended). A check is measured only on its own run: started with
/// exactly the check's edits (`set`), unchanged while running, of the check's duration (a column
/// check whose window ends by then also on a longer run: a run's first seconds do not depend on
/// its length); the others report what they need in `error`.
LiveCheck MeasureOnRun(const LessonDef& lesson, const LessonCheck& check, const Experiment& exp,
                       const RunEdits& run = {});

/// The relation as printed: "< 0.01", "within [0.9, 1.1] (ratio to base)", ... (check ids bare: no {name} reaches a student)
std::string LessonRelationText(const LessonCheck& check);

/// A check's value as a paragraph shows it.
struct ShownCheck {
  bool measured = false;  ///< false: pending (not measured yet, or not on this run)
  double value = 0.0;
  bool holds = false;
  bool some_seeds = false;  ///< the check claims its share of the seeds only (share < 1)
  std::string robot = std::string();  ///< over robots: the robot that decides, shown before the value
};

/// The one renderer of a lesson's text, shared by the window, the page and `formsim lessons
/// show`: every `{id}` of `paragraph` becomes the check's value and verdict, "(0.995 √)" when
/// it holds ("(R6: −0.0012 √)" for a check over robots, naming the robot that decides), "(0.9, does not hold)" when it does not ("(0.9, not on this seed)" for a check
/// that claims a share of the seeds), "(…)" while pending (`shown` returns measured =
/// false); no `{id}` is left. Text in braces that names no check is kept as it is.
std::string RenderLessonParagraph(const std::string& paragraph,
                                  const std::function<ShownCheck(const std::string& id)>& shown);

/// A lesson's whole text as `formsim lessons show` prints it: title, goal, equations, then each
/// step (its text, its prediction's question, options and answer, its explanation), every
/// paragraph through RenderLessonParagraph with `shown`.
std::string RenderLessonText(const LessonDef& lesson,
                             const std::function<ShownCheck(const std::string& id)>& shown);

/// One line per result: "lesson  id  values  relation  holds|FAILS".
std::string FormatCheckResult(const LessonCheckResult& r);

/// A check whose value is the same on every seed checked while the lesson's text says its
/// effect depends on the seed (ChecksClaimingASeedEffect): the claim is not what the runs show.
struct SeedEffectWarning {
  std::string lesson, id;
  double value = 0.0;
  std::size_t seeds = 0;
  std::string claim;  ///< the sentence (or "share: 0.9") that claims the effect
};

/// The warnings for one lesson's results (checked on 2 seeds or more; a check measured on one
/// seed, or not measured, gives none).
std::vector<SeedEffectWarning> SeedEffectWarnings(const LessonDef& lesson,
                                                  const std::vector<LessonCheckResult>& results);

/// "warning: LESSON: check ID is V on every one of the N seeds checked, yet the text says it
/// depends on the seed: \"...\"".
std::string FormatSeedEffectWarning(const SeedEffectWarning& w);

}  // namespace formsim::sim
