#include "sim/study/tune.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>

#include "control/common/float_limits.hpp"
#include "sim/core/number_format.hpp"
#include "sim/study/metric_stats.hpp"
#include "sim/study/scenario_set.hpp"
#include "sim/study/sweep.hpp"
#include "sim/study/sweep_tables.hpp"

namespace formsim::sim {
namespace {

using control::kInf;

std::string Trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

bool IsPathChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' ||
         c == '[' || c == ']' || static_cast<unsigned char>(c) >= 0x80;
}

nlopt_algorithm Algorithm(const std::string& name) {
  if (name == "bobyqa") return NLOPT_LN_BOBYQA;
  if (name == "neldermead") return NLOPT_LN_NELDERMEAD;
  if (name == "cobyla") return NLOPT_LN_COBYLA;
  if (name == "direct-l") return NLOPT_GN_DIRECT_L;
  if (name == "crs2") return NLOPT_GN_CRS2_LM;
  if (name == "mlsl") return NLOPT_G_MLSL_LDS;
  return NLOPT_GN_ISRES;  // PlanTune let only known names through
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
  const std::vector<ScenarioSource>* sources;
  const TuneSettings* settings;
  TaskPool* pool;
  const std::function<void(const TuneEvaluation&, const TuneEvaluation&)>* progress;
  const std::function<bool()>* stop;
  TuneResult* result;
  std::vector<nlopt_opt> opts;  // every optimiser of the stage (an AUGLAG's subsidiary too)
  std::exception_ptr error;
  bool stopped = false;
  double worst = -kInf;  // the worst finite objective so far (penalty for failed evaluations)
  bool out_of_budget = false;
  std::size_t stage = 0;
  int limit = 0;  // evaluations recorded at most by the end of this stage
  const std::vector<TuneEvaluation>* recorded = nullptr;  // --resume: replayed, not run
  // The stage's coordinates: the optimiser's coordinate j is key dims[j]; the other keys keep
  // their value in `base` (a local polish holds the integer and choice keys).
  std::vector<std::size_t> dims{};
  std::vector<double> base{};
};

// The value of metric `path` in a completed run, for `flag` (--metric or --constraint). A
// setting (what the run ran with) or a missing name is refused, with the names there are.
double MetricIn(const SweepRecord& r, const std::string& path, const std::string& flag) {
  for (const auto& m : r.metrics)
    if (m.first == path) return m.second;
  for (const auto& m : r.settings)
    if (m.first == path)
      throw std::runtime_error(flag + ": '" + path +
                               "' is a setting the run ran with, not a result of it");
  std::vector<std::string> names;
  for (const auto& m : r.metrics) names.push_back(m.first);
  throw std::runtime_error(flag + ": the runs have no metric '" + path +
                           "' (similar: " + SimilarMetrics(names, path) + ")");
}

// Runs every scenario on every seed at `values`; fills the evaluation. Returns false when
// stopped.
bool Evaluate(Context& c, TuneEvaluation& ev) {
  const TuneSettings& s = *c.settings;
  const std::vector<ScenarioSource>& sources = *c.sources;
  std::vector<Override> base = TuneOverrides(s, ev.values);
  const std::size_t runs = sources.size() * s.seeds.size();
  std::vector<std::optional<SweepRecord>> recs(runs);
  c.pool->ForEach(
      runs,
      [&](std::size_t i) {
        std::vector<Override> o = base;
        o.push_back({"seed", std::to_string(s.seeds[i % s.seeds.size()]), "--seeds", -1});
        recs[i] = RunScenarioOnce(sources[i / s.seeds.size()], o, *c.stop);
      },
      *c.stop);
  for (const auto& r : recs)
    if (!r) return false;
  // Per run: the weighted sum, and each constrained metric (mirrored for >=, so the fold's
  // worst case is the largest value for every constraint).
  std::vector<double> sums;
  std::vector<std::vector<double>> constrained(s.constraints.size());
  ev.term_means.assign(s.objective.size(), 0.0);
  // The first completed run tells what the metrics are (labels and units for the figures).
  for (std::size_t i = 0; i < runs && c.result->info.empty(); ++i)
    if (!recs[i]->failed())
      for (const auto& [path, info] : recs[i]->info) {
        bool wanted = false;
        for (const MetricTerm& t : s.objective) wanted = wanted || t.path == path;
        for (const TuneConstraint& k : s.constraints) wanted = wanted || k.path == path;
        if (wanted) c.result->info.emplace_back(path, info);
      }
  for (std::size_t i = 0; i < runs; ++i) {
    const SweepRecord& r = *recs[i];
    if (r.failed()) {
      ++ev.failed_runs;
      if (ev.message.empty())
        ev.message = (sources.size() > 1 ? sources[i / s.seeds.size()].file() + " " : "") +
                     "seed " + std::to_string(s.seeds[i % s.seeds.size()]) + ": " + r.status +
                     ": " + r.message;
      continue;
    }
    double sum = 0;
    for (std::size_t t = 0; t < s.objective.size(); ++t) {
      const double m = MetricIn(r, s.objective[t].path, "--metric");
      ev.term_means[t] += m;
      sum += s.objective[t].weight * m;
    }
    sums.push_back(sum);
    for (std::size_t k = 0; k < s.constraints.size(); ++k) {
      const double m = MetricIn(r, s.constraints[k].path, "--constraint");
      constrained[k].push_back(s.constraints[k].at_most ? m : -m);
    }
  }
  const double nan = std::nan("");
  for (double& m : ev.term_means) m = ev.failed() ? nan : m / static_cast<double>(sums.size());
  ev.constraint_means.assign(s.constraints.size(), nan);
  ev.violation = 0;
  if (ev.failed()) {
    ev.objective = kInf;
    return true;
  }
  ev.objective = s.over.Of(sums);
  for (std::size_t k = 0; k < s.constraints.size(); ++k) {
    const double folded = s.over.Of(constrained[k]);
    ev.constraint_means[k] = s.constraints[k].at_most ? folded : -folded;
    ev.violation = std::max(ev.violation, s.constraints[k].Violation(ev.constraint_means[k]));
  }
  if (!std::isfinite(ev.objective)) {
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

// Whether `a` is a better result than `b`: feasible before infeasible, then the lower objective
// among feasible ones, the smaller violation among infeasible ones (the first of equals wins).
bool IsBetter(const TuneEvaluation& a, const TuneEvaluation& b) {
  if (a.feasible() != b.feasible()) return a.feasible();
  if (a.feasible()) return a.objective < b.objective;
  if (a.failed() != b.failed()) return !a.failed();
  return a.violation < b.violation;
}

void StopAll(Context& c) {
  for (nlopt_opt o : c.opts) nlopt_force_stop(o);
}

// Evaluates `values` (or finds them evaluated already). Returns the evaluation, or null when the
// optimisation must end: stopped, out of this stage's budget, or an error (kept in c.error).
const TuneEvaluation* Point(Context& c, const std::vector<double>& values) {
  TuneResult& res = *c.result;
  // A point met again (NLopt's start, a Nelder-Mead revisit, the polish's start) is not run
  // again.
  for (const TuneEvaluation& e : res.history)
    if (e.values == values) return &e;
  if (static_cast<int>(res.history.size()) >= c.limit) {
    c.out_of_budget = true;
    return nullptr;
  }
  TuneEvaluation ev;
  ev.index = res.history.size() + 1;
  ev.stage = c.stage;
  ev.values = values;
  if (res.history.size() < c.recorded->size()) {
    // --resume: the optimiser asks again for what it asked before; history.csv has the answer.
    const TuneEvaluation& rec = (*c.recorded)[res.history.size()];
    if (rec.values != values) {
      c.error = std::make_exception_ptr(std::runtime_error(
          "--resume: evaluation " + std::to_string(ev.index) +
          " asks for other values than history.csv holds; this tune cannot be resumed exactly "
          "(run it again without --resume)"));
      return nullptr;
    }
    ev = rec;
    ev.index = res.history.size() + 1;
    ev.stage = c.stage;
  } else {
    try {
      if (!Evaluate(c, ev)) {
        c.stopped = true;
        return nullptr;
      }
    } catch (...) {
      c.error = std::current_exception();
      return nullptr;
    }
  }
  res.history.push_back(ev);
  if (res.history.size() == 1 || IsBetter(ev, res.history[res.best]))
    res.best = res.history.size() - 1;
  if (*c.progress) (*c.progress)(res.history.back(), res.history[res.best]);
  if (std::isfinite(ev.objective)) c.worst = std::max(c.worst, ev.objective);
  return &res.history.back();
}

std::vector<double> Values(const Context& c, unsigned n, const double* u) {
  std::vector<double> values = c.base;
  for (unsigned j = 0; j < n; ++j) values[c.dims[j]] = c.settings->params[c.dims[j]].FromUnit(u[j]);
  return values;
}

double Objective(unsigned n, const double* u, double* /*grad*/, void* data) {
  Context& c = *static_cast<Context*>(data);
  const TuneEvaluation* ev = Point(c, Values(c, n, u));
  if (ev == nullptr) {
    StopAll(c);
    return 0;
  }
  return Seen(c, *ev);
}

// One inequality constraint for NLopt, g(u) <= 0: the violation relative to the bound's size.
struct ConstraintData {
  Context* context;
  std::size_t k;
};

double Constraint(unsigned n, const double* u, double* /*grad*/, void* data) {
  const ConstraintData& d = *static_cast<const ConstraintData*>(data);
  Context& c = *d.context;
  const TuneEvaluation* ev = Point(c, Values(c, n, u));
  if (ev == nullptr) {
    StopAll(c);
    return 0;
  }
  if (ev->failed()) return 1e10;  // a failed run satisfies nothing
  return c.settings->constraints[d.k].Violation(ev->constraint_means[d.k]);
}

// Runs one stage of the plan from `u` (scaled), with initial steps `step` of each interval.
nlopt_result RunStage(Context& c, const TuneStage& stage, std::vector<double>& u, double step,
                      std::vector<ConstraintData>& constraint_data) {
  const TuneSettings& s = *c.settings;
  const unsigned n = static_cast<unsigned>(c.dims.size());
  const bool constrained = !s.constraints.empty();
  const bool auglag = constrained && !TakesConstraints(stage.method);
  // NLopt's random stream, for the methods that draw from it, restarts at the search seed.
  nlopt_srand(s.search_seed);
  std::vector<double> lb(n, 0.0), ub(n, 1.0), steps(n, step);
  auto make = [&](nlopt_algorithm alg) {
    nlopt_opt o = nlopt_create(alg, n);
    if (o == nullptr) throw std::runtime_error("NLopt could not create the optimiser");
    c.opts.push_back(o);
    nlopt_set_lower_bounds(o, lb.data());
    nlopt_set_upper_bounds(o, ub.data());
    nlopt_set_xtol_abs1(o, 1e-5);  // 1e-5 of each search interval
    return o;
  };
  nlopt_opt outer = make(auglag ? NLOPT_AUGLAG : Algorithm(stage.method));
  nlopt_opt inner = outer;
  if (auglag) {
    inner = make(Algorithm(stage.method));
    nlopt_set_local_optimizer(outer, inner);
  }
  if (stage.method == "mlsl") {
    nlopt_opt local = make(NLOPT_LN_BOBYQA);
    nlopt_set_xtol_rel(local, 1e-4);
    nlopt_set_local_optimizer(inner, local);
  }
  // The budget counts new points: Point stops the stage at its limit.
  for (nlopt_opt o : c.opts) nlopt_set_maxeval(o, 4 * s.budget + 10);
  nlopt_set_initial_step(outer, steps.data());
  if (inner != outer) nlopt_set_initial_step(inner, steps.data());
  nlopt_set_min_objective(outer, Objective, &c);
  for (std::size_t k = 0; k < s.constraints.size(); ++k) constraint_data.push_back({&c, k});
  for (ConstraintData& d : constraint_data) nlopt_add_inequality_constraint(outer, Constraint, &d, 1e-9);
  double fmin = 0;
  const nlopt_result r = nlopt_optimize(outer, u.data(), &fmin);
  for (nlopt_opt o : c.opts) nlopt_destroy(o);
  c.opts.clear();
  constraint_data.clear();
  return r;
}

}  // namespace

std::string TuneConstraint::Text() const {
  return path + (at_most ? "<=" : ">=") + FormatDouble(bound);
}

double TuneConstraint::Violation(double mean) const {
  if (std::isnan(mean)) return kInf;
  // Relative to the bound's size, so constraints of different units weigh alike (absolute
  // for a bound of 0).
  const double scale = bound != 0 ? std::abs(bound) : 1.0;
  return std::max(0.0, (at_most ? mean - bound : bound - mean) / scale);
}

TuneConstraint ParseTuneConstraint(const std::string& arg) {
  auto fail = [&](const std::string& why) {
    return std::runtime_error("--constraint '" + arg + "': " + why +
                              " (expected METRIC<=VALUE or METRIC>=VALUE)");
  };
  std::size_t op = arg.find("<=");
  TuneConstraint c;
  if (op == std::string::npos) {
    op = arg.find(">=");
    c.at_most = false;
  }
  if (op == std::string::npos) throw fail("no <= or >=");
  c.path = Trim(arg.substr(0, op));
  if (c.path.empty()) throw fail("a metric name is missing");
  for (char ch : c.path)
    if (!IsPathChar(ch)) throw fail(std::string("'") + ch + "' in the metric name");
  if (!ParseFiniteDouble(Trim(arg.substr(op + 2)), &c.bound))
    throw fail("the bound is not a finite number");
  return c;
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

double TuneParam::FromUnit(double u) const {
  u = std::clamp(u, 0.0, 1.0);
  if (kind == Kind::kChoice)
    return std::min(hi, std::floor(u * static_cast<double>(choices.size())));
  if (u == 0.0) return lo;
  if (u == 1.0) return hi;
  const double v = log_scale ? std::exp(std::log(lo) + u * (std::log(hi) - std::log(lo)))
                             : lo + u * (hi - lo);
  return std::clamp(kind == Kind::kInteger ? std::round(v) : v, lo, hi);
}

double TuneParam::ToUnit(double v) const {
  if (kind == Kind::kChoice) return (v + 0.5) / static_cast<double>(choices.size());
  return log_scale ? (std::log(v) - std::log(lo)) / (std::log(hi) - std::log(lo))
                   : (v - lo) / (hi - lo);
}

std::string TuneParam::Text(double v) const {
  if (kind == Kind::kChoice) {
    const std::size_t i = static_cast<std::size_t>(std::clamp(v, 0.0, hi));
    return choices[i];
  }
  return FormatDouble(v);
}

TuneParam ParseTuneParam(const std::string& arg, const ParamTable& params) {
  const std::string where = "--param " + arg;
  const std::size_t colon = arg.find(':');
  TuneParam p;
  p.key = Trim(arg.substr(0, colon));
  const Param* q = params.Find(p.key);
  if (q == nullptr) throw ScenarioError(where, p.key, "not a tunable of this scenario");
  if (q->kind == Param::Kind::kChoice || q->kind == Param::Kind::kBool) {
    if (colon != std::string::npos)
      throw ScenarioError(where, p.key,
                          "a choice is searched over all its values: give the key alone");
    p.kind = TuneParam::Kind::kChoice;
    p.choices = q->kind == Param::Kind::kBool ? std::vector<std::string>{"false", "true"}
                                              : q->choices;
    if (p.choices.size() < 2)
      throw ScenarioError(where, p.key, "has a single choice: there is nothing to search");
    p.lo = 0;
    p.hi = static_cast<double>(p.choices.size() - 1);
    p.start = std::clamp(q->value, p.lo, p.hi);
    return p;
  }
  if (q->kind == Param::Kind::kInt) p.kind = TuneParam::Kind::kInteger;
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
  if (p.kind == TuneParam::Kind::kInteger) {
    if (colon != std::string::npos && (p.lo != std::round(p.lo) || p.hi != std::round(p.hi)))
      throw ScenarioError(where, p.key, "an integer key needs whole-number bounds");
    p.lo = std::ceil(p.lo);
    p.hi = std::floor(p.hi);
  }
  if (!(p.lo < p.hi))
    throw ScenarioError(
        where, p.key,
        "needs LO < HI, got [" + FormatDouble(p.lo) + ", " + FormatDouble(p.hi) + "]");
  p.log_scale = q->tune.log_scale && p.lo > 0 && p.kind == TuneParam::Kind::kReal;
  p.start = std::clamp(q->value, p.lo, p.hi);
  return p;
}

std::string TuneOver::Text() const {
  switch (kind) {
    case Kind::kMean:
      return "mean";
    case Kind::kMax:
      return "max";
    case Kind::kQuantile:
      break;
  }
  return "quantile:" + FormatDouble(q);
}

double TuneOver::Of(std::vector<double> values) const {
  if (kind == Kind::kMax) return *std::max_element(values.begin(), values.end());
  if (kind == Kind::kQuantile) {
    std::sort(values.begin(), values.end());
    return Quantile(values, q);
  }
  double sum = 0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

TuneOver ParseTuneOver(const std::string& text) {
  TuneOver o;
  if (text == "mean") return o;
  if (text == "max") {
    o.kind = TuneOver::Kind::kMax;
    return o;
  }
  if (text.rfind("quantile:", 0) == 0 && ParseFiniteDouble(text.substr(9), &o.q) && o.q > 0 &&
      o.q < 1) {
    o.kind = TuneOver::Kind::kQuantile;
    return o;
  }
  throw std::runtime_error("--over '" + text +
                           "': expected mean, max (the worst case) or quantile:Q with 0 < Q < 1");
}

void CheckTunedKeys(const std::vector<ScenarioSource>& sources, const TuneSettings& s) {
  if (sources.size() < 2) return;
  const ParsedScenario first = ParseScenario(sources[0], s.sets);
  std::vector<const Param*> keys;
  for (const TuneParam& p : s.params)
    if (const Param* q = first.params.Find(p.key)) keys.push_back(q);
  CheckScenarioKeys(sources, s.sets, keys, "tuned");
}

std::vector<Override> TuneOverrides(const TuneSettings& s, const std::vector<double>& values) {
  std::vector<Override> out;
  for (const Override& o : s.sets) {
    bool tuned = false;
    for (const TuneParam& p : s.params) tuned = tuned || p.key == o.key;
    if (!tuned) out.push_back(o);
  }
  for (std::size_t i = 0; i < s.params.size(); ++i)
    out.push_back({s.params[i].key, s.params[i].Text(values[i]), "formsim tune", -1});
  return out;
}

TuneResult RunTune(
    const ScenarioSource& source, const TuneSettings& s, TaskPool& pool,
    const std::function<void(const TuneEvaluation&, const TuneEvaluation&)>& progress,
    const std::function<bool()>& stop) {
  return RunTune(std::vector<ScenarioSource>{source}, s, pool, progress, stop);
}

TuneResult RunTune(
    const std::vector<ScenarioSource>& sources, const TuneSettings& s, TaskPool& pool,
    const std::function<void(const TuneEvaluation&, const TuneEvaluation&)>& progress,
    const std::function<bool()>& stop, const std::vector<TuneEvaluation>& recorded) {
  if (sources.empty()) throw std::runtime_error("formsim tune: give a scenario");
  if (s.params.empty()) throw std::runtime_error("formsim tune: give at least one --param");
  if (s.objective.empty()) throw std::runtime_error("formsim tune: give --metric");
  if (s.seeds.empty()) throw std::runtime_error("formsim tune: give --seeds");
  if (s.budget < 1) throw std::runtime_error("--budget must be at least 1");
  const unsigned n = static_cast<unsigned>(s.params.size());
  int reals = 0;
  for (const TuneParam& p : s.params) reals += p.discrete() ? 0 : 1;
  TuneResult result;
  result.plan = PlanTune(s.algorithm, static_cast<int>(n), s.budget, reals);
  Context c{&sources, &s, &pool, &progress, &stop, &result, {}, nullptr};
  c.recorded = &recorded;
  std::vector<double> start;
  for (const TuneParam& p : s.params) start.push_back(p.start);
  // Evaluation 1 is the scenario's own values, exactly (BOBYQA may move its first point away
  // from a bound); a metric it does not have is refused here, before the search.
  c.limit = result.plan.front().evaluations;
  nlopt_result r = NLOPT_MAXEVAL_REACHED;
  std::vector<ConstraintData> constraint_data;
  constraint_data.reserve(s.constraints.size());
  if (Point(c, start) != nullptr) {
    int used = 0;
    for (std::size_t k = 0; k < result.plan.size() && !c.stopped && !c.error; ++k) {
      used += result.plan[k].evaluations;
      c.stage = k;
      c.limit = used;
      c.out_of_budget = false;
      // A global stage searches every key; a local one the real keys, from the best point so
      // far (the start for a plan of one local method), with finer first steps after a global
      // stage.
      const bool global = IsGlobalMethod(result.plan[k].method);
      c.base = k == 0 ? start : result.history[result.best].values;
      c.dims.clear();
      for (std::size_t i = 0; i < n; ++i)
        if (global || !s.params[i].discrete()) c.dims.push_back(i);
      std::vector<double> u;
      for (std::size_t i : c.dims)
        u.push_back(std::clamp(s.params[i].ToUnit(c.base[i]), 0.0, 1.0));
      try {
        r = RunStage(c, result.plan[k], u, k == 0 ? 0.15 : 0.05, constraint_data);
      } catch (...) {
        for (nlopt_opt o : c.opts) nlopt_destroy(o);
        throw;
      }
    }
  }
  if (c.error) std::rethrow_exception(c.error);
  if (result.history.size() < recorded.size())
    throw std::runtime_error("--resume: history.csv holds " + std::to_string(recorded.size()) +
                             " evaluations, more than this tune makes (" +
                             std::to_string(result.history.size()) + ")");
  result.stop_reason = c.stopped                                   ? "interrupted"
                       : c.out_of_budget || r == NLOPT_FORCED_STOP ? "budget used"
                                                                   : StopText(r);
  return result;
}

}  // namespace formsim::sim
