#pragma once
/// \file Turns a sim::FigureSpec into plottable data by reading the recorder's columns.

#include "app/render/plot.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

/// Resolves every series of `spec` (recorded column vs "t" or vs `x_column`, or inline data).
/// A missing column does not throw: the figure's `error` names it, so the GUI can show it.
PlotData ResolveFigure(const sim::FigureSpec& spec, const sim::Recorder& recorder);

}  // namespace formsim::app
