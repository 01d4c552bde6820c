#include "sim/study/lesson_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "control/common/float_limits.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/recorder.hpp"
#include "sim/core/task_pool.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/study/sweep.hpp"

namespace formsim::sim {
namespace {

using Check = LessonCheck;
using control::kNaN;

std::string Num(double v) { return FormatSignificant(v, 4); }

// A run a check needs: the lesson's scenario with edits, a duration and a seed.
struct RunKey {
  std::vector<std::string> sets;
  double duration = 0.0;
  std::uint64_t seed = 1;
  bool operator<(const RunKey& o) const {
    return std::tie(sets, duration, seed) < std::tie(o.sets, o.duration, o.seed);
  }
};

// The raw quantity of one check on one seed: one value, or one per robot (every / any).
struct Slot {
  double raw = kNaN;
  std::string error;
  std::vector<double> per;  ///< over robots: the value of each robot (raw unused)
};

// The i-th value of a slot: its robot's, or the one value for every robot.
double At(const Slot& s, std::size_t i) { return s.per.empty() ? s.raw : s.per[i]; }

// `v` divided by (or minus) `d`, robot by robot; a slot of one value applies to every robot.
Slot Combine(Slot v, const Slot& d, bool minus) {
  if (v.per.empty() && d.per.empty()) {
    v.raw = minus ? v.raw - d.raw : v.raw / d.raw;
    return v;
  }
  const std::size_t n = std::max(v.per.size(), d.per.size());
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = minus ? At(v, i) - At(d, i) : At(v, i) / At(d, i);
  v.per = std::move(out);
  return v;
}

// How far a value is inside its relation (negative, or 0 for < and >: it fails).
double Margin(const Check& c, double v, double operand) {
  if (std::isnan(v) || std::isnan(operand)) return -std::numeric_limits<double>::infinity();
  switch (c.relation) {
    case Check::Relation::kLess:
      return operand - v;
    case Check::Relation::kGreater:
      return v - operand;
    case Check::Relation::kWithin:
      return std::min(v - c.lo, c.hi - v);
    case Check::Relation::kEqual:
      return c.tolerance - std::abs(v - operand);
    case Check::Relation::kAbout:
      return c.rel * std::abs(operand) - std::abs(v - operand);
  }
  return -std::numeric_limits<double>::infinity();
}

// The robot that decides a check over robots: for every, the one nearest to failing (or the
// first failing); for any, the one holding best. 0 for a check of one value.
std::size_t Decider(const Check& c, const Slot& v, const Slot& rhs) {
  if (c.over == Check::Over::kOne) return 0;
  std::size_t best = 0;
  for (std::size_t i = 1; i < c.robots.size(); ++i) {
    const double m = Margin(c, At(v, i), At(rhs, i)), b = Margin(c, At(v, best), At(rhs, best));
    if (c.over == Check::Over::kEvery ? m < b : m > b) best = i;
  }
  return best;
}

std::vector<Override> RunOverrides(const RunKey& k) {
  std::vector<Override> o = CliOverrides(k.sets, -1);
  for (Override& x : o) x.origin = "lesson check --set";
  if (k.duration > 0) o.push_back({"duration", FormatDouble(k.duration), "lesson check", -1});
  o.push_back({"seed", std::to_string(k.seed), "lesson check seed", -1});
  return o;
}

Slot MeasureOne(const Check& c, const Experiment& exp,
                const std::vector<std::pair<std::string, double>>& metrics);

// The check's quantity on a finished run; over robots, each robot's (an error names the robot's
// quantity that is missing).
Slot Measure(const Check& c, const Experiment& exp,
             const std::vector<std::pair<std::string, double>>& metrics) {
  if (c.over == Check::Over::kOne) return MeasureOne(c, exp, metrics);
  Slot s;
  for (const std::string& r : c.robots) {
    const Slot one = MeasureOne(c.ForRobot(r), exp, metrics);
    if (!one.error.empty() && s.error.empty()) s.error = one.error;
    s.per.push_back(one.raw);
  }
  return s;
}

Slot MeasureOne(const Check& c, const Experiment& exp,
                const std::vector<std::pair<std::string, double>>& metrics) {
  Slot s;
  switch (c.source) {
    case Check::Source::kMetric: {
      for (const auto& [name, v] : metrics)
        if (name == c.name) {
          s.raw = v;
          return s;
        }
      s.error = "the run has no metric '" + c.name + "'";
      return s;
    }
    case Check::Source::kEvents:
      s.raw = static_cast<double>(c.robot.empty() ? exp.events().Count(c.name)
                                                  : exp.events().CountForRobot(c.name, c.robot));
      return s;
    case Check::Source::kColumn: {
      const Recorder& rec = exp.recorder();
      const int col = rec.Column(c.name), tcol = rec.Column("t");
      if (col < 0) {
        s.error = "the run has no column '" + c.name + "'";
        return s;
      }
      if (rec.history_stride() > 1) {
        s.error = "the run is too long to keep every row; give the check a shorter duration";
        return s;
      }
      s.raw = ColumnStat(rec.Series(tcol), rec.Series(col), c);
      if (std::isnan(s.raw)) s.error = "no value of '" + c.name + "' in the window";
      return s;
    }
  }
  return s;
}

std::string RelationText(const Check& c) {
  const std::string rhs = c.against.empty() ? Num(c.value) : c.against;
  std::string q = c.ratio_to.empty() ? "" : (c.minus ? " (minus " : " (ratio to ") + c.ratio_to + ")";
  if (c.over != Check::Over::kOne) {
    std::string robots;
    for (const std::string& r : c.robots) robots += (robots.empty() ? "" : " ") + r;
    q += std::string(c.over == Check::Over::kEvery ? " for each of [" : " for one of [") + robots +
         (c.over == Check::Over::kEvery ? "]" : "] at least");
  }
  switch (c.relation) {
    case Check::Relation::kLess:
      return "< " + rhs + q;
    case Check::Relation::kGreater:
      return "> " + rhs + q;
    case Check::Relation::kWithin:
      return "within [" + Num(c.lo) + ", " + Num(c.hi) + "]" + q;
    case Check::Relation::kEqual:
      return "= " + rhs + (c.tolerance > 0 ? " ± " + Num(c.tolerance) : "") + q;
    case Check::Relation::kAbout:
      return "= " + rhs + " ± " + Num(100 * c.rel) + " %" + q;
  }
  return "?";
}

std::vector<std::uint64_t> OwnSeeds(const Check& c, const LessonCheckOptions& opt) {
  if (!opt.seeds.empty()) return opt.seeds;
  std::vector<std::uint64_t> s;
  const int n = c.all_seeds ? 5 : c.seeds;
  for (int i = 1; i <= n; ++i) s.push_back(static_cast<std::uint64_t>(i));
  return s;
}

}  // namespace

bool LessonCheckResult::ok() const {
  if (!error.empty() || holds.empty()) return false;
  if (SeedChangesNothing()) return false;
  const auto n = std::count(holds.begin(), holds.end(), true);
  // share < 1: at least that share of the seeds (27 of 30 for 0.9).
  return static_cast<double>(n) >= share * static_cast<double>(holds.size()) - 1e-9;
}

double ColumnStat(const std::vector<double>& t, const std::vector<double>& x, const Check& c) {
  std::vector<double> tt, xx;
  for (std::size_t i = 0; i < t.size() && i < x.size(); ++i) {
    if (t[i] < c.from - 1e-9 || t[i] > c.to + 1e-9) continue;
    if (IsNotSampled(x[i]) || std::isnan(x[i])) continue;
    tt.push_back(t[i]);
    xx.push_back(x[i]);
  }
  if (xx.empty()) return kNaN;
  const double n = static_cast<double>(xx.size());
  switch (c.stat) {
    case Check::Stat::kMaxAbs: {
      double m = 0;
      for (double v : xx) m = std::max(m, std::abs(v));
      return m;
    }
    case Check::Stat::kMax:
      return *std::max_element(xx.begin(), xx.end());
    case Check::Stat::kMin:
      return *std::min_element(xx.begin(), xx.end());
    case Check::Stat::kMean: {
      double s = 0;
      for (double v : xx) s += v;
      return s / n;
    }
    case Check::Stat::kRms: {
      double s = 0;
      for (double v : xx) s += v * v;
      return std::sqrt(s / n);
    }
    case Check::Stat::kJitter: {
      // RMS of the change from one recorded row to the next.
      if (xx.size() < 2) return kNaN;
      double s = 0;
      for (std::size_t i = 1; i < xx.size(); ++i) s += (xx[i] - xx[i - 1]) * (xx[i] - xx[i - 1]);
      return std::sqrt(s / (n - 1));
    }
    case Check::Stat::kFirstBelow:
      for (std::size_t i = 0; i < xx.size(); ++i)
        if (std::abs(xx[i]) < c.level) return tt[i];
      return std::numeric_limits<double>::infinity();
    case Check::Stat::kTau: {
      // Least-squares line through ln|x| over time: |x| ∝ e^(−t/τ), τ = −1 / slope.
      double st = 0, sy = 0, stt = 0, sty = 0, m = 0;
      for (std::size_t i = 0; i < xx.size(); ++i) {
        if (xx[i] == 0.0) continue;
        const double y = std::log(std::abs(xx[i]));
        st += tt[i], sy += y, stt += tt[i] * tt[i], sty += tt[i] * y, m += 1;
      }
      if (m < 3) return kNaN;
      const double den = m * stt - st * st;
      if (den <= 0) return kNaN;
      const double slope = (m * sty - st * sy) / den;
      return slope < 0 ? -1.0 / slope : std::numeric_limits<double>::infinity();
    }
    case Check::Stat::kFinal:
      return xx.back();
  }
  return kNaN;
}

bool RelationHolds(const Check& c, double v, double operand) {
  if (std::isnan(v)) return false;
  switch (c.relation) {
    case Check::Relation::kLess:
      return v < operand;
    case Check::Relation::kGreater:
      return v > operand;
    case Check::Relation::kWithin:
      return v >= c.lo && v <= c.hi;
    case Check::Relation::kEqual:
      return std::abs(v - operand) <= c.tolerance;
    case Check::Relation::kAbout:
      return std::abs(v - operand) <= c.rel * std::abs(operand);
  }
  return false;
}

std::vector<LessonCheckResult> CheckLesson(const std::string& file, const LessonCheckOptions& opt) {
  const ScenarioSource source = ScenarioSource::FromFile(file);
  const ParsedScenario parsed = ParseScenario(source, {});
  const LessonDef& lesson = parsed.lesson;
  const std::string stem = std::filesystem::path(file).stem().string();
  if (!lesson.present) throw std::runtime_error(file + ": not a lesson (no lesson: block)");
  const std::vector<Check>& checks = lesson.checks;
  auto index = [&](const std::string& id) {
    for (std::size_t i = 0; i < checks.size(); ++i)
      if (checks[i].id == id) return static_cast<int>(i);
    return -1;
  };

  // The checks asked for and those they compare with, each on its own seeds and on those of
  // every check that refers to it.
  std::vector<std::vector<std::uint64_t>> seeds(checks.size());
  std::vector<bool> wanted(checks.size(), opt.only.empty());
  for (const std::string& id : opt.only) {
    const int i = index(id);
    if (i < 0) throw std::runtime_error(stem + ": no check '" + id + "'");
    wanted[static_cast<std::size_t>(i)] = true;
  }
  std::function<void(int, const std::vector<std::uint64_t>&, int)> need =
      [&](int i, const std::vector<std::uint64_t>& s, int depth) {
        if (depth > static_cast<int>(checks.size()))
          throw std::runtime_error(stem + ": checks refer to each other in a cycle (at '" +
                                   checks[static_cast<std::size_t>(i)].id + "')");
        auto& mine = seeds[static_cast<std::size_t>(i)];
        for (std::uint64_t x : s)
          if (std::find(mine.begin(), mine.end(), x) == mine.end()) mine.push_back(x);
        const Check& c = checks[static_cast<std::size_t>(i)];
        for (const std::string* o : {&c.against, &c.ratio_to})
          if (!o->empty()) need(index(*o), s, depth + 1);
      };
  for (std::size_t i = 0; i < checks.size(); ++i)
    if (wanted[i]) need(static_cast<int>(i), OwnSeeds(checks[i], opt), 0);

  // Every distinct run once; each knows the checks measured on it.
  std::map<RunKey, std::vector<std::size_t>> runs;  // run -> checks
  for (std::size_t i = 0; i < checks.size(); ++i)
    for (std::uint64_t s : seeds[i]) {
      std::vector<std::string> sets = opt.extra_sets;
      sets.insert(sets.end(), checks[i].sets.begin(), checks[i].sets.end());
      runs[{sets, checks[i].duration, s}].push_back(i);
    }
  std::vector<std::pair<RunKey, std::vector<std::size_t>>> list(runs.begin(), runs.end());
  std::vector<std::vector<Slot>> slots(list.size());
  TaskPool pool(std::max(1, opt.jobs));
  pool.ForEach(list.size(), [&](std::size_t r) {
    // Named references, not a structured binding: clang 14 cannot capture a binding in the
    // lambda below.
    const RunKey& key = list[r].first;
    const std::vector<std::size_t>& on = list[r].second;
    std::vector<Slot>& out = slots[r];
    out.resize(on.size());
    std::optional<SweepRecord> rec =
        RunScenarioOnce(source, RunOverrides(key), {}, [&](const Experiment& exp) {
          const auto metrics = exp.Results().Scalars();
          for (std::size_t j = 0; j < on.size(); ++j) out[j] = Measure(checks[on[j]], exp, metrics);
        });
    if (!rec || rec->status != "completed")
      for (Slot& s : out)
        s = {kNaN, "run " + std::string(rec ? rec->status + ": " + rec->message : "stopped"), {}};
  });
  // raw[check][seed]
  std::vector<std::map<std::uint64_t, Slot>> raw(checks.size());
  for (std::size_t r = 0; r < list.size(); ++r)
    for (std::size_t j = 0; j < list[r].second.size(); ++j)
      raw[list[r].second[j]][list[r].first.seed] = slots[r][j];

  // A check's value on a seed: its quantity, divided by ratio_to's value when it has one.
  std::function<Slot(std::size_t, std::uint64_t)> value = [&](std::size_t i, std::uint64_t s) {
    Slot v = raw[i][s];
    const Check& c = checks[i];
    if (v.error.empty() && !c.ratio_to.empty()) {
      const Slot d = value(static_cast<std::size_t>(index(c.ratio_to)), s);
      if (!d.error.empty()) return Slot{kNaN, c.ratio_to + ": " + d.error, {}};
      v = Combine(v, d, c.minus);
    }
    return v;
  };

  std::vector<LessonCheckResult> out;
  for (std::size_t i = 0; i < checks.size(); ++i) {
    if (!wanted[i]) continue;
    const Check& c = checks[i];
    LessonCheckResult res;
    res.lesson = stem;
    res.id = c.id;
    res.relation = RelationText(c);
    res.against_check = !c.against.empty();
    res.share = c.share;
    if (c.share < 1) res.relation += " on " + Num(100 * c.share) + " % of the seeds";
    res.seeds = OwnSeeds(c, opt);
    for (std::uint64_t s : res.seeds) {
      const Slot v = value(i, s);
      Slot rhs{c.value, "", {}};
      if (!c.against.empty()) {
        rhs = value(static_cast<std::size_t>(index(c.against)), s);
        if (!rhs.error.empty()) rhs.error = c.against + ": " + rhs.error;
      }
      if (res.error.empty() && !v.error.empty()) res.error = "seed " + std::to_string(s) + ": " + v.error;
      if (res.error.empty() && !rhs.error.empty()) res.error = "seed " + std::to_string(s) + ": " + rhs.error;
      // Over robots: the robot that decides stands for the check on this seed.
      const std::size_t d = Decider(c, v, rhs);
      res.values.push_back(At(v, d));
      res.operands.push_back(At(rhs, d));
      if (c.over != Check::Over::kOne) res.deciders.push_back(c.robots[d]);
      res.holds.push_back(v.error.empty() && rhs.error.empty() && RelationHolds(c, At(v, d), At(rhs, d)));
    }
    out.push_back(std::move(res));
  }
  return out;
}

namespace {

// A value as compared between edits: numbers by value ("0.50" is "0.5"), the rest as text.
std::string Canonical(const std::string& v) {
  double x = 0;
  return ParseFiniteDouble(v, &x) ? FormatDouble(x) : v;
}

// Why `run` is not the run of check `c` ("" when it is).
std::string NotTheRunOf(const Check& c, const Experiment& exp, const RunEdits& run) {
  std::map<std::string, std::string> want;
  for (const std::string& e : c.sets) {
    const auto eq = e.find('=');
    want[e.substr(0, eq)] = Canonical(e.substr(eq + 1));
  }
  std::map<std::string, std::string> have;
  for (const auto& [k, v] : run.edits) have[k] = Canonical(v);
  if (have != want) {
    std::string edits;
    for (const std::string& e : c.sets) edits += (edits.empty() ? "" : ", ") + e;
    return c.id + " is measured on a run started with " +
           (edits.empty() ? std::string("the lesson's own values") : edits);
  }
  if (run.changed_while_running) return "the run was changed while it ran; reset it (r) to measure";
  if (c.duration > 0 && std::abs(exp.setup().duration - c.duration) > 0.5 * exp.setup().dt &&
      !(c.source == Check::Source::kColumn && c.to <= c.duration && exp.setup().duration > c.duration))
    return c.id + " needs a " + Num(c.duration) + " s run";
  return "";
}

}  // namespace

double CheckNeedsTime(const LessonDef& lesson, const Check& check) {
  const double inf = std::numeric_limits<double>::infinity();
  std::function<double(const Check&, int)> need = [&](const Check& c, int depth) -> double {
    double t = c.source == Check::Source::kColumn ? c.to : inf;
    if (depth > 8) return inf;
    for (const std::string* other : {&c.ratio_to, &c.against})
      if (const Check* o = other->empty() ? nullptr : lesson.Find(*other))
        t = std::max(t, need(*o, depth + 1));
    return t;
  };
  return need(check, 0);
}

LiveCheck MeasureOnRun(const LessonDef& lesson, const Check& check, const Experiment& exp,
                       const RunEdits& run) {
  LiveCheck out;
  const double need = CheckNeedsTime(lesson, check);
  out.ready = exp.finished() || exp.time() >= need - 0.5 * exp.setup().dt;
  if (!out.ready) return out;
  const auto metrics = exp.Results().Scalars();
  // The value of a check on this run, through its ratio_to chain.
  std::function<Slot(const Check&, int)> value = [&](const Check& c, int depth) -> Slot {
    const std::string why = NotTheRunOf(c, exp, run);
    if (!why.empty()) return {kNaN, why, {}};
    Slot v = Measure(c, exp, metrics);
    if (!v.error.empty() || c.ratio_to.empty()) return v;
    const Check* d = lesson.Find(c.ratio_to);
    if (d == nullptr || depth > 8) return {kNaN, "no check '" + c.ratio_to + "'", {}};
    // The divisor is a check of another run (omega_ratio: L = 0.05 over the lesson's own run):
    // only its own run measures it.
    if (d->sets != c.sets) return {kNaN, c.id + " compares two runs; formsim lessons check runs both", {}};
    const Slot dv = value(*d, depth + 1);
    if (!dv.error.empty()) return dv;
    return Combine(v, dv, c.minus);
  };
  Slot v = value(check, 0);
  Slot rhs{check.value, "", {}};
  if (v.error.empty() && !check.against.empty()) {
    const Check* o = lesson.Find(check.against);
    rhs = o == nullptr ? Slot{kNaN, "no check '" + check.against + "'", {}}
          : o->sets != check.sets
              ? Slot{kNaN, check.id + " compares two runs; formsim lessons check runs both", {}}
              : value(*o, 1);
  }
  const std::size_t d = Decider(check, v, rhs);
  out.value = At(v, d);
  if (check.over != Check::Over::kOne) out.robot = check.robots[d];
  out.error = !v.error.empty() ? v.error : rhs.error;
  out.holds = out.error.empty() && RelationHolds(check, At(v, d), At(rhs, d));
  return out;
}

std::string LessonRelationText(const Check& c) { return RelationText(c); }

std::string RenderLessonParagraph(const std::string& text,
                                  const std::function<ShownCheck(const std::string&)>& shown) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t open = text.find('{', i);
    if (open == std::string::npos) break;
    const std::size_t close = text.find('}', open);
    if (close == std::string::npos) break;
    const std::string id = text.substr(open + 1, close - open - 1);
    out += text.substr(i, open - i);
    if (CheckReferences("{" + id + "}").empty()) {
      out += text.substr(open, close + 1 - open);  // not a check's name
    } else {
      const ShownCheck s = shown(id);
      // NaN is shown as pending: it is no number a student can read; an infinite value (a level
      // never crossed, an error that does not decay) as ∞.
      if (!s.measured || std::isnan(s.value))
        out += "(…)";
      else
        out += "(" + (s.robot.empty() ? std::string() : s.robot + ": ") +
               (std::isinf(s.value) ? std::string(s.value > 0 ? "∞" : "−∞") : Num(s.value)) +
               (s.holds ? " √)" : s.some_seeds ? ", not on this seed)" : ", does not hold)");
    }
    i = close + 1;
  }
  out += text.substr(std::min(i, text.size()));
  return out;
}

