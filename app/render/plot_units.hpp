#pragma once
/// \file A resolved plot in the window's angle unit: an axis whose label's unit is built on the
/// radian ("e_φ [rad]", "ω [rad/s]") is shown in degrees when the window shows degrees, its
/// numbers and its label alike. View-only: the recorded data and the exported figures keep
/// radians.

#include "app/render/plot.hpp"

namespace formsim::app {

/// Scales the series, bands, error bars and reference lines of `data` on each axis whose label
/// names an angle unit, and writes the unit shown in the label. Nothing changes with `degrees`
/// false or without an angle axis.
void ShowPlotInUnits(PlotData& data, bool degrees);

}  // namespace formsim::app
