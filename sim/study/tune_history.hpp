#pragma once
/// \file A tune's history.csv: written one row per evaluation as the tune goes (so a crash or a
/// kill keeps every finished evaluation), read back by `formsim tune --resume`, which replays the
/// recorded evaluations into the optimiser. Evaluations are deterministic and every number is
/// written as shortest round-trip text, so the optimiser asks for the same points in the same
/// order and a resumed tune ends where one never stopped would. `tune.manifest` names what the
/// history belongs to; a resume with other settings is refused.
///
/// Columns: eval, stage (its method), the tuned keys, objective, each term's mean, each
/// constrained metric's fold (when not a term's column already), feasible (1/0), failed_runs,
/// best_so_far (the best feasible objective so far), message.

#include <string>
#include <vector>

#include "sim/scenario/scenario.hpp"
#include "sim/study/tune.hpp"

namespace formsim::sim {

/// The header line (ends with '\n').
std::string TuneHistoryHeader(const TuneSettings& s);
/// The line of `e` (ends with '\n'); `best_so_far`: the best feasible objective up to it.
std::string TuneHistoryRow(const TuneSettings& s, const std::vector<TuneStage>& plan,
                           const TuneEvaluation& e, double best_so_far);
/// The whole file for a result.
std::string TuneHistoryCsv(const TuneSettings& s, const TuneResult& r);

/// The evaluations of a history.csv written for `s`, in order. A last line cut short (a kill
/// while it was written) is left out. Throws std::runtime_error naming --resume when the
/// header is another tune's or a row does not read back.
std::vector<TuneEvaluation> ReadTuneHistory(const std::string& text, const TuneSettings& s);

/// What identifies a tune for --resume: each scenario's file and SHA-256, the tuned keys and
/// bounds, the objective, the constraints, the fold, the seeds, --set, the method, the budget and
/// the search seed, one per line.
std::string TuneManifest(const std::vector<ScenarioSource>& sources, const TuneSettings& s);

}  // namespace formsim::sim
