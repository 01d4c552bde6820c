#pragma once
/// \file Runs of different lengths compared honestly: the metrics of a run over its first
/// `steps` steps, from an exact replay of its log (the simulation is deterministic), made in the
/// background and kept per run. The comparison table cuts every run to the common span with it.

#include <atomic>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "sim/core/metrics.hpp"
#include "sim/session/run_log.hpp"

namespace formsim::app {

class SpanMetrics {
 public:
  SpanMetrics() = default;
  SpanMetrics(const SpanMetrics&) = delete;
  SpanMetrics& operator=(const SpanMetrics&) = delete;
  ~SpanMetrics() { Clear(); }

  /// The metrics of run `run` ("now:3", "pin:1") over its first `steps` steps, or null while
  /// they are being replayed (the first ask starts the replay of `source` with `log`; asking
  /// for another length replaces it). `error` gets why a replay failed.
  /// `replayed` gives the run's source and log (asked only when a replay starts).
  using Replayed = std::pair<std::shared_ptr<const sim::ScenarioSource>, sim::RunLog>;
  const sim::Metrics* Get(const std::string& run, long steps,
                          const std::function<Replayed()>& replayed, std::string* error = nullptr);
  /// A replay is still running (the script action `wait` holds).
  bool Busy() const;
  /// Forgets every run (their replays are stopped).
  void Clear();

 private:
  struct Entry {
    long steps = 0;
    std::shared_ptr<std::atomic<bool>> cancel;
    std::future<std::optional<sim::Metrics>> job;
    std::optional<sim::Metrics> metrics;
    std::string error;
  };
  std::map<std::string, Entry> runs_;
};

/// The step of a run with `steps` steps over `seconds` seconds at which it reaches `t` seconds
/// (its last step when it never does): where a run is cut to a common span.
long StepAtTime(long steps, double seconds, double t);

}  // namespace formsim::app
