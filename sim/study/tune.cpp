#include "sim/study/tune.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>

#include "sim/core/number_format.hpp"
#include "sim/study/sweep.hpp"
#include "sim/study/sweep_tables.hpp"

namespace formsim::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string Trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

bool IsPathChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' ||
         c == '[' || c == ']' || static_cast<unsigned char>(c) >= 0x80;
}

// Scaled coordinate u in [0, 1] <-> the tunable's value.
double ToValue(const TuneParam& p, double u) {
  u = std::clamp(u, 0.0, 1.0);
  if (u == 0.0) return p.lo;
  if (u == 1.0) return p.hi;
  const double v = p.log_scale ? std::exp(std::log(p.lo) + u * (std::log(p.hi) - std::log(p.lo)))
                               : p.lo + u * (p.hi - p.lo);
  return std::clamp(v, p.lo, p.hi);
}
double ToUnit(const TuneParam& p, double v) {
  return p.log_scale ? (std::log(v) - std::log(p.lo)) / (std::log(p.hi) - std::log(p.lo))
                     : (v - p.lo) / (p.hi - p.lo);
}

nlopt_algorithm Algorithm(const std::string& name) {
  if (name == "bobyqa") return NLOPT_LN_BOBYQA;
  if (name == "neldermead") return NLOPT_LN_NELDERMEAD;
  if (name == "cobyla") return NLOPT_LN_COBYLA;
  std::string known;
  for (const std::string& a : TuneAlgorithms()) known += (known.empty() ? "" : ", ") + a;
  throw std::runtime_error("--algorithm '" + name + "': unknown (one of " + known + ")");
}

std::string StopText(nlopt_result r) {
  switch (r) {
    case NLOPT_SUCCESS:
      return "converged";
    case NLOPT_STOPVAL_REACHED:
      return "target value reached";
    case NLOPT_FTOL_REACHED:
      return "converged (objective tolerance)";
    case NLOPT_XTOL_REACHED:
      return "converged (parameter tolerance)";
    case NLOPT_MAXEVAL_REACHED:
      return "budget used";
    case NLOPT_MAXTIME_REACHED:
      return "time limit";
    case NLOPT_FORCED_STOP:
      return "stopped";
    case NLOPT_ROUNDOFF_LIMITED:
      return "stopped by round-off";
    default:
      return std::string("NLopt failed (") + nlopt_result_to_string(r) + ")";
  }
}

struct Context {
  const ScenarioSource* source;
  const TuneSettings* settings;
  TaskPool* pool;
  const std::function<void(const TuneEvaluation&, const TuneEvaluation&)>* progress;
  const std::function<bool()>* stop;
  TuneResult* result;
  nlopt_opt opt;
  std::exception_ptr error;
  bool stopped = false;
  double worst = -kInf;  // the worst finite objective so far (penalty for failed evaluations)
  bool out_of_budget = false;
};

// Runs every seed at `values`; fills the evaluation. Returns false when stopped.
bool Evaluate(Context& c, TuneEvaluation& ev) {
  const TuneSettings& s = *c.settings;
  std::vector<Override> base = TuneOverrides(s, ev.values);
  std::vector<std::optional<SweepRecord>> recs(s.seeds.size());
  bool abandoned = false;
  c.pool->ForEach(
      s.seeds.size(),
      [&](std::size_t i) {
        std::vector<Override> o = base;
        o.push_back({"seed", std::to_string(s.seeds[i]), "--seeds", -1});
        recs[i] = RunScenarioOnce(*c.source, o, *c.stop);
      },
      *c.stop);
  for (const auto& r : recs) abandoned = abandoned || !r;
  if (abandoned) return false;
  ev.term_means.assign(s.objective.size(), 0.0);
  std::vector<std::size_t> counted(s.objective.size(), 0);
  for (std::size_t i = 0; i < recs.size(); ++i) {
    const SweepRecord& r = *recs[i];
    if (r.failed()) {
      ++ev.failed_runs;
      if (ev.message.empty())
        ev.message = "seed " + std::to_string(s.seeds[i]) + ": " + r.status + ": " + r.message;
      continue;
    }
    for (std::size_t t = 0; t < s.objective.size(); ++t) {
      const auto it = std::find_if(r.metrics.begin(), r.metrics.end(),
                                   [&](const auto& m) { return m.first == s.objective[t].path; });
      if (it == r.metrics.end()) {
        std::vector<std::string> names;
        for (const auto& m : r.metrics) names.push_back(m.first);
        throw std::runtime_error("--metric: the runs have no metric '" + s.objective[t].path +
                                 "' (similar: " + SimilarMetrics(names, s.objective[t].path) + ")");
      }
      ev.term_means[t] += it->second;
      ++counted[t];
    }
  }
  ev.objective = 0;
  for (std::size_t t = 0; t < s.objective.size(); ++t) {
    ev.term_means[t] =
        ev.failed() ? std::nan("") : ev.term_means[t] / static_cast<double>(counted[t]);
    ev.objective += s.objective[t].weight * ev.term_means[t];
  }
  if (ev.failed()) {
    ev.objective = kInf;
  } else if (!std::isfinite(ev.objective)) {
    ev.failed_runs = 0;
    ev.message = "the objective is not finite";
    ev.objective = kInf;
  }
  return true;
}

