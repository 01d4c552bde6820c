#include "sim/study/sweep_spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>
#include <unordered_set>

#include "sim/core/number_format.hpp"
#include "sim/core/rng.hpp"
#include "sim/core/sha256.hpp"
#include "sim/study/scenario_set.hpp"

namespace formsim::sim {
namespace {

// A computed design value rounded to 12 significant digits, so ranges read as 0.15, not
// 0.15000000000000002 (a change far below anything a sweep resolves).
double Tidy(double v) {
  return std::strtod(FormatSignificant(v, 12).c_str(), nullptr);
}

// a * b, or SIZE_MAX when that overflows.
std::size_t SaturatingProduct(std::size_t a, std::size_t b) {
  if (a != 0 && b > std::numeric_limits<std::size_t>::max() / a)
    return std::numeric_limits<std::size_t>::max();
  return a * b;
}

struct AxisBuilder {
  const std::string where;  // "--vary KEY=SPEC"
  const Param& param;
  SweepAxis axis;
  std::unordered_set<std::string> seen = {};  // axis.values, for the duplicate check

  [[noreturn]] void Fail(const std::string& why) const {
    throw ScenarioError(where, param.key, why);
  }

  double Number(const std::string& text, const char* what) const {
    double v = 0;
    if (!ParseFiniteDouble(text, &v))
      Fail(std::string("expected a number for ") + what + ", got '" + text + "'");
    return v;
  }
  std::size_t Count(const std::string& text, const char* what) const {
    long long n = 0;
    if (!ParseInteger(text, 1, 1000000, &n))
      Fail(std::string(what) + " must be an integer in 1 ... 1000000, got '" + text + "'");
    return static_cast<std::size_t>(n);
  }
  bool numeric() const { return !axis.categorical(); }

  // Adds a value given as text, checked against the tunable's kind and validity.
  void Add(const std::string& text) {
    std::string canonical;
    const std::string why = param.Parse(text, &canonical);
    if (!why.empty()) Fail("value '" + text + "': " + why);
    if (!seen.insert(canonical).second) {
      if (axis.random) {
        axis.values.push_back(canonical);  // samples may coincide (integers, choices)
        return;
      }
      Fail("value " + canonical + " appears twice" +
           (param.kind == Param::Kind::kInt ? " (a range of integers rounds to the same value)"
                                            : ""));
    }
    axis.values.push_back(canonical);
  }
  void AddNumber(double v) {
    if (param.kind == Param::Kind::kInt) {
      Add(std::to_string(std::llround(v)));
    } else {
      Add(FormatDouble(Tidy(v)));
    }
  }

  void Range(const std::vector<std::string>& parts, bool log) {
    if (!numeric()) Fail("a range needs a numeric tunable; list the values or write 'all'");
    const std::size_t o = log ? 1 : 0;
    if (parts.size() != 3 + o) Fail(log ? "expected log:LO:HI:N" : "expected LO:HI:N");
    const double lo = Number(parts[o], "LO"), hi = Number(parts[o + 1], "HI");
    const std::size_t n = Count(parts[o + 2], "N");
    if (n < 2) Fail("a range needs N >= 2 (write a single value for one)");
    if (log && !(lo > 0 && hi > 0)) Fail("a log range needs LO > 0 and HI > 0");
    if (!(lo != hi)) Fail("LO and HI must differ");
    axis.log_scale = log;
    for (std::size_t i = 0; i < n; ++i) {
      const double f = static_cast<double>(i) / static_cast<double>(n - 1);
      double v =
          log ? std::exp(std::log(lo) + f * (std::log(hi) - std::log(lo))) : lo + f * (hi - lo);
      if (i == 0) v = lo;
      if (i + 1 == n) v = hi;
      AddNumber(v);
    }
  }

