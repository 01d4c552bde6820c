#pragma once
/// \file What a sweep runs: its scenarios, `--vary KEY=SPEC` axes expanded into values, the
/// parameter points (every combination), the seeds, and so the numbered list of runs. Run r is
/// scenario r / (points x seeds), point (r / seeds) % points, seed r % seeds (one scenario: point
/// r / seeds); the numbering depends only on the definition, never on how or where the runs are
/// executed, so shards, resumed sweeps and job lists all agree on it.
///
/// SPEC is a list (`0.1,0.2,0.4`, `truth,raw,ukf`, `all` for every choice of an enum or flag),
/// a linear range `LO:HI:N`, a log range `log:LO:HI:N`, or `random:N` (`random:N:LO:HI`):
/// N samples within the tunable's declared slider range (log-spaced when the slider is), drawn
/// as one Latin hypercube shared by every random axis, seeded by the sample seed.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/core/param_table.hpp"
#include "sim/core/provenance.hpp"
#include "sim/scenario/scenario.hpp"

namespace formsim::sim {

/// The largest sweep formsim plans at all (runs = points x seeds), whatever `--max-runs` says.
constexpr std::size_t kMaxSweepRuns = 10000000;
/// The largest sweep formsim plans unless asked for more (`formsim sweep --max-runs N`).
constexpr std::size_t kDefaultMaxSweepRuns = 100000;

/// One varied tunable.
struct SweepAxis {
  std::string key;   ///< the tunable's key, e.g. "robots.R2.follow.k_l"
  std::string spec;  ///< as given after '='
  Param::Kind kind = Param::Kind::kDouble;
  std::vector<std::string> choices;  ///< names of an enum (or false/true)
  std::vector<std::string> values;   ///< YAML text of each value (random: one per sample)
  bool log_scale = false;  ///< figures use log10 of the value (log ranges, log random samples)
  bool random = false;     ///< a Latin hypercube axis (paired with the other random axes)

  /// True for enums and flags: figures place them by index and label them by name.
  bool categorical() const { return kind == Param::Kind::kBool || kind == Param::Kind::kChoice; }
  /// values[i] as a number (the choice index for enums and flags).
  double Numeric(std::size_t i) const;
};

/// One scenario of a sweep.
struct SweepScenario {
  std::string file;    ///< the scenario file as given (for messages and job lines)
  std::string sha256;  ///< of its text: a sweep is tied to one text of each scenario
  /// Its name in the tables and figures: the file's stem (ScenarioStem).
  std::string Name() const;
};

/// A sweep: its scenarios, fixed overrides, the axes, the seeds and the points they make. Every
/// scenario runs every point with every seed.
struct SweepDefinition {
  std::vector<SweepScenario> scenarios;  ///< at least one; several: a `scenario` column
  std::vector<Override> sets;   ///< --set overrides applied to every run
  std::vector<SweepAxis> axes;
  std::vector<std::uint64_t> seeds;
  std::uint64_t sample_seed = 1;  ///< seeds the Latin hypercube of random:N axes
  /// points[p][a]: index into axes[a].values (random axes: the sample row).
  std::vector<std::vector<std::size_t>> points;
  std::string id;  ///< SHA-256 of everything that defines the runs (not of file paths)

  std::size_t runs() const { return scenarios.size() * points.size() * seeds.size(); }
  /// True for a sweep over more than one scenario (its tables get a `scenario` column).
  bool MultiScenario() const { return scenarios.size() > 1; }
  std::size_t ScenarioOf(std::size_t run) const { return run / (points.size() * seeds.size()); }
  std::size_t PointOf(std::size_t run) const { return (run / seeds.size()) % points.size(); }
  std::uint64_t SeedOf(std::size_t run) const { return seeds[run % seeds.size()]; }
  /// The value of axis `a` at point `p` as YAML text.
  const std::string& Value(std::size_t p, std::size_t a) const {
    return axes[a].values[points[p][a]];
  }
  /// --set overrides, then the point's values, then the seed: what ParseScenario gets.
  std::vector<Override> RunOverrides(std::size_t run) const;
  /// The axes that are crossed with each other (no random axis among them).
  bool IsGrid() const;
  /// Recomputes `points` and `id` from the axes, seeds and the rest (after reading a manifest).
  void Finish();
};

/// `text` cut at every `sep` ("a,,b" -> "a", "", "b"; "" -> one empty piece): the lists of
/// --vary, --seeds, --tables and metric paths.
std::vector<std::string> SplitAt(const std::string& text, char sep);

/// "1..20", "1,2,5", "3" or mixtures ("1..5,9"); seeds are 0 ... 2^64-1, no duplicates, at most
/// 1000000. An empty text is refused too. Throws std::runtime_error naming `flag`.
std::vector<std::uint64_t> ParseSeeds(const std::string& text, const std::string& flag = "--seeds");

/// The number of runs `vary` x `seeds` makes, counted from the specs alone (a list's items, a
/// range's N, random:N once for all random axes, `all` as the choices of `params`' tunable),
/// without building any value; saturates at SIZE_MAX instead of overflowing. A spec that does
/// not parse counts 1 (DefineSweep reports it). `seed_count` 0 counts as 1 (the scenario's).
std::size_t CountSweepRuns(const ParamTable& params, const std::vector<std::string>& vary,
                           std::size_t seed_count);

/// Builds a sweep of `sources` (one or more scenarios) with fixed `sets`. `vary` holds
/// "KEY=SPEC" strings; every key must be a tunable of the first scenario (with `sets` applied)
/// and every value valid for it; every other scenario must have each key as a tunable of the same
/// kind (CheckScenarioKeys) for which every value is valid too. Empty
/// `seeds`: the scenario's own seed. A sweep of more than `max_runs` runs (at most
/// kMaxSweepRuns) is refused before any value is built, with its run count. Throws
/// ScenarioError naming the --vary argument (or `--scenario FILE` and the key),
/// std::runtime_error for the run count.
SweepDefinition DefineSweep(const std::vector<ScenarioSource>& sources,
                            const std::vector<Override>& sets, const std::vector<std::string>& vary,
                            std::vector<std::uint64_t> seeds, std::uint64_t sample_seed = 1,
                            std::size_t max_runs = kDefaultMaxSweepRuns);
/// One scenario.
SweepDefinition DefineSweep(const ScenarioSource& source, const std::vector<Override>& sets,
                            const std::vector<std::string>& vary, std::vector<std::uint64_t> seeds,
                            std::uint64_t sample_seed = 1,
                            std::size_t max_runs = kDefaultMaxSweepRuns);

/// `n` points of a Latin hypercube in [0, 1)^dims: each dimension is cut into n equal strata
/// and every stratum holds exactly one point. Deterministic for a seed.
std::vector<std::vector<double>> LatinHypercube(std::size_t n, std::size_t dims,
                                                std::uint64_t seed);

}  // namespace formsim::sim