std::string RenderLessonText(const LessonDef& l,
                             const std::function<ShownCheck(const std::string&)>& shown) {
  auto para = [&](const std::string& p) { return RenderLessonParagraph(p, shown); };
  std::string out = l.title + "\n\n" + para(l.goal) + "\n";
  if (!l.equations.empty()) {
    out += "\n";
    for (const std::string& e : l.equations) out += "  " + e + "\n";
  }
  for (std::size_t i = 0; i < l.steps.size(); ++i) {
    const LessonStep& s = l.steps[i];
    out += "\nStep " + std::to_string(i + 1) + ". " + para(s.text) + "\n";
    if (!s.action.label.empty()) out += "  [" + s.action.label + "]\n";
    if (!s.predict.question.empty()) {
      out += "  Predict: " + para(s.predict.question) + "\n";
      for (std::size_t k = 0; k < s.predict.options.size(); ++k)
        out += "    " + std::string(1, static_cast<char>('A' + k)) + ". " + para(s.predict.options[k]) +
               (static_cast<int>(k) == s.predict.answer ? "   (the answer)" : "") + "\n";
      if (!s.predict.explain.empty()) out += "  " + para(s.predict.explain) + "\n";
    }
  }
  return out;
}

bool LessonCheckResult::SeedChangesNothing() const {
  if (share >= 1 || values.size() < 2) return false;
  return std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
}

