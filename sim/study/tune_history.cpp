#include "sim/study/tune_history.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "control/common/float_limits.hpp"
#include "sim/core/number_format.hpp"
#include "sim/study/sweep_tables.hpp"

namespace formsim::sim {
namespace {

using control::kInf;

// Constraints with a column of their own: a term's column holds a constrained metric already
// when the fold is the mean.
std::vector<std::size_t> ConstraintColumns(const TuneSettings& s) {
  const bool mean = s.over.kind == TuneOver::Kind::kMean;
  std::vector<std::size_t> shown;
  for (std::size_t k = 0; k < s.constraints.size(); ++k) {
    bool dup = false;
    for (const MetricTerm& t : s.objective) dup = dup || (mean && t.path == s.constraints[k].path);
    for (std::size_t j : shown) dup = dup || s.constraints[j].path == s.constraints[k].path;
    if (!dup) shown.push_back(k);
  }
  return shown;
}

void Number(std::string& csv, double v) {
  csv += ',';
  if (!std::isnan(v)) AppendDouble(csv, v);
}

// The records of a CSV text (quoted fields may hold commas, quotes and line breaks); a last
// record without its line break is dropped (torn by a kill).
std::vector<std::vector<std::string>> Records(const std::string& text) {
  std::vector<std::vector<std::string>> out;
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c == '\n') {
      out.push_back(std::move(fields));
      fields.assign(1, "");
    } else {
      fields.back() += c;
    }
  }
  return out;
}

// A number of history.csv: empty is NaN, "inf" the objective of a failed evaluation.
double Read(const std::string& field, std::size_t row) {
  if (field.empty()) return std::nan("");
  if (field == "inf") return kInf;
  double v = 0;
  if (!ParseFiniteDouble(field, &v))
    throw std::runtime_error("--resume: history.csv row " + std::to_string(row) + ": '" + field +
                             "' is not a number");
  return v;
}

}  // namespace

std::string TuneHistoryHeader(const TuneSettings& s) {
  const bool mean = s.over.kind == TuneOver::Kind::kMean;
  std::string csv = "eval,stage";
  for (const TuneParam& p : s.params) csv += "," + p.key;
  csv += ",objective";
  for (const MetricTerm& t : s.objective) csv += ",mean." + t.path;
  for (std::size_t k : ConstraintColumns(s))
    csv += "," + (mean ? std::string("mean") : s.over.Text()) + "." + s.constraints[k].path;
  return csv + ",feasible,failed_runs,best_so_far,message\n";
}

std::string TuneHistoryRow(const TuneSettings& s, const std::vector<TuneStage>& plan,
                           const TuneEvaluation& e, double best_so_far) {
  std::string csv = std::to_string(e.index) + ",";
  csv += e.stage < plan.size() ? plan[e.stage].method : s.algorithm;
  for (std::size_t i = 0; i < e.values.size(); ++i) {
    if (s.params[i].kind == TuneParam::Kind::kChoice)
      csv += "," + CsvField(s.params[i].Text(e.values[i]));  // the choice's name
    else
      Number(csv, e.values[i]);
  }
  Number(csv, e.objective);
  for (double m : e.term_means) Number(csv, m);
  for (std::size_t k : ConstraintColumns(s))
    Number(csv, k < e.constraint_means.size() ? e.constraint_means[k] : std::nan(""));
  csv += std::string(",") + (e.feasible() ? "1" : "0") + "," + std::to_string(e.failed_runs);
  Number(csv, best_so_far);
  return csv + "," + CsvField(e.message) + "\n";
}

std::string TuneHistoryCsv(const TuneSettings& s, const TuneResult& r) {
  std::string csv = TuneHistoryHeader(s);
  double best = kInf;
  for (const TuneEvaluation& e : r.history) {
    if (e.feasible()) best = std::min(best, e.objective);
    csv += TuneHistoryRow(s, r.plan, e, best);
  }
  return csv;
}