// The value the optimiser sees for an evaluation. A failed one (a numerical fault, an invalid
// combination) is worse than anything seen, but finite, so the optimiser's model stays usable.
double Seen(const Context& c, const TuneEvaluation& ev) {
  if (std::isfinite(ev.objective)) return ev.objective;
  return std::isfinite(c.worst) ? c.worst + std::max(1.0, std::abs(c.worst)) : 1e10;
}

// Evaluates `values` (or finds them evaluated already) and records the evaluation. Returns
// false when the optimisation must end: stopped, out of budget, or an error (kept in c.error).
bool Point(Context& c, const std::vector<double>& values, double* seen) {
  TuneResult& res = *c.result;
  // A point met again (NLopt's start, a Nelder-Mead revisit) is not run again.
  for (const TuneEvaluation& e : res.history)
    if (e.values == values) {
      *seen = Seen(c, e);
      return true;
    }
  if (static_cast<int>(res.history.size()) >= c.settings->budget) {
    c.out_of_budget = true;
    return false;
  }
  TuneEvaluation ev;
  ev.index = res.history.size() + 1;
  ev.values = values;
  try {
    if (!Evaluate(c, ev)) {
      c.stopped = true;
      return false;
    }
  } catch (...) {
    c.error = std::current_exception();
    return false;
  }
  res.history.push_back(ev);
  if (res.history.size() == 1 || ev.objective < res.history[res.best].objective)
    res.best = res.history.size() - 1;
  if (*c.progress) (*c.progress)(res.history.back(), res.history[res.best]);
  if (std::isfinite(ev.objective)) c.worst = std::max(c.worst, ev.objective);
  *seen = Seen(c, ev);
  return true;
}

double Objective(unsigned n, const double* u, double* /*grad*/, void* data) {
  Context& c = *static_cast<Context*>(data);
  std::vector<double> values;
  for (unsigned i = 0; i < n; ++i) values.push_back(ToValue(c.settings->params[i], u[i]));
  double seen = 0;
  if (!Point(c, values, &seen)) nlopt_force_stop(c.opt);
  return seen;
}

}  // namespace

std::vector<std::string> TuneAlgorithms() {
  return {"bobyqa", "neldermead", "cobyla"};
}

std::vector<MetricTerm> ParseMetricExpr(const std::string& expr) {
  auto fail = [&](const std::string& why) {
    return std::runtime_error("--metric '" + expr + "': " + why +
                              " (expected PATH or a sum like 'a.b + 10*c.d')");
  };
  std::vector<MetricTerm> out;
  std::size_t i = 0;
  const std::size_t n = expr.size();
  auto skip = [&] {
    while (i < n && (expr[i] == ' ' || expr[i] == '\t')) ++i;
  };
  for (;;) {
    skip();
    MetricTerm t;
    // An optional weight: a number followed by '*'.
    const char* begin = expr.c_str() + i;
    char* end = nullptr;
    const double w = std::strtod(begin, &end);
    std::size_t j = i + static_cast<std::size_t>(end - begin);
    while (j < n && (expr[j] == ' ' || expr[j] == '\t')) ++j;
    if (end != begin && j < n && expr[j] == '*') {
      if (!std::isfinite(w)) throw fail("the weight must be finite");
      t.weight = w;
      i = j + 1;
      skip();
    }
    const std::size_t start = i;
    while (i < n && IsPathChar(expr[i])) ++i;
    t.path = expr.substr(start, i - start);
    if (t.path.empty()) throw fail("a metric name is missing");
    out.push_back(t);
    skip();
    if (i == n) break;
    if (expr[i] != '+') throw fail(std::string("unexpected '") + expr[i] + "'");
    ++i;
  }
  return out;
}

TuneParam ParseTuneParam(const std::string& arg, const ParamTable& params) {
  const std::string where = "--param " + arg;
  const std::size_t colon = arg.find(':');
  TuneParam p;
  p.key = Trim(arg.substr(0, colon));
  const Param* q = params.Find(p.key);
  if (q == nullptr) throw ScenarioError(where, p.key, "not a tunable of this scenario");
  if (q->kind != Param::Kind::kDouble)
    throw ScenarioError(
        where, p.key,
        "tune searches real-valued tunables; vary integers, flags and enums with formsim sweep");
  if (colon == std::string::npos) {
    p.lo = q->slider_min();
    p.hi = q->slider_max();
  } else {
    const std::string rest = arg.substr(colon + 1);
    const std::size_t c2 = rest.find(':');
    if (c2 == std::string::npos || !ParseFiniteDouble(Trim(rest.substr(0, c2)), &p.lo) ||
        !ParseFiniteDouble(Trim(rest.substr(c2 + 1)), &p.hi))
      throw ScenarioError(where, p.key, "expected KEY or KEY:LO:HI with numbers LO and HI");
    for (double v : {p.lo, p.hi}) {
      const std::string why = q->tune.Check(v);
      if (!why.empty())
        throw ScenarioError(where, p.key,
                            "bound " + FormatDouble(v) + " is not a valid value: " + why);
    }
  }
  if (!(p.lo < p.hi))
    throw ScenarioError(
        where, p.key,
        "needs LO < HI, got [" + FormatDouble(p.lo) + ", " + FormatDouble(p.hi) + "]");
  p.log_scale = q->tune.log_scale && p.lo > 0;
  p.start = std::clamp(q->value, p.lo, p.hi);
  return p;
}