  // random:N or random:N:LO:HI: the sample count now, the values once the hypercube is drawn.
  std::size_t Random(const std::vector<std::string>& parts, double* lo, double* hi) {
    if (parts.size() != 2 && parts.size() != 4) Fail("expected random:N or random:N:LO:HI");
    const std::size_t n = Count(parts[1], "N");
    axis.random = true;
    if (!numeric()) {
      if (parts.size() == 4)
        Fail("LO:HI makes no sense for an enum or a flag; random:N draws among its choices");
      return n;
    }
    *lo = parts.size() == 4 ? Number(parts[2], "LO") : param.slider_min();
    *hi = parts.size() == 4 ? Number(parts[3], "HI") : param.slider_max();
    if (!(*lo < *hi))
      Fail("random samples need LO < HI, got [" + FormatDouble(*lo) + ", " + FormatDouble(*hi) +
           "]");
    for (double v : {*lo, *hi}) {
      const std::string why = param.tune.Check(v);
      if (!why.empty())
        Fail("the sampling range [" + FormatDouble(*lo) + ", " + FormatDouble(*hi) +
             "] leaves the valid values: " + why);
    }
    axis.log_scale = param.tune.log_scale && *lo > 0;
    return n;
  }

  // Maps u in [0, 1) to a value of the axis.
  void AddSample(double u, double lo, double hi) {
    if (!numeric()) {
      const std::size_t k = param.kind == Param::Kind::kBool ? 2 : param.choices.size();
      const std::size_t i = std::min(k - 1, static_cast<std::size_t>(u * static_cast<double>(k)));
      Add(param.kind == Param::Kind::kBool ? (i ? "true" : "false") : param.choices[i]);
      return;
    }
    double v = axis.log_scale ? std::exp(std::log(lo) + u * (std::log(hi) - std::log(lo)))
                              : lo + u * (hi - lo);
    if (param.kind == Param::Kind::kInt) {
      // Equal strata of the integers lo..hi.
      v = std::floor(std::ceil(lo) + u * (std::floor(hi) - std::ceil(lo) + 1));
      v = std::min(v, std::floor(hi));
    }
    AddNumber(std::clamp(Tidy(v), lo, hi));
  }
};

// Every scenario after the first has every varied key, of the same kind, and takes every value.
void CheckOtherScenarios(const std::vector<ScenarioSource>& sources,
                         const std::vector<Override>& sets, const ParamTable& first,
                         const std::vector<SweepAxis>& axes) {
  if (sources.size() < 2) return;
  std::vector<const Param*> keys;
  for (const SweepAxis& a : axes) keys.push_back(first.Find(a.key));
  CheckScenarioKeys(sources, sets, keys, "--vary");
  for (std::size_t i = 1; i < sources.size(); ++i) {
    const ParsedScenario parsed = ParseScenario(sources[i], sets);
    for (const SweepAxis& a : axes) {
      const Param& p = *parsed.params.Find(a.key);
      for (const std::string& v : a.values) {
        std::string canonical;
        const std::string why = p.Parse(v, &canonical);
        if (!why.empty())
          throw ScenarioError("--scenario " + sources[i].file(), a.key,
                              "value '" + v + "' of --vary " + a.key + "=" + a.spec + ": " + why);
      }
    }
  }
}

}  // namespace

double SweepAxis::Numeric(std::size_t i) const {
  const std::string& v = values[i];
  if (kind == Param::Kind::kBool) return v == "true" ? 1.0 : 0.0;
  if (kind == Param::Kind::kChoice) {
    for (std::size_t c = 0; c < choices.size(); ++c)
      if (choices[c] == v) return static_cast<double>(c);
    return std::nan("");
  }
  double x = std::nan("");
  ParseFiniteDouble(v, &x);
  return x;
}

std::vector<Override> SweepDefinition::RunOverrides(std::size_t run) const {
  std::vector<Override> out = sets;
  const std::size_t p = PointOf(run);
  for (std::size_t a = 0; a < axes.size(); ++a)
    out.push_back({axes[a].key, Value(p, a), "--vary", -1});
  out.push_back({"seed", std::to_string(SeedOf(run)), "--seeds", -1});
  return out;
}

bool SweepDefinition::IsGrid() const {
  for (const SweepAxis& a : axes)
    if (a.random) return false;
  return true;
}

std::string SweepScenario::Name() const {
  return std::filesystem::path(file).stem().string();
}

void SweepDefinition::Finish() {
  // Factors in the order of the axes: each list or range is one, all random axes together are
  // one (placed where the first of them is). The first factor varies slowest.
  struct Factor {
    std::vector<std::size_t> axes;
    std::size_t size = 0;
  };
  std::vector<Factor> factors;
  int random_factor = -1;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    if (axes[a].random) {
      if (random_factor < 0) {
        random_factor = static_cast<int>(factors.size());
        factors.push_back({{}, axes[a].values.size()});
      }
      factors[random_factor].axes.push_back(a);
    } else {
      factors.push_back({{a}, axes[a].values.size()});
    }
  }
  std::size_t total = 1;
  for (const Factor& f : factors) {
    if (f.size == 0) throw std::runtime_error("a sweep axis without values");
    total = SaturatingProduct(total, f.size);
    if (SaturatingProduct(SaturatingProduct(total, std::max<std::size_t>(1, seeds.size())),
                          std::max<std::size_t>(1, scenarios.size())) > kMaxSweepRuns)
      throw std::runtime_error("the sweep would have more than " + std::to_string(kMaxSweepRuns) +
                               " runs; vary fewer values");
  }
  points.assign(total, std::vector<std::size_t>(axes.size(), 0));
  for (std::size_t p = 0; p < total; ++p) {
    std::size_t rest = p;
    for (std::size_t f = factors.size(); f-- > 0;) {
      const std::size_t i = rest % factors[f].size;
      rest /= factors[f].size;
      for (std::size_t a : factors[f].axes) points[p][a] = i;
    }
  }
  // The identity: the scenarios' texts (by hash), the overrides, the values and the seeds.
  std::string what = "formsim sweep\n";
  for (const SweepScenario& s : scenarios) what += "scenario " + s.sha256 + "\n";
  for (const Override& o : sets) what += "set " + o.key + "=" + o.value + "\n";
  for (const SweepAxis& a : axes) {
    what += "axis " + a.key + (a.random ? " random" : "") + "\n";
    for (const std::string& v : a.values) what += "  " + v + "\n";
  }
  what += "seeds";
  for (std::uint64_t s : seeds) what += " " + std::to_string(s);
  what += "\nsample_seed " + std::to_string(sample_seed) + "\n";
  id = Sha256Hex(what);
}

