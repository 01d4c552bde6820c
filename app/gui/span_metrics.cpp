#include "app/gui/span_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "sim/core/background.hpp"
#include "sim/core/experiment.hpp"
#include "sim/core/run_output.hpp"

namespace formsim::app {

const sim::Metrics* SpanMetrics::Get(const std::string& run, long steps,
                                     const std::function<Replayed()>& replayed,
                                     std::string* error) {
  Entry& e = runs_[run];
  if (e.cancel && e.steps != steps) {
    *e.cancel = true;  // another length: the old replay stops at its next poll
    e = Entry();
  }
  if (!e.cancel) {
    e.steps = steps;
    e.cancel = std::make_shared<std::atomic<bool>>(false);
    auto cancel = e.cancel;
    Replayed r = replayed();  // named, not a structured binding: clang 14 cannot capture one
    std::shared_ptr<const sim::ScenarioSource> source = std::move(r.first);
    sim::RunLog log = std::move(r.second);
    e.job =
        sim::StartBackground(
                   [source, log = std::move(log), steps, cancel]() -> std::optional<sim::Metrics> {
                     // The history bound of the GUI's runs, as a pin's replay has it.
                     sim::RunReplay replay(*source, log, [](sim::Experiment& x) {
                       x.mutable_recorder().SetHistoryLimit(sim::kRunHistoryRows);
                     });
                     if (!replay.AdvanceTo(steps, true, [&] { return cancel->load(); }))
                       return std::nullopt;
                     return replay.exp().Results();
                   });
  }
  if (e.job.valid() && e.job.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      e.metrics = e.job.get();
      if (!e.metrics) e.error = "cancelled";
    } catch (const std::exception& x) {
      e.error = x.what();
    }
  }
  if (error != nullptr) *error = e.error;
  return e.metrics ? &*e.metrics : nullptr;
}

bool SpanMetrics::Busy() const {
  for (const auto& [run, e] : runs_)
    if (e.job.valid() && e.job.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
      return true;
  return false;
}

void SpanMetrics::Clear() {
  for (auto& [run, e] : runs_)
    if (e.cancel) *e.cancel = true;
  runs_.clear();  // each future's destructor waits for its replay's next poll
}

long StepAtTime(long steps, double seconds, double t) {
  if (steps <= 0 || !(seconds > 0) || t >= seconds) return steps;
  const double dt = seconds / static_cast<double>(steps);
  // The last step at or before t (a step's time is a multiple of dt, up to rounding).
  return std::clamp(static_cast<long>(std::floor(t / dt + 1e-6)), 0L, steps);
}

}  // namespace formsim::app
