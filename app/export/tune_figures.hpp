#pragma once
/// \file The figures of `formsim tune`, as PlotData for the plot widget:
///   convergence.png   the objective of each evaluation (those that break a constraint in grey)
///                     and the best feasible so far
///   landscape.png     two tuned keys: the visited points over a heatmap of the objective
///                     estimated from the history (inverse-distance weighting of the
///                     evaluations that ran), the start and the best marked
///   validation.png    --holdout: best - start per held-out run, with the mean and its 95% CI

#include <string>

#include "app/render/plot.hpp"
#include "sim/study/tune.hpp"
#include "sim/study/tune_validation.hpp"

namespace formsim::app {

/// The convergence of a tuning run.
PlotData TuneConvergenceFigure(const sim::TuneSettings& settings, const sim::TuneResult& result,
                               const std::string& expr);

/// The objective landscape over the two tuned keys (settings.params.size() == 2), `cells` x
/// `cells` in the search's scaled coordinates (log keys in log space).
PlotData TuneLandscapeFigure(const sim::TuneSettings& settings, const sim::TuneResult& result,
                             const std::string& expr, int cells = 24);

/// The paired differences best - start on the held-out runs.
PlotData TuneValidationFigure(const sim::TuneValidation& validation,
                              const sim::TuneSettings& settings, const sim::TuneResult& result,
                              const std::string& expr);

// A single-metric objective is named by the label and unit its kind declares (with markup), a
// weighted sum by its expression.

}  // namespace formsim::app
