#pragma once
/// \file A plot's logarithmic y axis (PlotData::log_y): the data turned into decades (log10 of
/// y) before the ordinary stages lay it out, decade ticks labelled 10^k, and non-positive values
/// dropped from what is drawn (and counted, for the note the plot writes above its axes). An
/// exponential decay is a straight line on it.

#include <string>
#include <vector>

#include "app/render/plot.hpp"

namespace formsim::app {

/// `data` with every y value (lines, bands, error bars, reference lines) replaced by its log10;
/// values <= 0 (or not finite) become NaN, which the plot skips, and are counted in `dropped`.
/// Bars and heatmaps keep their linear axis (log_y is ignored for them: `*applies` false).
PlotData LogYData(const PlotData& data, long* dropped, bool* applies);

/// Ticks of a log axis over [lo, hi] in decades (log10 units): the whole decades k, every m-th
/// so that at most about `max_ticks` are written (`step` gets m); with fewer than two whole
/// decades in range, the logs of 1, 2 and 5 (or of every digit) times powers of ten (`step` 0).
std::vector<double> DecadeTicks(double lo, double hi, int max_ticks, double* step);

/// `e` in Unicode superscript digits ("⁻³").
std::string SuperscriptInt(long e);

/// The label of log tick `k` (decades) of ticks `step` apart (DecadeTicks): "10⁻³" for a whole
/// decade when the ticks are decades, else the value 10^k with three significant digits
/// ("0.02", "0.0316").
std::string DecadeLabel(double k, double step);

}  // namespace formsim::app
