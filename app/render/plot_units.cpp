#include "app/render/plot_units.hpp"

#include "app/render/display_unit.hpp"

namespace formsim::app {
namespace {

void Scale(std::vector<double>& v, double k) {
  for (double& x : v) x *= k;
}

}  // namespace

void ShowPlotInUnits(PlotData& data, bool degrees) {
  if (!degrees) return;
  const double kx =
      data.x_tick_labels.empty() ? ShownUnit(LabelUnit(data.x_label), true).scale : 1.0;
  const double ky =
      data.y_tick_labels.empty() ? ShownUnit(LabelUnit(data.y_label), true).scale : 1.0;
  if (kx != 1.0) {
    data.x_label = ShownLabel(data.x_label, true);
    for (PlotSeries& s : data.series) Scale(s.x, kx);
  }
  if (ky != 1.0) {
    data.y_label = ShownLabel(data.y_label, true);
    for (PlotSeries& s : data.series) {
      Scale(s.y, ky);
      Scale(s.band_lo, ky);
      Scale(s.band_hi, ky);
      Scale(s.err_lo, ky);
      Scale(s.err_hi, ky);
    }
    Scale(data.reference_lines, ky);
  }
}

}  // namespace formsim::app
