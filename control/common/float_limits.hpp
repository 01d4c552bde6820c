#pragma once
/// Named non-finite doubles, so that each file need not spell out std::numeric_limits (and a
/// unity build does not see the same constant defined twice).
#include <limits>

namespace formsim::control {

/// A quiet NaN: "no value" in tables, plots and metrics.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Positive infinity.
inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace formsim::control
