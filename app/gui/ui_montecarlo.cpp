/// \file "Run N seeds": the current settings (what a reset would run with) over seeds 1..N in
/// background threads, exactly the runs of `formsim sweep SCENARIO --set <settings> --seeds
/// 1..N` (sim::MonteCarlo on the sweep engine): the window stays responsive, a progress bar
/// shows the runs done, Cancel stops what has not started. The spread goes onto every time plot
/// as bands and the metrics' mean ± σ into the comparison table; with --out the tables are
/// written as the sweep writes them.
#include <filesystem>

#include "app/gui/ui.hpp"
#include "sim/core/run_output.hpp"
#include "sim/study/sweep_tables.hpp"
#include "sim/core/task_pool.hpp"

namespace fs = std::filesystem;

namespace formsim::app {

std::string AppUi::CmdSeeds(int n) {
  if (mc_.run && !mc_.run->finished()) {
    const std::string why = "seeds: a Monte Carlo is running (cancel it first)";
    SetStatus(why, true);
    return why;
  }
  if (n < 1) {
    const std::string why = "seeds: give at least 1 seed";
    SetStatus(why, true);
    return why;
  }
  // What a reset would run with, without the seed: the seeds are the Monte Carlo's.
  std::vector<sim::Override> sets;
  for (const sim::Override& o : session_->EffectiveOverrides())
    if (o.key != "seed") sets.push_back(o);
  std::vector<std::uint64_t> seeds;
  for (int s = 1; s <= n; ++s) seeds.push_back(static_cast<std::uint64_t>(s));
  RunValues loaded, values;
  for (const sim::Param& p : session_->loaded_params().all()) {
    loaded.emplace_back(p.key, p.Text());
    values.emplace_back(p.key, session_->EffectiveValue(p.key));
  }
  try {
    // One core stays with the window.
    const int threads = std::max(1, sim::TaskPool::HardwareThreads() - 1);
    mc_ = MonteCarloState();
    mc_.run = std::make_unique<sim::MonteCarlo>(session_->source(), sets, seeds, threads);
  } catch (const std::exception& e) {
    mc_ = MonteCarloState();
    SetStatus(std::string("seeds: ") + e.what(), true);
    return state_.status;
  }
  mc_.seeds = n;
  mc_.values = values;
  mc_.settings = sim::DescribeDifferences(loaded, values, session_->loaded_params());
  if (mc_.settings.empty()) mc_.settings = "as loaded";
  sim::SessionEvent note;
  note.kind = sim::SessionEvent::Kind::kNote;
  note.key = "seeds";
  note.value = std::to_string(n) + " seeds, " + mc_.settings;
  note.step = session_->exp().steps();
  record_.Add(note);
  SetStatus("Monte Carlo: " + std::to_string(n) + " seeds of " + mc_.settings);
  return "";
}

std::string AppUi::CmdCancelSeeds() {
  if (!mc_.run || mc_.run->finished()) {
    const std::string why = "cancel-seeds: no Monte Carlo is running";
    SetStatus(why, true);
    return why;
  }
  mc_.run->Cancel();
  SetStatus("Monte Carlo: cancelling (the runs under way stop at their next step)");
  return "";
}

bool AppUi::WriteMonteCarlo(const std::string& dir) {
  if (!mc_.tables) return false;
  const std::string out = (fs::path(dir) / "montecarlo").string();
  sim::PrepareOutputDir(out);
  sim::WriteSweepTables(out, *mc_.tables);
  return true;
}

}  // namespace formsim::app
