#pragma once
/// \file Figures of a sweep and of a tuning run, as PlotData for the plot widget (the same
/// widget and headless renderer as every other figure):
///   sweep, no varied key   the metric for each seed, the mean as a reference line
///   sweep, one varied key  the metric's mean against the key with a band (--band: 95% CI of
///                          the mean by default, ±1σ or min-max), and each seed
///   sweep, two grid keys   a heatmap of the mean, each cell annotated "mean ± CI half-width"
///   random samples of two or more keys, grids of three or more: panels (SweepPanels), one per
///                          varied key: each point's mean against the key, coloured by the
///                          metric, and for grid keys the mean over the other keys with its band
/// A sweep over several scenarios draws each scenario in its colour, named by its stem in the
/// legend: with no varied key or one, one figure (a series per scenario); otherwise the figure
/// or panels above for each scenario, one scenario to a row (SweepScenarioPanels).
/// (The tune's figures: app/export/tune_figures.hpp.)

#include <string>
#include <vector>

#include "app/render/plot.hpp"
#include "sim/study/sweep_tables.hpp"

namespace formsim::app {

/// The spread a sweep figure shades around the mean (`--band`).
enum class SweepBand {
  kSd,     ///< mean ± one sample standard deviation
  kCi95,   ///< the 95% confidence interval of the mean (Student t): the default
  kMinMax  ///< from the smallest to the largest value over the seeds
};
/// Parses `--band`'s value: sd, ci95 or minmax. Throws std::runtime_error naming --band and
/// listing what is accepted.
SweepBand ParseSweepBand(const std::string& text);
/// The band in a legend: "± 1σ", "95% CI of the mean", "min–max".
std::string SweepBandText(SweepBand band);

/// The figure of metric `m` (an index into tables.metrics) for a sweep. Returns false when the
/// sweep's shape has no single figure (see SweepPanels).
bool SweepFigure(const sim::SweepDefinition& def, const sim::SweepTables& tables,
                 const std::vector<sim::SweepRecord>& records, int m, PlotData* out,
                 SweepBand band = SweepBand::kCi95);

/// The panels of a sweep that has no single figure: random samples of two or more keys (a
/// scatter of each point's mean against each key, coloured by the metric) and grids of three
/// or more keys (small multiples: the same, with the mean over the other keys and its band at
/// each value). Empty when SweepFigure draws the sweep (or `m` is no metric).
std::vector<PlotData> SweepPanels(const sim::SweepDefinition& def, const sim::SweepTables& tables,
                                  int m, SweepBand band = SweepBand::kCi95);

/// A sweep over several scenarios that SweepFigure does not draw (two grid keys or more, or
/// random samples of two or more): for each scenario the figure or panels a sweep of it alone
/// would get, each title starting with the scenario's name, one scenario to a row of `*columns`
/// panels. Empty for a sweep of one scenario (or when `m` is no metric).
std::vector<PlotData> SweepScenarioPanels(const sim::SweepDefinition& def,
                                          const sim::SweepTables& tables,
                                          const std::vector<sim::SweepRecord>& records, int m,
                                          SweepBand band, int* columns);

/// Renders `panels` headless into one PNG, `columns` panels to a row, each panel_width x
/// panel_height pixels. Throws std::runtime_error when it cannot be written.
void WritePanelsPng(const std::vector<PlotData>& panels, const std::string& path,
                    int panel_width = 640, int panel_height = 440, int columns = 2);

/// Renders `data` headless (OSMesa) as a white paper-style figure and writes it as a PNG.
/// Throws std::runtime_error when it cannot be written.
void WriteFigurePng(const PlotData& data, const std::string& path, int width = 960,
                    int height = 600);

}  // namespace formsim::app
