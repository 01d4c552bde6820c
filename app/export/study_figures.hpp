#pragma once
/// \file Figures of a sweep and of a tuning run, as PlotData for the plot widget (the same
/// widget and headless renderer as every other figure):
///   sweep, no varied key   the metric for each seed, the mean as a reference line
///   sweep, one varied key  the metric's mean against the key with a ±1σ band, and each seed
///   sweep, two grid keys   a heatmap of the mean with a colour bar
///   tune                   the objective of each evaluation and the best so far
/// A sweep of three or more keys (or a Latin hypercube of two or more) has no figure: its
/// ranking table (sim::RankingText) stands for it.

#include <string>
#include <vector>

#include "app/render/plot.hpp"
#include "sim/study/sweep_tables.hpp"
#include "sim/study/tune.hpp"

namespace formsim::app {

/// The figure of metric `m` (an index into tables.metrics) for a sweep. Returns false when the
/// sweep's shape has no figure.
bool SweepFigure(const sim::SweepDefinition& def, const sim::SweepTables& tables,
                 const std::vector<sim::SweepRecord>& records, int m, PlotData* out);

/// The convergence of a tuning run.
PlotData TuneConvergenceFigure(const sim::TuneSettings& settings, const sim::TuneResult& result,
                               const std::string& expr);

/// Renders `data` headless (OSMesa) as a white paper-style figure and writes it as a PNG.
/// Throws std::runtime_error when it cannot be written.
void WriteFigurePng(const PlotData& data, const std::string& path, int width = 960,
                    int height = 600);

}  // namespace formsim::app
