#include "sim/study/monte_carlo.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/common/float_limits.hpp"

namespace formsim::sim {
namespace {

using control::kNaN;

// The recorded columns of the experiment's time figures (series against "t").
std::vector<std::string> TimeColumns(const Experiment& exp) {
  std::vector<std::string> out;
  for (const FigureSpec& f : exp.Figures())
    for (const SeriesSpec& s : f.series) {
      if (s.column.empty() || !(s.x_column.empty() || s.x_column == "t")) continue;
      if (std::find(out.begin(), out.end(), s.column) == out.end()) out.push_back(s.column);
    }
  return out;
}

}  // namespace

long BandStride(const Experiment& exp, long max_rows) {
  const ExperimentSetup& s = exp.setup();
  const double steps = std::ceil(s.duration / s.dt - 1e-9);
  const double rows = std::floor(steps / s.record_every) + 1;
  long stride = 1;
  while (rows / static_cast<double>(stride) > static_cast<double>(max_rows)) stride *= 2;
  return stride;
}

// One run's channels on the band grid: slot k is the run's sampled row k * stride.
struct MonteCarlo::Extract {
  bool completed = false;
  std::vector<Metrics::HeadlineValue> headlines;
  std::vector<double> t;
  std::vector<std::pair<std::string, std::vector<double>>> columns;
};

MonteCarlo::MonteCarlo(const ScenarioSource& source, const std::vector<Override>& sets,
                       std::vector<std::uint64_t> seeds, int threads)
    : def_(DefineSweep(source, sets, {}, std::move(seeds))), source_(source) {
  progress_.total = def_.runs();
  recorded_.assign(def_.runs(), false);
  thread_ = BackgroundThread([this, threads] {
    try {
      TaskPool pool(std::max(1, threads));
      std::vector<std::size_t> runs(def_.runs());
      for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = i;
      RunSweep(
          source_, def_, runs, pool,
          [this](const SweepRecord& rec, const SweepProgress& p) {
            std::lock_guard<std::mutex> lock(mu_);
            progress_ = p;
            records_.push_back(rec);
            recorded_[rec.run] = true;
            // Fold in run order: a run's spread goes in once every earlier run is recorded.
            while (next_fold_ < recorded_.size() && recorded_[next_fold_]) {
              const auto it = pending_.find(next_fold_);
              if (it != pending_.end()) {
                Fold(*it->second);
                pending_.erase(it);
              }
              ++next_fold_;
            }
          },
          [this] { return stop_.load(); },
          [this](std::size_t run, const Experiment& exp) { Inspect(run, exp); });
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mu_);
      error_ = e.what();
    }
    finished_ = true;
  });
}

MonteCarlo::~MonteCarlo() {
  stop_ = true;
  thread_.Join();
}

void MonteCarlo::Inspect(std::size_t run, const Experiment& exp) {
  auto x = std::make_shared<Extract>();
  x->completed = exp.status() == "completed";
  x->headlines = exp.Results().Headlines();
  const Recorder& rec = exp.recorder();
  const long stride = BandStride(exp);
  const long kept = static_cast<long>(rec.history_stride());
  std::vector<std::size_t> rows;  // history rows on the grid
  for (std::size_t r = 0; r < rec.rows(); ++r)
    if ((static_cast<long>(r) * kept) % stride == 0) rows.push_back(r);
  auto column = [&](int c) {
    std::vector<double> v(
        rows.empty() ? 0
                     : static_cast<std::size_t>(static_cast<long>(rows.back()) * kept / stride + 1),
        kNaN);
    for (std::size_t r : rows) v[static_cast<long>(r) * kept / stride] = rec.At(r, c);
    return v;
  };
  x->t = column(rec.Column("t"));
  for (const std::string& name : TimeColumns(exp)) {
    const int c = rec.Column(name);
    if (c >= 0) x->columns.emplace_back(name, column(c));
  }
  std::lock_guard<std::mutex> lock(mu_);
  pending_[run] = std::move(x);
}

void MonteCarlo::Fold(const Extract& x) {
  if (x.completed)
    for (const Metrics::HeadlineValue& h : x.headlines) {
      auto it = std::find_if(headlines_.begin(), headlines_.end(),
                             [&](const auto& e) { return e.first == h.label; });
      if (it == headlines_.end()) it = headlines_.insert(headlines_.end(), {h.label, {}});
      if (std::isfinite(h.value)) it->second.push_back(h.value);
    }
  ChannelBands& b = bands_;
  ++b.runs;
  if (b.t.size() < x.t.size()) b.t.resize(x.t.size(), kNaN);
  for (std::size_t k = 0; k < x.t.size(); ++k)
    if (std::isnan(b.t[k])) b.t[k] = x.t[k];
  for (const auto& [name, v] : x.columns) {
    ChannelBands::Band& band = b.channels[name];
    std::vector<double>& m2 = m2_[name];
    if (band.mean.size() < v.size()) {
      band.mean.resize(v.size(), kNaN);
      band.sd.resize(v.size(), kNaN);
      band.lo.resize(v.size(), kNaN);
      band.hi.resize(v.size(), kNaN);
      band.n.resize(v.size(), 0);
      m2.resize(v.size(), 0.0);
    }
    for (std::size_t k = 0; k < v.size(); ++k) {
      const double y = v[k];
      if (!std::isfinite(y)) continue;  // not sampled in this row, or a fault
      // Welford's update, in run order: the same numbers on any number of threads.
      const int n = ++band.n[k];
      if (n == 1) {
        band.mean[k] = band.lo[k] = band.hi[k] = y;
        m2[k] = 0;
      } else {
        const double d = y - band.mean[k];
        band.mean[k] += d / n;
        m2[k] += d * (y - band.mean[k]);
        band.lo[k] = std::min(band.lo[k], y);
        band.hi[k] = std::max(band.hi[k], y);
      }
      band.sd[k] = n > 1 ? std::sqrt(m2[k] / (n - 1)) : kNaN;
    }
  }
}

SweepProgress MonteCarlo::progress() const {
  std::lock_guard<std::mutex> lock(mu_);
  return progress_;
}

SweepTables MonteCarlo::Tables() const {
  std::vector<SweepRecord> records;
  {
    std::lock_guard<std::mutex> lock(mu_);
    records = records_;
  }
  return BuildSweepTables(def_, std::move(records));
}

ChannelBands MonteCarlo::Bands() const {
  std::lock_guard<std::mutex> lock(mu_);
  return bands_;
}

std::vector<std::pair<std::string, MetricStats>> MonteCarlo::HeadlineStats() const {
  std::lock_guard<std::mutex> lock(mu_);
  std::vector<std::pair<std::string, MetricStats>> out;
  for (const auto& [label, values] : headlines_) out.emplace_back(label, StatsOf(values));
  return out;
}

std::string MonteCarlo::error() const {
  std::lock_guard<std::mutex> lock(mu_);
  return error_;
}

}  // namespace formsim::sim
