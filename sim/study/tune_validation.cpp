#include "sim/study/tune_validation.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "sim/core/number_format.hpp"
#include "sim/study/sweep.hpp"
#include "sim/study/sweep_tables.hpp"

namespace formsim::sim {
namespace {

// The objective of one completed run: the weighted sum of its metrics; NaN when it failed or a
// constraint is wanted (feasible: whether every constraint holds in this run).
double RunObjective(const TuneSettings& s, const SweepRecord& r, bool* feasible) {
  *feasible = !r.failed();
  if (r.failed()) return std::nan("");
  auto metric = [&](const std::string& path, const std::string& flag) {
    for (const auto& m : r.metrics)
      if (m.first == path) return m.second;
    std::vector<std::string> names;
    for (const auto& m : r.metrics) names.push_back(m.first);
    throw std::runtime_error(flag + ": the holdout runs have no metric '" + path +
                             "' (similar: " + SimilarMetrics(names, path) + ")");
  };
  double f = 0;
  for (const MetricTerm& t : s.objective) f += t.weight * metric(t.path, "--metric");
  for (const TuneConstraint& c : s.constraints)
    if (c.Violation(metric(c.path, "--constraint")) > 0) *feasible = false;
  return f;
}

std::string Seeds(const std::vector<std::uint64_t>& seeds) {
  std::string out;
  for (std::size_t i = 0; i < seeds.size() && i < 8; ++i)
    out += (i ? ", " : "") + std::to_string(seeds[i]);
  return out + (seeds.size() > 8 ? ", ..." : "");
}

std::string MeanCi(const MetricStats& m) {
  std::string out = FormatSignificant(m.mean, 4);
  if (!std::isnan(m.ci95_half())) out += " ± " + FormatSignificant(m.ci95_half(), 2);
  return out;
}

}  // namespace

void CheckHoldout(const std::vector<std::uint64_t>& holdout,
                  const std::vector<std::uint64_t>& seeds) {
  if (holdout.empty()) throw std::runtime_error("--holdout: give at least one seed");
  std::vector<std::uint64_t> both;
  for (std::uint64_t h : holdout)
    if (std::find(seeds.begin(), seeds.end(), h) != seeds.end()) both.push_back(h);
  if (!both.empty())
    throw std::runtime_error("--holdout: seed" + std::string(both.size() > 1 ? "s " : " ") +
                             Seeds(both) + (both.size() > 1 ? " are" : " is") +
                             " also in --seeds; held-out seeds must be ones the search never ran");
}

std::optional<TuneValidation> ValidateTune(const std::vector<ScenarioSource>& sources,
                                           const TuneSettings& s,
                                           const std::vector<double>& start_values,
                                           const std::vector<double>& best_values,
                                           const std::vector<std::uint64_t>& holdout,
                                           TaskPool& pool, const std::function<bool()>& stop) {
  const std::size_t seeds = holdout.size(), n = sources.size() * seeds;
  // Runs 0 .. n-1: the start point; n .. 2n-1: the best point; scenario-major within each.
  std::vector<std::optional<SweepRecord>> recs(2 * n);
  pool.ForEach(
      2 * n,
      [&](std::size_t i) {
        std::vector<Override> o = TuneOverrides(s, i < n ? start_values : best_values);
        o.push_back({"seed", std::to_string(holdout[i % seeds]), "--holdout", -1});
        recs[i] = RunScenarioOnce(sources[(i % n) / seeds], o, stop);
      },
      stop);
  for (const auto& r : recs)
    if (!r) return std::nullopt;
  TuneValidation v;
  v.seeds = holdout;
  for (const ScenarioSource& src : sources)
    v.scenarios.push_back(std::filesystem::path(src.file()).stem().string());
  std::vector<double> a, b, d;
  for (std::size_t i = 0; i < n; ++i) {
    bool start_ok = false, best_ok = false;
    v.start.push_back(RunObjective(s, *recs[i], &start_ok));
    v.best.push_back(RunObjective(s, *recs[n + i], &best_ok));
    v.best_feasible.push_back(best_ok);
    if (std::isfinite(v.start.back()) && std::isfinite(v.best.back())) {
      a.push_back(v.start.back());
      b.push_back(v.best.back());
      d.push_back(v.best.back() - v.start.back());
      if (d.back() < 0) ++v.best_better;
    }
  }
  v.compared = d.size();
  v.start_stats = StatsOf(a);
  v.best_stats = StatsOf(b);
  v.difference = StatsOf(d);
  return v;
}

std::string TuneValidationCsv(const TuneValidation& v) {
  std::string csv = "scenario,seed,objective_start,objective_best,difference,best_feasible\n";
  auto num = [&](double x) {
    if (!std::isnan(x)) AppendDouble(csv, x);
  };
  for (std::size_t i = 0; i < v.start.size(); ++i) {
    csv += CsvField(v.scenarios[i / v.seeds.size()]) + "," +
           std::to_string(v.seeds[i % v.seeds.size()]) + ",";
    num(v.start[i]);
    csv += ",";
    num(v.best[i]);
    csv += ",";
    num(v.best[i] - v.start[i]);
    csv += std::string(",") + (v.best_feasible[i] ? "1" : "0") + "\n";
  }
  const MetricStats* cols[] = {&v.start_stats, &v.best_stats, &v.difference};
  for (const char* row : {"mean", "ci95_lo", "ci95_hi"}) {
    csv += std::string(",") + row;
    for (const MetricStats* m : cols) {
      csv += ",";
      num(row[0] == 'm' ? m->mean : row[5] == 'l' ? m->ci95_lo : m->ci95_hi);
    }
    csv += ",\n";
  }
  return csv;
}

std::string TuneValidationText(const TuneValidation& v) {
  std::string out = "held-out seeds " + Seeds(v.seeds) +
                    (v.scenarios.size() > 1
                         ? " of " + std::to_string(v.scenarios.size()) + " scenarios"
                         : std::string()) +
                    " (" + std::to_string(v.compared) + " runs compared), objective mean ± 95% CI:\n";
  out += "  start " + MeanCi(v.start_stats) + "\n";
  out += "  best  " + MeanCi(v.best_stats) + "\n";
  out += "  best - start (paired) " + MeanCi(v.difference) + "; best is better on " +
         std::to_string(v.best_better) + " of " + std::to_string(v.compared) + " runs\n";
  std::size_t infeasible = 0;
  for (bool f : v.best_feasible) infeasible += f ? 0 : 1;
  if (infeasible > 0)
    out += "  the best point breaks a constraint on " + std::to_string(infeasible) + " of " +
           std::to_string(v.best_feasible.size()) + " held-out runs\n";
  return out;
}

}  // namespace formsim::sim