std::string FormatCheckResult(const LessonCheckResult& r) {
  std::string values;
  for (std::size_t i = 0; i < r.values.size(); ++i) values += (i ? " " : "") + Num(r.values[i]);
  std::string against;
  if (r.against_check) {
    for (std::size_t i = 0; i < r.operands.size(); ++i) against += (i ? " " : "") + Num(r.operands[i]);
    against = "  vs [" + against + "]";
  }
  // Over robots: the robot each value is of (the one that decides), once when it is always the same.
  std::string robots;
  if (!r.deciders.empty()) {
    const bool same = std::all_of(r.deciders.begin(), r.deciders.end(),
                                  [&](const std::string& d) { return d == r.deciders.front(); });
    if (same) {
      robots = "  (" + r.deciders.front() + (r.deciders.size() > 1 ? " on every seed)" : ")");
    } else {
      for (std::size_t i = 0; i < r.deciders.size(); ++i) robots += (i ? " " : "") + r.deciders[i];
      robots = "  (robots " + robots + ")";
    }
  }
  std::string line = r.lesson + "  " + r.id + "  seeds " + std::to_string(r.seeds.size()) + "  [" +
                     values + "]" + robots + against + "  " + r.relation + "  " +
                     (r.ok() ? "holds" : "FAILS");
  if (!r.error.empty()) line += "  (" + r.error + ")";
  if (r.SeedChangesNothing())
    line += "  (the same value on every seed, though the check says its effect depends on the seed)";
  return line;
}

std::vector<SeedEffectWarning> SeedEffectWarnings(const LessonDef& lesson,
                                                  const std::vector<LessonCheckResult>& results) {
  std::vector<SeedEffectWarning> out;
  for (const auto& [id, claim] : ChecksClaimingASeedEffect(lesson))
    for (const LessonCheckResult& r : results) {
      if (r.id != id || !r.error.empty() || r.values.size() < 2) continue;
      const bool same = std::all_of(r.values.begin(), r.values.end(),
                                    [&](double v) { return v == r.values.front(); });
      if (same) out.push_back({r.lesson, r.id, r.values.front(), r.values.size(), claim});
    }
  return out;
}

std::string FormatSeedEffectWarning(const SeedEffectWarning& w) {
  return "warning: " + w.lesson + ": check " + w.id + " is " + Num(w.value) + " on every one of the " +
         std::to_string(w.seeds) + " seeds checked, yet the lesson's text says it depends on the seed: \"" +
         w.claim + "\"";
}

}  // namespace formsim::sim
