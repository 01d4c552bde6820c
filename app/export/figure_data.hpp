#pragma once
/// \file Turns a sim::FigureSpec into plottable data by reading the recorder's columns.

#include "app/render/plot.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

/// "" when every text of `spec` (title, axis labels, series labels) is good label
/// markup, else which one is not and why, e.g. "series 2 'e_{\foo}': unknown markup command ...".
std::string FigureMarkupError(const sim::FigureSpec& spec);

/// A plot against time (every series against "t"; not an equal-aspect plane, not bars): the
/// figures whose y axis may be logarithmic.
bool IsTimePlot(const sim::FigureSpec& spec);

/// Resolves every series of `spec` (recorded column vs "t" or vs `x_column`, or inline data).
/// A missing column or bad markup does not throw: the figure's `error` names it, so the GUI can
/// show it.
PlotData ResolveFigure(const sim::FigureSpec& spec, const sim::Recorder& recorder);

}  // namespace formsim::app
