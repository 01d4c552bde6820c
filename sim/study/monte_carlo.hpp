#pragma once
/// \file Monte Carlo of one set of settings in the background: the runs of
/// `formsim sweep SCENARIO --set <settings> --seeds <seeds>` (DefineSweep, RunSweep on a
/// TaskPool, BuildSweepTables: the same runs, the same metrics, the same runs.csv and
/// aggregate.csv), plus the spread of the recorded channels of every time figure over the seeds:
/// per recorded row (thinned to at most about 1000 rows), the mean, sample σ, min and max. The
/// spread is folded in run order as runs finish, so it never depends on the number of threads
/// and memory holds one thinned copy per run only while earlier runs are still running.

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "sim/core/background.hpp"
#include <vector>

#include "sim/core/metrics.hpp"
#include "sim/study/sweep.hpp"
#include "sim/study/sweep_tables.hpp"

namespace formsim::sim {

/// The spread of recorded channels over the runs, on a common grid of recorded rows.
struct ChannelBands {
  struct Band {
    std::vector<double> mean, sd, lo, hi;  ///< per grid row; NaN where no run has the row
    std::vector<int> n;                    ///< runs that have the row
  };
  std::vector<double> t;                 ///< time of each grid row (NaN: no run reached it)
  std::map<std::string, Band> channels;  ///< by recorded column name
  int runs = 0;                          ///< runs folded in
  const Band* Find(const std::string& column) const {
    const auto it = channels.find(column);
    return it == channels.end() ? nullptr : &it->second;
  }
};

class MonteCarlo {
 public:
  /// Starts the runs at once on a thread of their own with `threads` workers in all (>= 1).
  /// Throws ScenarioError when the settings or seeds do not define a sweep (nothing started).
  MonteCarlo(const ScenarioSource& source, const std::vector<Override>& sets,
             std::vector<std::uint64_t> seeds, int threads);
  /// Cancels what is left and waits for the runs under way.
  ~MonteCarlo();
  MonteCarlo(const MonteCarlo&) = delete;
  MonteCarlo& operator=(const MonteCarlo&) = delete;

  /// No further run starts; runs under way are abandoned at their next poll.
  void Cancel() { stop_ = true; }
  bool cancelled() const { return stop_; }
  /// Every run has been recorded, or the rest was cancelled.
  bool finished() const { return finished_; }
  /// Runs recorded so far (failed ones included) and in all.
  SweepProgress progress() const;

  const SweepDefinition& definition() const { return def_; }
  /// The tables of the records so far (built when asked; byte-identical to `formsim sweep`'s
  /// runs.csv and aggregate.csv once every run is recorded).
  SweepTables Tables() const;
  /// The spread folded so far (a copy, safe while runs go on).
  ChannelBands Bands() const;
  /// The statistics of each headline metric (Metrics::Headlines) over the completed runs folded
  /// so far, in headline order.
  std::vector<std::pair<std::string, MetricStats>> HeadlineStats() const;
  /// A failure of the sweep itself (not of a run), "" when none.
  std::string error() const;

 private:
  struct Extract;
  void Inspect(std::size_t run, const Experiment& exp);
  void Fold(const Extract& x);

  SweepDefinition def_;
  ScenarioSource source_;
  std::atomic<bool> stop_{false}, finished_{false};
  mutable std::mutex mu_;
  SweepProgress progress_;
  std::vector<SweepRecord> records_;
  std::vector<bool> recorded_;
  std::map<std::size_t, std::shared_ptr<Extract>> pending_;  ///< extracts waiting for their turn
  std::size_t next_fold_ = 0;
  ChannelBands bands_;
  std::vector<std::pair<std::string, std::vector<double>>> headlines_;  ///< values in run order
  std::map<std::string, std::vector<double>> m2_;  ///< Welford's sums of squares per channel
  std::string error_;
  BackgroundThread thread_;  ///< the runs (without threads: done in the constructor)
};

/// Rows of a run's history thinned for bands: every `stride`-th sampled row, where the stride is
/// the smallest power of two giving at most `max_rows` rows over the run's whole duration, so
/// runs of the same duration share the grid whatever their history kept.
long BandStride(const Experiment& exp, long max_rows = 1000);

}  // namespace formsim::sim