std::vector<std::string> SplitAt(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = text.find(sep, start);
    out.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

std::vector<std::uint64_t> ParseSeeds(const std::string& text, const std::string& flag) {
  auto fail = [&](const std::string& why) -> std::runtime_error {
    return std::runtime_error(flag + " '" + text + "': " + why);
  };
  if (text.find_first_not_of(" \t") == std::string::npos)
    throw fail("no seeds (write 1..20 or 1,2,5, or leave " + flag +
               " out for the scenario's seed)");
  std::vector<std::uint64_t> out;
  std::set<std::uint64_t> seen;
  auto add = [&](std::uint64_t s) {
    if (!seen.insert(s).second) throw fail("seed " + std::to_string(s) + " appears twice");
    if (out.size() >= 1000000) throw fail("more than 1000000 seeds");
    out.push_back(s);
  };
  for (const std::string& part : SplitAt(text, ',')) {
    const std::size_t dots = part.find("..");
    std::uint64_t a = 0, b = 0;
    if (dots == std::string::npos) {
      if (!ParseUint64(part, &a))
        throw fail("expected seeds like 1..20 or 1,2,5, got '" + part + "'");
      add(a);
      continue;
    }
    if (!ParseUint64(part.substr(0, dots), &a) || !ParseUint64(part.substr(dots + 2), &b))
      throw fail("expected a range FIRST..LAST of non-negative integers, got '" + part + "'");
    if (b < a) throw fail("the range " + part + " is empty (LAST < FIRST)");
    if (b - a >= 1000000) throw fail("more than 1000000 seeds");
    for (std::uint64_t s = a;; ++s) {
      add(s);
      if (s == b) break;
    }
  }
  return out;
}

std::vector<std::vector<double>> LatinHypercube(std::size_t n, std::size_t dims,
                                                std::uint64_t seed) {
  Rng rng(seed);
  std::vector<std::vector<double>> pts(n, std::vector<double>(dims, 0.0));
  std::vector<std::size_t> perm(n);
  for (std::size_t d = 0; d < dims; ++d) {
    for (std::size_t i = 0; i < n; ++i) perm[i] = i;
    // Fisher-Yates with our portable generator (std::shuffle is implementation-defined).
    for (std::size_t i = n; i > 1; --i) {
      const std::size_t j =
          std::min(i - 1, static_cast<std::size_t>(rng.Uniform() * static_cast<double>(i)));
      std::swap(perm[i - 1], perm[j]);
    }
    for (std::size_t i = 0; i < n; ++i)
      pts[i][d] = (static_cast<double>(perm[i]) + rng.Uniform()) / static_cast<double>(n);
  }
  return pts;
}

std::size_t CountSweepRuns(const ParamTable& params, const std::vector<std::string>& vary,
                           std::size_t seed_count) {
  auto count = [](const std::string& text) -> std::size_t {
    long long n = 0;
    return ParseInteger(text, 1, 1000000, &n) ? static_cast<std::size_t>(n) : 1;
  };
  std::size_t runs = std::max<std::size_t>(1, seed_count), random_n = 0;
  for (const std::string& arg : vary) {
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = arg.substr(0, eq), spec = arg.substr(eq + 1);
    const std::vector<std::string> parts = SplitAt(spec, ':');
    std::size_t n = 1;
    if (parts[0] == "random") {
      // Every random axis is one factor of N samples (DefineSweep insists on one N).
      if (parts.size() > 1) random_n = std::max(random_n, count(parts[1]));
      continue;
    } else if (parts[0] == "log") {
      if (parts.size() == 4) n = count(parts[3]);
    } else if (parts.size() > 1) {
      if (parts.size() == 3) n = count(parts[2]);
    } else if (spec == "all") {
      const Param* p = params.Find(key);
      if (p != nullptr && p->kind == Param::Kind::kBool)
        n = 2;
      else if (p != nullptr && p->kind == Param::Kind::kChoice)
        n = std::max<std::size_t>(1, p->choices.size());
    } else {
      n = static_cast<std::size_t>(std::count(spec.begin(), spec.end(), ',')) + 1;
    }
    runs = SaturatingProduct(runs, n);
  }
  return SaturatingProduct(runs, std::max<std::size_t>(1, random_n));
}

SweepDefinition DefineSweep(const ScenarioSource& source, const std::vector<Override>& sets,
                            const std::vector<std::string>& vary, std::vector<std::uint64_t> seeds,
                            std::uint64_t sample_seed, std::size_t max_runs) {
  return DefineSweep(std::vector<ScenarioSource>{source}, sets, vary, std::move(seeds), sample_seed,
                     max_runs);
}

SweepDefinition DefineSweep(const std::vector<ScenarioSource>& sources,
                            const std::vector<Override>& sets, const std::vector<std::string>& vary,
                            std::vector<std::uint64_t> seeds, std::uint64_t sample_seed,
                            std::size_t max_runs) {
  if (sources.empty()) throw std::runtime_error("a sweep needs a scenario");
  const ScenarioSource& source = sources.front();
  const ParsedScenario base = ParseScenario(source, sets);
  // The size first, from the specs alone: a sweep of 10^18 runs is refused before a value of it
  // is built (building a million values of one axis already takes a while).
  max_runs = std::min(max_runs, kMaxSweepRuns);
  const std::size_t runs =
      SaturatingProduct(CountSweepRuns(base.params, vary, seeds.size()), sources.size());
  if (runs > max_runs)
    throw std::runtime_error(
        "the sweep has " +
        (runs == std::numeric_limits<std::size_t>::max() ? "more than " + std::to_string(runs)
                                                         : std::to_string(runs)) +
        (sources.size() > 1 ? " runs (scenarios x points x seeds), more than "
                            : " runs (points x seeds), more than ") +
        std::to_string(max_runs) +
        (max_runs < kMaxSweepRuns ? "; vary fewer values, or allow it with --max-runs N (N <= " +
                                        std::to_string(kMaxSweepRuns) + ")"
                                  : ", the most formsim plans; vary fewer values"));
  SweepDefinition def;
  for (const ScenarioSource& s : sources) def.scenarios.push_back({s.file(), s.sha256()});
  def.sets = sets;
  def.sample_seed = sample_seed;
  def.seeds = seeds.empty() ? std::vector<std::uint64_t>{base.setup.seed} : std::move(seeds);

  struct RandomAxis {
    std::size_t axis;
    AxisBuilder builder;
    double lo, hi;
  };
  std::vector<RandomAxis> randoms;
  std::size_t random_n = 0;
  std::string random_first;
  for (const std::string& arg : vary) {
    const std::string where = "--vary " + arg;
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos || eq == 0)
      throw ScenarioError(where, "", "expected KEY=SPEC, e.g. robots.R2.follow.k_l=0.05:0.5:10");
    const std::string key = arg.substr(0, eq), spec = arg.substr(eq + 1);
    if (key == "seed")
      throw ScenarioError(where, key, "the seed is varied with --seeds, not --vary");
    const Param* p = base.params.Find(key);
    if (p == nullptr) {
      // Say which tunables look alike (same last part or same prefix).
      std::string near, some;
      const std::size_t dot = key.rfind('.');
      const std::string last = key.substr(dot == std::string::npos ? 0 : dot + 1);
      const std::string parent = dot == std::string::npos ? "" : key.substr(0, dot + 1);
      int shown = 0, listed = 0;
      for (const Param& q : base.params.all()) {
        const std::string qlast =
            q.key.substr(q.key.rfind('.') == std::string::npos ? 0 : q.key.rfind('.') + 1);
        if ((qlast == last || (!parent.empty() && q.key.rfind(parent, 0) == 0)) && shown++ < 8)
          near += (near.empty() ? "" : ", ") + q.key;
        if (listed++ < 8) some += (some.empty() ? "" : ", ") + q.key;
      }
      throw ScenarioError(
          where, key,
          "not a tunable of " + source.file() +
              (near.empty() ? " (tunables: " + some + (listed > 8 ? ", ..." : "") + ")"
                            : " (similar: " + near + ")"));
    }
    for (const SweepAxis& a : def.axes)
      if (a.key == key) throw ScenarioError(where, key, "varied twice");
    if (spec.empty()) throw ScenarioError(where, key, "empty SPEC");
    AxisBuilder b{where, *p, {}};
    b.axis.key = key;
    b.axis.spec = spec;
    b.axis.kind = p->kind;
    b.axis.choices =
        p->kind == Param::Kind::kBool ? std::vector<std::string>{"false", "true"} : p->choices;
    const std::vector<std::string> parts = SplitAt(spec, ':');
    if (parts[0] == "random") {
      double lo = 0, hi = 0;
      const std::size_t n = b.Random(parts, &lo, &hi);
      if (random_n != 0 && n != random_n)
        throw ScenarioError(
            where, key,
            "every random axis is part of one Latin hypercube and needs the same N (" +
                random_first + " has " + std::to_string(random_n) + ")");
      random_n = n;
      if (random_first.empty()) random_first = key;
      def.axes.push_back(b.axis);
      randoms.push_back({def.axes.size() - 1, b, lo, hi});
      continue;
    }
    if (parts[0] == "log") {
      b.Range(parts, true);
    } else if (parts.size() > 1) {
      b.Range(parts, false);
    } else if (spec == "all" && b.axis.categorical()) {
      for (const std::string& c : b.axis.choices) b.Add(c);
    } else {
      for (const std::string& v : SplitAt(spec, ',')) {
        if (v.empty()) b.Fail("empty value in the list '" + spec + "'");
        b.Add(v);
      }
    }
    def.axes.push_back(b.axis);
  }
  if (!randoms.empty()) {
    const auto lhs = LatinHypercube(random_n, randoms.size(), sample_seed);
    for (std::size_t d = 0; d < randoms.size(); ++d) {
      RandomAxis& r = randoms[d];
      for (std::size_t i = 0; i < random_n; ++i) r.builder.AddSample(lhs[i][d], r.lo, r.hi);
      def.axes[r.axis].values = r.builder.axis.values;
    }
  }
  CheckOtherScenarios(sources, sets, base.params, def.axes);
  def.Finish();
  return def;
}

}  // namespace formsim::sim
