#pragma once
/// \file The unit a value is shown in: the window's angle unit applied to any unit built on the
/// radian (rad, rad/s, rad/s², rad/√s, rad²), everything else as it is. View-only: values are
/// stored, edited, recorded and saved in SI units and radians; only their text changes.

#include <string>

namespace formsim::app {

/// How to show a quantity whose stored unit is `unit`.
struct DisplayUnit {
  double scale = 1.0;  ///< shown = stored * scale
  std::string unit;    ///< the unit shown ("°", "°/s", "deg²", "m")
  bool angle = false;  ///< the unit is built on the radian
};

/// `unit` as shown with angles in degrees (`degrees`) or radians: "rad" -> "°" (×180/π),
/// "rad/s" -> "°/s", "rad²" (or "rad^2") -> "deg²" (×(180/π)²), "rad/√s" -> "°/√s"; any other
/// unit (and every unit with `degrees` false) unchanged with scale 1.
DisplayUnit ShownUnit(const std::string& unit, bool degrees);

/// The unit in `label`'s trailing brackets ("max|e_phi| [rad]" -> "rad"; "" when none).
std::string LabelUnit(const std::string& label);
/// `label` with its bracketed unit as shown: "max|e_phi| [°]" with `degrees`.
std::string ShownLabel(const std::string& label, bool degrees);

}  // namespace formsim::app
