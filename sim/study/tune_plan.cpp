#include "sim/study/tune_plan.hpp"

#include <algorithm>
#include <stdexcept>

namespace formsim::sim {
namespace {

std::string Known() {
  std::string known;
  for (const std::string& a : TuneAlgorithms()) known += (known.empty() ? "" : ", ") + a;
  return known + ", or GLOBAL+LOCAL such as direct-l+bobyqa";
}

void CheckKnown(const std::string& spec, const std::string& m) {
  const auto all = TuneAlgorithms();
  if (std::find(all.begin(), all.end(), m) == all.end())
    throw std::runtime_error("--method '" + spec + "': unknown method '" + m + "' (one of " +
                             Known() + ")");
}

}  // namespace

std::vector<std::string> TuneAlgorithms() {
  return {"bobyqa", "neldermead", "cobyla", "direct-l", "crs2", "mlsl", "isres"};
}

bool IsGlobalMethod(const std::string& m) {
  return m == "direct-l" || m == "crs2" || m == "mlsl" || m == "isres";
}

bool TakesConstraints(const std::string& m) { return m == "cobyla" || m == "isres"; }

bool IsRandomMethod(const std::string& m) { return m == "crs2" || m == "mlsl" || m == "isres"; }

int MinEvaluations(const std::string& m, int n) {
  if (m == "crs2") return 10 * (n + 1) + 1;
  if (m == "isres") return 20 * (n + 1) + 1;
  if (m == "mlsl") return 4 * (n + 2);
  if (m == "direct-l") return 2 * n + 2;
  return n + 2;  // a local method's first simplex or interpolation set
}

std::vector<TuneStage> PlanTune(const std::string& spec, int n, int budget, int reals) {
  if (reals < 0) reals = n;
  const std::size_t plus = spec.find('+');
  std::vector<TuneStage> plan;
  if (plus == std::string::npos) {
    CheckKnown(spec, spec);
    if (!IsGlobalMethod(spec) && reals < n)
      throw std::runtime_error("--method " + spec +
                               ": integer and choice keys are searched by a global stage; use a "
                               "global method or GLOBAL+LOCAL (such as direct-l+" +
                               spec + ")");
    plan.push_back({spec, budget});
  } else {
    const std::string g = spec.substr(0, plus), l = spec.substr(plus + 1);
    CheckKnown(spec, g);
    CheckKnown(spec, l);
    if (!IsGlobalMethod(g) || IsGlobalMethod(l))
      throw std::runtime_error("--method '" + spec +
                               "': a two-stage plan is GLOBAL+LOCAL (global: direct-l, crs2, "
                               "mlsl, isres; local: bobyqa, neldermead, cobyla)");
    if (reals == 0) {
      plan.push_back({g, budget});  // nothing real to polish
    } else {
      const int global = std::max(MinEvaluations(g, n), budget * 2 / 5);
      plan.push_back({g, global});
      plan.push_back({l, budget - global});
    }
  }
  // A global stage searches every key, a local one the real keys.
  auto need = [&](const std::string& m) { return MinEvaluations(m, IsGlobalMethod(m) ? n : reals); };
  int needed = 0;
  std::string parts;
  for (const TuneStage& s : plan) {
    needed += need(s.method);
    parts += (parts.empty() ? "" : ", ") + std::to_string(need(s.method)) + " for " + s.method;
  }
  // Evaluation 1 is the scenario's own values: it counts in the first stage's budget.
  if (budget < needed)
    throw std::runtime_error("--budget " + std::to_string(budget) + ": too small for --method " +
                             spec + " with " + std::to_string(n) + " tunable" +
                             (n == 1 ? "" : "s") + " (needs at least " + std::to_string(needed) +
                             ": " + parts + ")");
  return plan;
}

std::string PlanText(const std::vector<TuneStage>& plan) {
  std::string out;
  for (const TuneStage& s : plan)
    out += (out.empty() ? "" : " + ") + s.method + " " + std::to_string(s.evaluations);
  return out + " evaluations";
}

}  // namespace formsim::sim
