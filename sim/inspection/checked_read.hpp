#pragma once
/// \file Keys that are not tunables but still need a hard validity (lengths, counts, rates that
/// only apply on reset and have no slider): read with the same Tune rule and the same message
/// as a tunable ("must be in [0.001, 1000]"), without entering the ParamTable.

#include <string>

#include "sim/core/multirate.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/param_table.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim::inspection {

/// A number at `key` (default `def`) that must satisfy `valid` (its validity only is used).
inline double CheckedReal(YamlReader& r, const std::string& key, double def, const Tune& valid) {
  const double v = r.Double(key, def);
  if (const std::string why = valid.Check(v); !why.empty()) r.Fail(key, why);
  return v;
}

/// An integer at `key` (default `def`) that must satisfy `valid`.
inline int CheckedInt(YamlReader& r, const std::string& key, int def, const Tune& valid) {
  const int v = r.Int(key, def);
  if (const std::string why = valid.Check(v); !why.empty()) r.Fail(key, why);
  return v;
}

/// World steps between two runs of something at `rate_hz` (read at `key`), through
/// StepsPerPeriod: a rate above 1/dt or one that gives more than 10^8 steps fails at the key.
inline int RateSteps(YamlReader& r, const std::string& key, double rate_hz, double dt) {
  int steps = 1;
  const double period = 1.0 / rate_hz;
  if (const std::string why = StepsPerPeriod(period, dt, false, &steps); !why.empty())
    r.Fail(key, "the period 1/" + key + " = " + FormatDouble(period) + " s " + why);
  return steps;
}

}  // namespace formsim::sim::inspection
