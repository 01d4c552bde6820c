#include "app/render/display_unit.hpp"

namespace formsim::app {

DisplayUnit ShownUnit(const std::string& unit, bool degrees) {
  constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;
  DisplayUnit d;
  d.unit = unit;
  if (unit.rfind("rad", 0) != 0) return d;
  std::string rest = unit.substr(3);
  // "rad" itself, or followed by a power or a "/": not "radius" or "rad_x".
  const bool squared = rest.rfind("²", 0) == 0 || rest.rfind("^2", 0) == 0;
  if (squared) rest = rest.substr(rest[0] == '^' ? 2 : std::string("²").size());
  if (!rest.empty() && rest[0] != '/' && rest[0] != ' ') return d;
  d.angle = true;
  if (!degrees) return d;
  d.scale = squared ? kDegPerRad * kDegPerRad : kDegPerRad;
  // A squared degree reads "deg²" (a lone "°²" is easy to misread); rates and plain angles "°".
  d.unit = (squared ? std::string("deg²") : std::string("°")) + rest;
  return d;
}

std::string LabelUnit(const std::string& label) {
  const auto open = label.rfind(" [");
  if (open == std::string::npos || label.empty() || label.back() != ']') return "";
  return label.substr(open + 2, label.size() - open - 3);
}

std::string ShownLabel(const std::string& label, bool degrees) {
  const std::string unit = LabelUnit(label);
  if (unit.empty()) return label;
  return label.substr(0, label.size() - unit.size() - 1) + ShownUnit(unit, degrees).unit + "]";
}

}  // namespace formsim::app