std::vector<TuneEvaluation> ReadTuneHistory(const std::string& text, const TuneSettings& s) {
  const std::string header = TuneHistoryHeader(s);
  if (text.compare(0, header.size(), header) != 0)
    throw std::runtime_error(
        "--resume: history.csv has other columns than this tune writes (another tune's history)");
  const std::vector<std::vector<std::string>> rows = Records(text.substr(header.size()));
  const std::vector<std::size_t> shown = ConstraintColumns(s);
  const std::size_t width =
      2 + s.params.size() + 1 + s.objective.size() + shown.size() + 4;
  std::vector<TuneEvaluation> out;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::vector<std::string>& f = rows[r];
    const std::size_t row = r + 1;
    if (f.size() != width || f[0] != std::to_string(row))
      throw std::runtime_error("--resume: history.csv row " + std::to_string(row) +
                               " does not read back (" + std::to_string(f.size()) + " fields, " +
                               std::to_string(width) + " expected)");
    TuneEvaluation e;
    e.index = row;
    std::size_t c = 2;
    for (std::size_t i = 0; i < s.params.size(); ++i) {
      const TuneParam& p = s.params[i];
      if (p.kind != TuneParam::Kind::kChoice) {
        e.values.push_back(Read(f[c++], row));
        continue;
      }
      const auto it = std::find(p.choices.begin(), p.choices.end(), f[c++]);
      if (it == p.choices.end())
        throw std::runtime_error("--resume: history.csv row " + std::to_string(row) + ": '" +
                                 f[c - 1] + "' is not a choice of " + p.key);
      e.values.push_back(static_cast<double>(it - p.choices.begin()));
    }
    e.objective = Read(f[c++], row);
    for (std::size_t t = 0; t < s.objective.size(); ++t) e.term_means.push_back(Read(f[c++], row));
    // A constraint without a column of its own reads its term's mean.
    e.constraint_means.assign(s.constraints.size(), std::nan(""));
    for (std::size_t k : shown) e.constraint_means[k] = Read(f[c++], row);
    for (std::size_t k = 0; k < s.constraints.size(); ++k)
      for (std::size_t t = 0; t < s.objective.size(); ++t)
        if (std::isnan(e.constraint_means[k]) && s.objective[t].path == s.constraints[k].path)
          e.constraint_means[k] = e.term_means[t];
    c++;  // feasible: recomputed from the constraints
    long long failed = 0;
    if (!ParseInteger(f[c++], 0, 1LL << 40, &failed))
      throw std::runtime_error("--resume: history.csv row " + std::to_string(row) +
                               ": failed_runs is not a count");
    e.failed_runs = static_cast<std::size_t>(failed);
    c++;  // best_so_far: recomputed
    e.message = f[c];
    e.violation = 0;
    if (!e.failed())
      for (std::size_t k = 0; k < s.constraints.size(); ++k)
        e.violation = std::max(e.violation, s.constraints[k].Violation(e.constraint_means[k]));
    out.push_back(std::move(e));
  }
  return out;
}

std::string TuneManifest(const std::vector<ScenarioSource>& sources, const TuneSettings& s) {
  std::string m = "formsim tune manifest 1\n";
  for (const ScenarioSource& src : sources) m += "scenario " + src.file() + " " + src.sha256() + "\n";
  for (const TuneParam& p : s.params) {
    m += "param " + p.key + " ";
    AppendDouble(m, p.lo);
    m += " ";
    AppendDouble(m, p.hi);
    m += p.log_scale ? " log" : p.kind == TuneParam::Kind::kInteger ? " integer" : "";
    for (const std::string& choice : p.choices) m += " " + choice;
    m += "\n";
  }
  for (const MetricTerm& t : s.objective) {
    m += "term ";
    AppendDouble(m, t.weight);
    m += " " + t.path + "\n";
  }
  for (const TuneConstraint& c : s.constraints) m += "constraint " + c.Text() + "\n";
  m += "over " + s.over.Text() + "\nseeds";
  for (std::uint64_t seed : s.seeds) m += " " + std::to_string(seed);
  m += "\n";
  for (const Override& o : s.sets) m += "set " + o.key + "=" + o.value + "\n";
  m += "method " + s.algorithm + "\nbudget " + std::to_string(s.budget) + "\nsearch_seed " +
       std::to_string(s.search_seed) + "\n";
  return m;
}

}  // namespace formsim::sim
