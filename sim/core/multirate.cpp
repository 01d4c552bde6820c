#include "sim/core/multirate.hpp"

#include <cmath>

#include "sim/core/number_format.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

std::string StepsPerPeriod(double period, double dt, bool exact, int* steps) {
  constexpr double kMaxSteps = 1e8;
  if (!(period > 0) || !std::isfinite(period)) return "must be a positive finite period";
  const double ratio = period / dt;
  if (!(ratio >= 1.0 - 1e-9))
    return "must be at least one world step (dt = " + FormatDouble(dt) + " s)";
  if (ratio > kMaxSteps) return "is more than 10^8 world steps of " + FormatDouble(dt) + " s";
  const double n = std::round(ratio);
  if (exact && std::abs(ratio - n) > 1e-9 * std::max(1.0, n))
    return "must be a whole multiple of dt = " + FormatDouble(dt) + " s";
  *steps = static_cast<int>(std::max(1.0, n));
  return "";
}

int ReadPeriodSteps(YamlReader& r, const std::string& key, double def, double dt, bool exact) {
  const double period = r.Double(key, def);
  int steps = 1;
  const std::string err = StepsPerPeriod(period, dt, exact, &steps);
  if (!err.empty()) r.Fail(key, err);
  return steps;
}

int RateSteps(YamlReader& r, const std::string& key, double rate_hz, double dt) {
  int steps = 1;
  if (!(rate_hz > 0)) r.Fail(key, "must be a positive rate");
  const double period = 1.0 / rate_hz;
  if (const std::string why = StepsPerPeriod(period, dt, false, &steps); !why.empty())
    r.Fail(key, "the period 1/" + key.substr(key.rfind('.') + 1) + " = " + FormatDouble(period) + " s " + why);
  return steps;
}

}  // namespace formsim::sim
