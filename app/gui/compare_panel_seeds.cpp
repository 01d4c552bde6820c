/// \file The Compare panel's "Run N seeds": the current settings (what a reset would run with) over seeds 1..N in
/// background threads, exactly the runs of `formsim sweep SCENARIO --set <settings> --seeds
/// 1..N` (sim::MonteCarlo on the sweep engine): the window stays responsive, a progress bar
/// shows the runs done, Cancel stops what has not started. The spread goes onto every time plot
/// as bands and the metrics' mean ± σ into the comparison table; with --out the tables are
/// written as the sweep writes them.
#include <filesystem>

#include "app/gui/compare_panel.hpp"
#include "sim/session/session.hpp"
#include "sim/core/run_output.hpp"
#include "sim/study/sweep_tables.hpp"
#include "sim/core/task_pool.hpp"

namespace fs = std::filesystem;

namespace formsim::app {

std::string ComparePanel::CmdSeeds(int n) {
  if (mc_.run && !mc_.run->finished()) {
    return ctx_.Refuse("seeds: a Monte Carlo is running (cancel it first)");
  }
  if (n < 1) {
    return ctx_.Refuse("seeds: give at least 1 seed");
  }
  // What a reset would run with, without the seed: the seeds are the Monte Carlo's.
  std::vector<sim::Override> sets;
  for (const sim::Override& o : ctx_.session().EffectiveOverrides())
    if (o.key != "seed") sets.push_back(o);
  std::vector<std::uint64_t> seeds;
  for (int s = 1; s <= n; ++s) seeds.push_back(static_cast<std::uint64_t>(s));
  RunValues loaded, values;
  for (const sim::Param& p : ctx_.session().loaded_params().all()) {
    loaded.emplace_back(p.key, p.Text());
    values.emplace_back(p.key, ctx_.session().EffectiveValue(p.key));
  }
  try {
    // One core stays with the window.
    const int threads = std::max(1, sim::TaskPool::HardwareThreads() - 1);
    mc_ = MonteCarloState();
    mc_.run = std::make_unique<sim::MonteCarlo>(ctx_.session().source(), sets, seeds, threads);
  } catch (const std::exception& e) {
    mc_ = MonteCarloState();
    return ctx_.Refuse(std::string("seeds: ") + e.what());
  }
  mc_.seeds = n;
  mc_.values = values;
  mc_.settings = sim::DescribeDifferences(loaded, values, ctx_.session().loaded_params());
  if (mc_.settings.empty()) mc_.settings = "as loaded";
  Note("seeds", std::to_string(n) + " seeds, " + mc_.settings);
  ctx_.SetStatus("Monte Carlo: " + std::to_string(n) + " seeds of " + mc_.settings);
  return "";
}

std::string ComparePanel::CmdCancelSeeds() {
  if (!mc_.run || mc_.run->finished()) {
    return ctx_.Refuse("cancel-seeds: no Monte Carlo is running");
  }
  mc_.run->Cancel();
  ctx_.SetStatus("Monte Carlo: cancelling (the runs under way stop at their next step)");
  return "";
}

bool ComparePanel::WriteMonteCarlo(const std::string& dir) {
  if (!mc_.tables) return false;
  const std::string out = (fs::path(dir) / "montecarlo").string();
  sim::PrepareOutputDir(out);
  sim::WriteSweepTables(out, *mc_.tables);
  return true;
}

}  // namespace formsim::app
