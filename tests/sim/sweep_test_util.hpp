#pragma once
// What the sweep and tune tests share: the core test kind's circle as a scenario, and the
// message of what a call throws.
#include <functional>
#include <stdexcept>
#include <string>

#include "sim/scenario/scenario.hpp"
#include "test_kind.hpp"

namespace formsim::sim::sweeptest {

/// testkind::kScenario, named circle.yaml.
inline ScenarioSource Circle() {
  return ScenarioSource::FromText(testkind::kScenario, "circle.yaml", "");
}

/// What `f` throws, or "" when it does not.
inline std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace formsim::sim::sweeptest
