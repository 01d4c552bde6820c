#include "app/export/figure_size.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

constexpr int kMinLogical = 64, kMaxLogical = 8192, kMaxDevice = 8192;

// One side: "8.5cm", "960", "960px", "3.5in". Returns false when malformed.
bool ParseLength(const std::string& s, FigureLength* out) {
  if (s.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || !std::isfinite(v) || !(v > 0)) return false;
  const std::string unit(end);
  if (!(unit.empty() || unit == "px" || unit == "cm" || unit == "mm" || unit == "in")) return false;
  out->value = v;
  out->unit = unit.empty() ? "px" : unit;
  return true;
}

}  // namespace

double FigureLength::Pixels() const {
  if (unit == "cm") return value / 2.54 * 96.0;
  if (unit == "mm") return value / 25.4 * 96.0;
  if (unit == "in") return value * 96.0;
  return value;
}

std::string FigureLength::Text() const {
  return sim::FormatSignificant(value) + unit;
}

double FigureSize::LayoutScale() const {
  return width.unit == "px" && height.unit == "px" ? 1.0 : 0.75;
}

int FigureSize::LayoutWidth() const {
  return static_cast<int>(std::lround(width.Pixels() / LayoutScale()));
}

int FigureSize::LayoutHeight() const {
  return static_cast<int>(std::lround(height.Pixels() / LayoutScale()));
}

int FigureSize::PngWidth(double dpi) const {
  return static_cast<int>(std::lround(width.Pixels() * dpi / 96.0));
}

int FigureSize::PngHeight(double dpi) const {
  return static_cast<int>(std::lround(height.Pixels() * dpi / 96.0));
}

std::string FigureSize::Text() const {
  return width.Text() + "x" + height.Text();
}

FigureSize ParseFigureSize(const std::string& text, const std::string& flag) {
  // The separator is the 'x' that follows a digit or a unit: "8.5cmx6cm", "960x600".
  FigureSize size;
  bool ok = false;
  for (std::size_t i = 1; i + 1 < text.size() && !ok; ++i) {
    if (text[i] != 'x' && text[i] != 'X') continue;
    ok = ParseLength(text.substr(0, i), &size.width) &&
         ParseLength(text.substr(i + 1), &size.height);
  }
  if (!ok)
    throw std::runtime_error(flag + " '" + text +
                             "': expected WIDTHxHEIGHT in pixels or with units px, cm, mm, in "
                             "(e.g. 960x600, 8.5cmx6cm, 3.5inx2.5in)");
  for (const FigureLength* l : {&size.width, &size.height}) {
    const double px = l->Pixels();
    if (px < kMinLogical - 0.5 || px > kMaxLogical + 0.5) {
      const std::string side =
          l->unit == "px" ? l->Text()
                          : l->Text() + " (" + sim::FormatSignificant(std::round(px)) + " px)";
      const std::string range = sim::Sprintf(
          "': %s is out of range; each side must be %d ... %d px (%.2f ... %.1f cm)", side.c_str(),
          kMinLogical, kMaxLogical, kMinLogical / 96.0 * 2.54, kMaxLogical / 96.0 * 2.54);
      throw std::runtime_error(flag + " '" + text + range);
    }
  }
  return size;
}

double ParseDpi(double dpi) {
  if (!(dpi >= 24 && dpi <= 1200))
    throw std::runtime_error("--dpi " + sim::FormatSignificant(dpi) +
                             ": expected 24 ... 1200 (96 = one pixel per "
                             "logical pixel, 300 for print)");
  return dpi;
}

void CheckDeviceSize(double width, double height, double dpi, const std::string& what) {
  const long w = std::lround(width * dpi / 96.0), h = std::lround(height * dpi / 96.0);
  if (w > kMaxDevice || h > kMaxDevice)
    throw std::runtime_error(what + " at --dpi " + sim::FormatSignificant(dpi) + " gives a " +
                             std::to_string(w) + "x" + std::to_string(h) + " PNG; the limit is " +
                             std::to_string(kMaxDevice) + " pixels a side (lower --dpi)");
}

}  // namespace formsim::app
