#include "app/render/plot_log_scale.hpp"

#include <cmath>
#include <limits>

#include "control/common/float_limits.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

using control::kNaN;

// log10 of the values in place; the non-positive ones become NaN and are counted.
void ToDecades(std::vector<double>& v, long* dropped) {
  for (double& y : v) {
    if (std::isnan(y)) continue;  // a gap already
    if (y > 0 && std::isfinite(y)) {
      y = std::log10(y);
    } else {
      y = kNaN;
      ++*dropped;
    }
  }
}

}  // namespace

PlotData LogYData(const PlotData& data, long* dropped, bool* applies) {
  *dropped = 0;
  *applies = data.log_y && data.heatmap.empty() && data.y_tick_labels.empty();
  for (const PlotSeries& s : data.series) *applies = *applies && !s.bars;
  if (!*applies) return data;
  PlotData out = data;
  for (PlotSeries& s : out.series) {
    ToDecades(s.y, dropped);
    long band_dropped = 0;  // a band's ends count once with their line
    ToDecades(s.band_lo, &band_dropped);
    ToDecades(s.band_hi, &band_dropped);
    if (s.y.empty()) *dropped += band_dropped;
  }
  std::vector<double> refs;
  for (double r : out.reference_lines)
    if (r > 0 && std::isfinite(r)) refs.push_back(std::log10(r));
  out.reference_lines = refs;  // a line at zero has no place on a log axis (not data: no note)
  return out;
}

std::vector<double> DecadeTicks(double lo, double hi, int max_ticks, double* step) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double first = std::ceil(lo - 1e-9), last = std::floor(hi + 1e-9);
  if (last - first < 1) {
    // Less than two whole decades: 1, 2 and 5 times a power of ten (or every digit when those
    // are too few), labelled as values.
    if (step != nullptr) *step = 0;
    for (const std::vector<double>& mantissas :
         {std::vector<double>{1, 2, 5}, std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9}}) {
      ticks.clear();
      for (double k = std::floor(lo); k <= std::ceil(hi); ++k)
        for (double m : mantissas) {
          const double t = k + std::log10(m);
          if (t >= lo - 1e-9 && t <= hi + 1e-9) ticks.push_back(t);
        }
      if (ticks.size() >= 3) return ticks;
    }
    return NiceTicks(lo, hi, max_ticks);  // a range within one digit step
  }
  const double m = std::ceil((last - first + 1) / std::max(2, max_ticks));
  // Every m-th decade, on multiples of m so the labels do not wander as the range moves.
  for (double k = std::ceil(first / m) * m; k <= last; k += m) ticks.push_back(k);
  if (step != nullptr) *step = m;
  return ticks;
}

std::string SuperscriptInt(long e) {
  static const char* sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string out = e < 0 ? "⁻" : "";
  for (char c : std::to_string(std::labs(e))) out += sup[c - '0'];
  return out;
}

std::string DecadeLabel(double k, double step) {
  if (step >= 1 && std::abs(k - std::round(k)) < 1e-9) return "10" + SuperscriptInt(std::lround(k));
  return sim::FormatSignificant(std::pow(10.0, k), 3);
}

}  // namespace formsim::app
