#pragma once
/// \file How `formsim tune` searches: `--method` names one NLopt method, or a two-stage plan
/// "GLOBAL+LOCAL" (a global stage over the whole box, then a local polish from its best point;
/// the default is direct-l+bobyqa). The plan splits the evaluation budget between the stages
/// and refuses a budget too small for a method's first iteration.
///
///   local   bobyqa (NLopt LN_BOBYQA), neldermead (LN_NELDERMEAD), cobyla (LN_COBYLA)
///   global  direct-l (GN_DIRECT_L, deterministic), crs2 (GN_CRS2_LM), mlsl (G_MLSL_LDS with a
///           BOBYQA local search), isres (GN_ISRES)
///
/// With constraints, cobyla and isres take them natively; every other method runs inside NLopt's
/// augmented Lagrangian (AUGLAG), which adds a penalty that grows until the constraints hold.

#include <string>
#include <vector>

namespace formsim::sim {

/// The single methods `--method` accepts, local first.
std::vector<std::string> TuneAlgorithms();
/// True for a global method (direct-l, crs2, mlsl, isres).
bool IsGlobalMethod(const std::string& method);
/// True when NLopt's method takes inequality constraints itself (cobyla, isres).
bool TakesConstraints(const std::string& method);
/// Uses a random number stream (crs2, mlsl, isres): `--search-seed` matters.
bool IsRandomMethod(const std::string& method);
/// The fewest evaluations a method needs for its first iteration with `n` tunables (BOBYQA's
/// n + 2 interpolation points, CRS2's population 10 (n + 1), ISRES's 20 (n + 1), ...).
int MinEvaluations(const std::string& method, int n);

/// One stage of a plan: a method and the evaluations it may use (cumulative budgets add up to
/// the whole budget).
struct TuneStage {
  std::string method;
  int evaluations = 0;
};

/// The default `--method`: a global stage, then a local polish.
inline const char* kDefaultTuneMethod = "direct-l+bobyqa";

/// Parses `--method` ("bobyqa", "crs2", "direct-l+bobyqa") for `n` tunables, `reals` of them
/// real (the others integer or choice keys, which only a global stage searches), and `budget`
/// evaluations. A two-stage plan gives the global stage 40% of the budget (at least what it
/// needs) and the rest to the local one; with no real key it is the global stage alone. Throws
/// std::runtime_error naming --method (unknown method, a second stage that is not local, a
/// local method alone with integer or choice keys) or --budget (too small, saying how small).
std::vector<TuneStage> PlanTune(const std::string& method, int n, int budget, int reals = -1);

/// "direct-l 24 + bobyqa 36 evaluations" (the split stated in the output).
std::string PlanText(const std::vector<TuneStage>& plan);

}  // namespace formsim::sim