std::vector<Override> TuneOverrides(const TuneSettings& s, const std::vector<double>& values) {
  std::vector<Override> out;
  for (const Override& o : s.sets) {
    bool tuned = false;
    for (const TuneParam& p : s.params) tuned = tuned || p.key == o.key;
    if (!tuned) out.push_back(o);
  }
  for (std::size_t i = 0; i < s.params.size(); ++i)
    out.push_back({s.params[i].key, FormatDouble(values[i]), "formsim tune", -1});
  return out;
}

TuneResult RunTune(
    const ScenarioSource& source, const TuneSettings& s, TaskPool& pool,
    const std::function<void(const TuneEvaluation&, const TuneEvaluation&)>& progress,
    const std::function<bool()>& stop) {
  if (s.params.empty()) throw std::runtime_error("formsim tune: give at least one --param");
  if (s.objective.empty()) throw std::runtime_error("formsim tune: give --metric");
  if (s.seeds.empty()) throw std::runtime_error("formsim tune: give --seeds");
  if (s.budget < 1) throw std::runtime_error("--budget must be at least 1");
  const nlopt_algorithm alg = Algorithm(s.algorithm);
  const unsigned n = static_cast<unsigned>(s.params.size());
  TuneResult result;
  nlopt_srand(1);  // no algorithm offered here draws random numbers; fixed all the same
  nlopt_opt opt = nlopt_create(alg, n);
  if (opt == nullptr) throw std::runtime_error("NLopt could not create the optimiser");
  Context c{&source, &s, &pool, &progress, &stop, &result, opt, nullptr};
  // The first steps span 15 % of each interval (NLopt keeps them inside the bounds).
  std::vector<double> lb(n, 0.0), ub(n, 1.0), u(n), step(n, 0.15);
  std::vector<double> start;
  for (unsigned i = 0; i < n; ++i) {
    u[i] = std::clamp(ToUnit(s.params[i], s.params[i].start), 0.0, 1.0);
    start.push_back(s.params[i].start);
  }
  // Evaluation 1 is the scenario's own values, exactly (BOBYQA may move its first point away
  // from a bound).
  double seen = 0;
  nlopt_result r = NLOPT_MAXEVAL_REACHED;
  if (Point(c, start, &seen)) {
    nlopt_set_lower_bounds(opt, lb.data());
    nlopt_set_upper_bounds(opt, ub.data());
    nlopt_set_min_objective(opt, Objective, &c);
    nlopt_set_maxeval(opt, 2 * s.budget + 10);  // the budget counts new points (Point stops)
    nlopt_set_xtol_abs1(opt, 1e-5);             // 1e-5 of each search interval
    nlopt_set_initial_step(opt, step.data());
    double fmin = 0;
    r = nlopt_optimize(opt, u.data(), &fmin);
  }
  nlopt_destroy(opt);
  if (c.error) std::rethrow_exception(c.error);
  result.stop_reason = c.stopped                                   ? "interrupted"
                       : c.out_of_budget || r == NLOPT_FORCED_STOP ? "budget used"
                                                                   : StopText(r);
  return result;
}

std::string TuneHistoryCsv(const TuneSettings& s, const TuneResult& r) {
  std::string csv = "eval";
  for (const TuneParam& p : s.params) csv += "," + p.key;
  csv += ",objective";
  for (const MetricTerm& t : s.objective) csv += ",mean." + t.path;
  csv += ",failed_runs,best_so_far,message\n";
  double best = kInf;
  for (const TuneEvaluation& e : r.history) {
    csv += std::to_string(e.index);
    for (double v : e.values) {
      csv += ',';
      AppendDouble(csv, v);
    }
    csv += ',';
    AppendDouble(csv, e.objective);
    for (double m : e.term_means) {
      csv += ',';
      if (!std::isnan(m)) AppendDouble(csv, m);
    }
    best = std::min(best, e.objective);
    csv += "," + std::to_string(e.failed_runs) + ",";
    AppendDouble(csv, best);
    csv += "," + CsvField(e.message) + "\n";
  }
  return csv;
}

}  // namespace formsim::sim
