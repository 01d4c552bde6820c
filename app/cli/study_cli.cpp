#include "app/cli/study_cli.hpp"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "app/cli/cli_messages.hpp"
#include "app/export/figure_titles.hpp"
#include "app/export/study_figures.hpp"
#include "app/export/tune_figures.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/stop_signal.hpp"
#include "sim/core/wall_clock.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/scenario/scenario_save.hpp"
#include "sim/study/scenario_set.hpp"
#include "sim/study/sweep.hpp"
#include "sim/study/sweep_tables.hpp"
#include "sim/study/tune.hpp"
#include "sim/study/tune_history.hpp"
#include "sim/study/tune_request.hpp"
#include "sim/study/tune_validation.hpp"

namespace fs = std::filesystem;

namespace formsim::app {

namespace {

using sim::WallSeconds;

// "[=====>     ] 37/200 runs, 1 failed, 0:42 left" on stderr, only on a terminal and not -q;
// redrawn at most ten times a second.
class RunsBar {
 public:
  RunsBar(bool enabled, std::size_t total)
      : enabled_(enabled && isatty(STDERR_FILENO)), total_(total) {}
  void Update(std::size_t done, std::size_t failed, bool force = false) {
    if (!enabled_ || total_ == 0) return;
    const double now = WallSeconds();
    if (!force && done < total_ && now - last_ < 0.1) return;  // the last state always shows
    last_ = now;
    const double f = static_cast<double>(done) / static_cast<double>(total_);
    const int width = 30, filled = static_cast<int>(f * width);
    std::string left = "…";
    if (done > 0)
      left = sim::FormatClock((now - start_) / static_cast<double>(done) * static_cast<double>(total_ - done));
    sim::Print(stderr, "\r[%s%s] %zu/%zu runs, %zu failed, %s left   ",
               std::string(filled, '=').c_str(), std::string(width - filled, ' ').c_str(), done,
               total_, failed, left.c_str());
    std::fflush(stderr);
  }
  void Done() {
    if (enabled_) ClearStatusLine();
  }

 private:
  bool enabled_;
  std::size_t total_;
  double start_ = WallSeconds(), last_ = 0;
};

// A word for a POSIX shell: as is when it is safe, else single-quoted.
std::string ShellWord(const std::string& s) {
  bool plain = !s.empty();
  for (char c : s)
    plain = plain && (std::isalnum(static_cast<unsigned char>(c)) ||
                      std::string("/._-=:,+@%").find(c) != std::string::npos);
  if (plain) return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string SelfExe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("formsim") : p.string();
}

int CheckJobs(int jobs, const std::string& flag) {
  if (jobs == 0) return sim::TaskPool::HardwareThreads();
  if (jobs < 0 || jobs > 1024) throw std::runtime_error(flag + " must be in 1 ... 1024");
  return jobs;
}

// A 64-bit seed flag's value, read here rather than by CLI11 (which wrapped values beyond
// 2^64-1 silently).
std::uint64_t ParseSeedFlag(const std::string& text, const std::string& flag) {
  std::uint64_t v = 0;
  if (!sim::ParseUint64(text, &v))
    throw std::runtime_error(flag + " '" + text + "': expected an integer in 0 ... 2^64-1");
  return v;
}

std::string JoinWith(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

// "wrote A, B, C in OUT": the last line of sweep, sweep collect and tune.
void PrintStudyWrote(const std::vector<std::string>& files, const std::string& out) {
  std::fputs(("wrote " + JoinWith(files, ", ") + " in " + out + "\n").c_str(), stdout);
}

// Tables, ranking and figure of a sweep from its records (a whole sweep, or one shard's part).
// Returns the exit code: 2 when --metric names no metric (the tables are written first).
int WriteSweepOutputs(const sim::SweepDefinition& def, const std::vector<sim::SweepRecord>& records,
                      const std::string& out, std::string metric, SweepBand band, TitleMode titles,
                      bool figures, bool quiet) {
  const sim::SweepTables tables = sim::BuildSweepTables(def, records);
  std::vector<std::string> wrote = sim::WriteSweepTables(out, tables);
  int rc = 0;
  if (figures && !tables.metrics.empty()) {
    if (metric.empty()) metric = tables.metrics[sim::DefaultMetric(tables)];
    const int m = tables.MetricIndex(metric);
    if (m < 0) {
      PrintCliError("--metric '" + metric + "': no such metric in the runs (similar: " +
                    sim::SimilarMetrics(tables.metrics, metric) + "); the tables were written");
      rc = 2;
    } else {
      const std::string ranking = "ranking_" + metric + ".txt";
      sim::WriteFileAtomic((fs::path(out) / ranking).string(), sim::RankingText(def, tables, m));
      wrote.push_back(ranking);
      PlotData fig;
      const bool single = SweepFigure(def, tables, records, m, &fig, band);
      int columns = 2;
      std::vector<PlotData> panels;
      if (!single)
        panels = def.MultiScenario() ? SweepScenarioPanels(def, tables, records, m, band, &columns)
                                     : SweepPanels(def, tables, m, band);
      fig.title = TitleFor(fig.title, titles);
      for (PlotData& p : panels) p.title = TitleFor(p.title, titles);
      if (single || !panels.empty()) {
        const std::string name = "plot_" + metric + ".png";
        try {
          if (single)
            WriteFigurePng(fig, (fs::path(out) / name).string());
          else
            WritePanelsPng(panels, (fs::path(out) / name).string(), 640, 440, columns);
          wrote.push_back(name);
        } catch (const std::exception& e) {
          PrintCliError(std::string("the figure could not be written (the tables were): ") +
                        e.what());
          rc = 4;
        }
      }
    }
  }
  if (!quiet) PrintStudyWrote(wrote, out);
  return rc;
}

// Records a power cut left empty or cut short are removed (and so run again); says so on stderr.
void RemoveDamaged(const std::string& out, const std::vector<std::size_t>& runs, bool quiet) {
  for (const std::string& p : sim::RemoveDamagedRecords(out, runs))
    if (!quiet)
      std::fputs(("formsim: " + p + " was cut short (a power cut?); it runs again\n").c_str(),
                 stderr);
}

std::vector<sim::SweepRecord> RecordsOf(const std::string& dir, const sim::SweepDefinition& def,
                                        const std::vector<std::size_t>& runs) {
  const std::set<std::size_t> want(runs.begin(), runs.end());
  std::vector<sim::SweepRecord> out;
  for (sim::SweepRecord& r : sim::ReadRecords(dir, def))
    if (want.count(r.run)) out.push_back(std::move(r));
  return out;
}

}  // namespace

StudyCommands::StudyCommands(CLI::App& app) {
  AddSweepCommands(app);
  AddTuneCommand(app);
}

void StudyCommands::AddSweepCommands(CLI::App& app) {
  sweep_ = app.add_subcommand("sweep",
                              "Run a scenario for every combination of varied tunables and seeds");
  sweep_->add_option("scenario", scenario_, "Scenario name (see `formsim list`) or YAML path");
  sweep_
      ->add_option("--scenario", scenarios_,
                   "One more scenario, repeatable, or @FILE (one per line): every scenario runs "
                   "every point and seed; each must have every --vary key. The tables get a "
                   "scenario column and aggregate_over_scenarios.csv")
      ->take_all();
  sweep_
      ->add_option("--vary", vary_,
                   "KEY=SPEC: a list 0.1,0.2,0.4 (names for enums, 'all'), a range LO:HI:N, "
                   "log:LO:HI:N, or random:N[:LO:HI] (Latin hypercube in the declared bounds)")
      ->take_all();
  sweep_->add_option("--seeds", seeds_,
                     "Seeds: 1..20, 1,2,5 or a mixture (default: the scenario's)");
  sweep_->add_option("--set", sets_, "Fixed override for every run: path.to.key=value")->take_all();
  sweep_->add_option("--jobs,-j", jobs_, "Runs at once (default: every core)");
  sweep_->add_option("--out", out_, "Output folder (default out/sweep_<scenario>)");
  sweep_->add_option("--metric", metric_,
                     "Metric the figure and ranking show: a dotted path under results in "
                     "summary.json, as in the columns of runs.csv (default: the first)");
  sweep_->add_option("--band", band_,
                     "Spread shaded around the mean in the figure: sd (± 1σ), ci95 (95% "
                     "confidence interval of the mean, Student t; default) or minmax");
  sweep_->add_flag("--resume", resume_,
                   "Continue the sweep in --out: run only what is not recorded");
  sweep_->add_option("--shard", shard_, "Run only the K-th of N slices of the runs: K/N");
  sweep_->add_flag(
      "--print-jobs", print_jobs_,
      "Print one self-contained command line per run (GNU parallel, Slurm, HTCondor) and exit");
  sweep_->add_option("--run", run_, "Run only run I and record it (what --print-jobs lines do)");
  sweep_->add_option("--max-runs", max_runs_,
                     "Allow a sweep of up to N runs (default 100000, at most 10000000)");
  sweep_->add_option("--sample-seed", sample_seed_,
                     "Seed of the Latin hypercube of random:N (default 1)");
  sweep_->add_flag("--no-figures", no_figures_, "Write the tables only");
  sweep_->add_option("--titles", titles_, TitleModeHelp());
  sweep_->add_flag("--quiet,-q", quiet_, "Print nothing but errors");

  collect_ =
      sweep_->add_subcommand("collect", "Merge the results of sweep shards into one set of tables");
  collect_->add_option("dirs", collect_dirs_, "Output folders of the shards")->required();
  collect_->add_option("--out", collect_out_, "Folder for the merged sweep")->required();
  collect_->add_option("--metric", collect_metric_, "Metric the figure and ranking show");
  collect_->add_option("--band", collect_band_,
                       "Spread shaded around the mean: sd, ci95 (default) or minmax");
  collect_->add_option("--titles", collect_titles_, TitleModeHelp());
  collect_->add_flag("--quiet,-q", collect_quiet_, "Print nothing but errors");
}

void StudyCommands::AddTuneCommand(CLI::App& app) {
  tune_ = app.add_subcommand("tune", "Optimise tunables for a metric averaged over seeds (NLopt)");
  tune_->add_option("scenario", tune_scenario_, "Scenario name or YAML path");
  tune_
      ->add_option("--scenario", tune_scenarios_,
                   "One more scenario, repeatable, or @FILE (one per line): the objective folds "
                   "every scenario's runs; each must have every tuned key")
      ->take_all();
  tune_->add_option("--over", over_,
                    "How the runs of an evaluation (every scenario x seed) fold into the "
                    "objective and the constraints: mean (default), max (the worst case) or "
                    "quantile:Q");
  tune_
      ->add_option("--param", params_,
                   "KEY or KEY:LO:HI (default bounds: the declared slider range); integer "
                   "keys, flags and choices too (KEY alone), searched by a global stage")
      ->take_all()
      ->required();
  tune_
      ->add_option("--metric", tune_metric_,
                   "Metric to minimise: PATH or a weighted sum 'a.b + 10*c.d'")
      ->required();
  tune_->add_option("--seeds", tune_seeds_,
                    "Seeds averaged per evaluation: 1..5 (default: the scenario's)");
  tune_->add_option("--budget", budget_, "Evaluations at most (default 60)");
  tune_->add_option("--method,--algorithm", algorithm_,
                    "local: bobyqa, neldermead, cobyla; global: direct-l, crs2, mlsl, isres; or "
                    "GLOBAL+LOCAL, a global stage (40% of the budget) then a local polish "
                    "(default direct-l+bobyqa)");
  tune_
      ->add_option("--constraint", constraints_,
                   "METRIC<=VALUE or METRIC>=VALUE on the mean over the seeds, repeatable; "
                   "best.yaml is the best point that meets them all")
      ->take_all();
  tune_->add_option("--holdout", holdout_,
                    "Seeds never searched (6..25): the start and the best point run on them; "
                    "writes validation.csv");
  tune_->add_flag("--resume", tune_resume_,
                  "Continue the tune in --out: its recorded evaluations are replayed into the "
                  "optimiser, which then goes on as if it had never stopped");
  tune_->add_option("--search-seed", search_seed_,
                    "Seed of the random methods (crs2, mlsl, isres; default 1)");
  tune_->add_option("--set", tune_sets_, "Fixed override for every run: path.to.key=value")
      ->take_all();
  tune_->add_option("--jobs,-j", tune_jobs_, "Runs at once (default: every core)");
  tune_->add_option("--out", tune_out_, "Output folder (default out/tune_<scenario>)");
  tune_->add_option("--titles", tune_titles_, TitleModeHelp());
  tune_->add_flag("--quiet,-q", tune_quiet_, "Print nothing but errors");
}

bool StudyCommands::parsed() const {
  return sweep_->parsed() || tune_->parsed();
}

int StudyCommands::Run() {
  if (collect_->parsed()) return Collect();
  if (sweep_->parsed()) return Sweep();
  return Tune();
}

// The sweep as its flags plan it, everything refused before anything runs.
struct StudyCommands::SweepPlan {
  SweepBand band;
  TitleMode titles;
  std::vector<sim::ScenarioSource> sources;
  std::string file;  ///< the first scenario's
  sim::SweepDefinition def;
  std::string out;
  int shard_k = 1, shard_n = 1;
  int jobs = 1;
  std::vector<std::size_t> mine;  ///< the runs of this shard (all of them without --shard)
};

StudyCommands::SweepPlan StudyCommands::PlanSweep() const {
  if (scenario_.empty() && scenarios_.empty())
    throw std::runtime_error(
        "formsim sweep: give a scenario (or `sweep collect DIR... --out DIR`)");
  SweepPlan p;
  p.band = ParseSweepBand(band_);
  p.titles = ParseTitleMode(titles_, "--titles");
  p.sources = sim::ReadScenarioSet(scenario_, scenarios_, "formsim sweep");
  p.file = p.sources.front().file();
  // Given but empty (`--seeds ''`) is refused, never read as "the scenario's seed".
  const std::vector<std::uint64_t> seeds =
      sweep_->count("--seeds") == 0 ? std::vector<std::uint64_t>{} : sim::ParseSeeds(seeds_);
  if (max_runs_ < 1 || max_runs_ > static_cast<long long>(sim::kMaxSweepRuns))
    throw std::runtime_error("--max-runs " + std::to_string(max_runs_) + ": must be in 1 ... " +
                             std::to_string(sim::kMaxSweepRuns));
  if (sweep_->count("--run") > 0 && run_ < 0)
    throw std::runtime_error("--run " + std::to_string(run_) +
                             ": a run number is 0 or more (runs are numbered 0 ... N-1)");
  p.def = sim::DefineSweep(p.sources, sim::CliOverrides(sets_, -1), vary_, seeds,
                           ParseSeedFlag(sample_seed_, "--sample-seed"),
                           static_cast<std::size_t>(max_runs_));
  p.out = !out_.empty()           ? out_
          : p.sources.size() == 1 ? "out/sweep_" + sim::ScenarioStem(p.sources[0])
                                  : "out/sweep_" + sim::ScenarioStem(p.sources[0]) + "_" +
                                        std::to_string(p.sources.size()) + "_scenarios";
  if (!shard_.empty()) sim::ParseShard(shard_, &p.shard_k, &p.shard_n);
  p.jobs = CheckJobs(jobs_, "--jobs");
  p.mine = sim::ShardRuns(p.def.runs(), p.shard_k, p.shard_n);
  return p;
}

int StudyCommands::Sweep() {
  const SweepPlan plan = PlanSweep();
  if (sweep_->count("--run") > 0) return SweepOneRun(plan);
  if (print_jobs_) return PrintSweepJobs(plan);
  return RunPlannedSweep(plan);
}

// --run I: one job line, this run only, recorded like any other.
int StudyCommands::SweepOneRun(const SweepPlan& plan) {
  const std::string& out = plan.out;
  if (static_cast<std::size_t>(run_) >= plan.def.runs())
    throw std::runtime_error("--run " + std::to_string(run_) + ": the sweep has runs 0 ... " +
                             std::to_string(plan.def.runs() - 1));
  sim::WriteManifest(out, plan.def);
  const std::size_t r = static_cast<std::size_t>(run_);
  RemoveDamaged(out, {r}, quiet_);
  if (sim::PendingRuns(out, {r}).empty()) {
    if (!quiet_) sim::Print(stdout, "run %zu is recorded already in %s\n", r, out.c_str());
    return 0;
  }
  sim::InstallStopSignals();
  const auto rec =
      sim::RunSweepRun(plan.sources, plan.def, r, [] { return sim::StopSignal() != 0; });
  if (!rec) return 128 + sim::StopSignal();
  sim::WriteRecord(out, plan.def, *rec);
  sim::SyncFileSystem(out);
  if (!quiet_)
    sim::Print(stdout, "run %zu: %s%s\n", r, rec->status.c_str(),
               rec->message.empty() ? "" : (": " + rec->message).c_str());
  return 0;
}

// --print-jobs: one self-contained command line per pending run of this shard.
int StudyCommands::PrintSweepJobs(const SweepPlan& plan) {
  const sim::SweepDefinition& def = plan.def;
  sim::WriteManifest(plan.out, def);
  // The scenarios by absolute path (a list file may change or move; the lines must not).
  std::string common = ShellWord(SelfExe()) + " sweep";
  if (plan.sources.size() == 1)
    common += " " + ShellWord(fs::absolute(plan.file).string());
  else
    for (const sim::ScenarioSource& src : plan.sources)
      common += " --scenario " + ShellWord(fs::absolute(src.file()).string());
  for (const std::string& v : vary_) common += " --vary " + ShellWord(v);
  for (const std::string& s : sets_) common += " --set " + ShellWord(s);
  if (!seeds_.empty()) common += " --seeds " + ShellWord(seeds_);
  if (def.sample_seed != 1) common += " --sample-seed " + std::to_string(def.sample_seed);
  if (sweep_->count("--max-runs") > 0) common += " --max-runs " + std::to_string(max_runs_);
  common += " --out " + ShellWord(fs::absolute(plan.out).string()) + " -q --run ";
  RemoveDamaged(plan.out, plan.mine, false);
  for (std::size_t r : sim::PendingRuns(plan.out, plan.mine))
    std::fputs((common + std::to_string(r) + "\n").c_str(), stdout);
  return 0;
}

// "sweep of FILE: P points x S seeds = N runs, ..., J jobs" on stdout.
void StudyCommands::PrintSweepHeader(const SweepPlan& plan, std::size_t pending) const {
  const sim::SweepDefinition& def = plan.def;
  std::string line;
  if (plan.sources.size() == 1) {
    line = "sweep of " + plan.file + ": ";
  } else {
    std::vector<std::string> names;
    for (const sim::ScenarioSource& src : plan.sources) names.push_back(sim::ScenarioStem(src));
    line = sim::Sprintf("sweep of %zu scenarios (%s): %zu scenarios x ", plan.sources.size(),
                        JoinWith(names, ", ").c_str(), plan.sources.size());
  }
  sim::AppendSprintf(line, "%zu point%s x %zu seed%s = %zu runs", def.points.size(),
                     def.points.size() == 1 ? "" : "s", def.seeds.size(),
                     def.seeds.size() == 1 ? "" : "s", def.runs());
  if (plan.shard_n > 1)
    sim::AppendSprintf(line, ", shard %d/%d: %zu runs", plan.shard_k, plan.shard_n,
                       plan.mine.size());
  if (pending != plan.mine.size())
    sim::AppendSprintf(line, ", %zu recorded already", plan.mine.size() - pending);
  sim::AppendSprintf(line, ", %d jobs\n", plan.jobs);
  std::fputs(line.c_str(), stdout);
  std::fflush(stdout);
}

// The runs of this shard not recorded yet, on all cores, then the tables and the figure.
int StudyCommands::RunPlannedSweep(const SweepPlan& plan) {
  const sim::SweepDefinition& def = plan.def;
  const std::string& out = plan.out;
  if (sim::HasManifest(out) && !resume_) {
    sim::WriteManifest(out, def);  // throws, saying how, when it is another sweep
    const std::size_t have =
        def.runs() - sim::PendingRuns(out, sim::ShardRuns(def.runs(), 1, 1)).size();
    throw std::runtime_error(
        "'" + out + "' holds a sweep already (" + std::to_string(have) +
        " runs recorded); add --resume to continue it, or choose another --out");
  }
  sim::WriteManifest(out, def);
  RemoveDamaged(out, plan.mine, quiet_);
  const std::vector<std::size_t> pending = sim::PendingRuns(out, plan.mine);
  if (!quiet_) PrintSweepHeader(plan, pending.size());
  sim::InstallStopSignals();
  sim::TaskPool pool(plan.jobs);
  RunsBar bar(!quiet_, pending.size());
  const double t0 = WallSeconds();
  const sim::SweepProgress progress = sim::RunSweep(
      plan.sources, def, pending, pool,
      [&](const sim::SweepRecord& rec, const sim::SweepProgress& p) {
        sim::WriteRecord(out, def, rec);
        bar.Update(p.done, p.failed);
      },
      [] { return sim::StopSignal() != 0; });
  bar.Done();
  sim::SyncFileSystem(out);  // the records, synced together
  const double wall = WallSeconds() - t0;
  if (sim::StopSignal() != 0) {
    sim::Print(stderr,
               "formsim: sweep interrupted by %s: %zu of %zu runs recorded in %s; add --resume "
               "to finish it\n",
               sim::StopSignalName(sim::StopSignal()).c_str(),
               plan.mine.size() - pending.size() + progress.done, plan.mine.size(), out.c_str());
    return 128 + sim::StopSignal();
  }
  if (!quiet_) {
    std::string line = sim::Sprintf(
        "%zu runs in %.2f s wall (%.1f ms per run on %d jobs)", progress.done, wall,
        progress.done ? 1e3 * wall / static_cast<double>(progress.done) : 0.0, plan.jobs);
    if (progress.failed)
      sim::AppendSprintf(line, ", %zu failed (status and message in runs.csv)", progress.failed);
    std::fputs((line + "\n").c_str(), stdout);
  }
  const bool whole = plan.shard_n == 1;
  const int rc = WriteSweepOutputs(def, RecordsOf(out, def, plan.mine), out, metric_, plan.band,
                                   plan.titles, whole && !no_figures_, quiet_);
  if (!whole && !quiet_)
    sim::Print(stdout,
               "shard %d/%d done; merge the shards with: formsim sweep collect DIR... --out DIR\n",
               plan.shard_k, plan.shard_n);
  return rc;
}

int StudyCommands::Collect() {
  const SweepBand band = ParseSweepBand(collect_band_);
  const TitleMode titles = ParseTitleMode(collect_titles_, "--titles");
  std::vector<sim::SweepDefinition> defs;
  for (const std::string& d : collect_dirs_) defs.push_back(sim::ReadManifest(d));
  const sim::SweepDefinition& def = defs.front();
  for (std::size_t i = 1; i < defs.size(); ++i)
    if (defs[i].id != def.id)
      throw std::runtime_error("'" + collect_dirs_[i] + "' holds another sweep than '" +
                               collect_dirs_[0] +
                               "' (a different scenario text, keys, values or seeds)");
  // Every run exactly once; a run recorded by two shards must say the same.
  std::map<std::size_t, sim::SweepRecord> all;
  for (const std::string& d : collect_dirs_)
    for (sim::SweepRecord& r : sim::ReadRecords(d, def)) {
      const auto it = all.find(r.run);
      if (it != all.end() && sim::RecordText(def, it->second) != sim::RecordText(def, r))
        throw std::runtime_error("run " + std::to_string(r.run) +
                                 " is recorded differently in two folders (" + d + ")");
      all.emplace(r.run, std::move(r));
    }
  if (all.size() != def.runs()) {
    std::string missing;
    int shown = 0;
    for (std::size_t r = 0; r < def.runs() && shown < 10; ++r)
      if (!all.count(r)) missing += (shown++ ? ", " : "") + std::to_string(r);
    throw std::runtime_error("the folders hold " + std::to_string(all.size()) + " of " +
                             std::to_string(def.runs()) + " runs (missing: " + missing +
                             (def.runs() - all.size() > 10 ? ", ..." : "") +
                             "); finish the shards (--resume) before collecting");
  }
  sim::WriteManifest(collect_out_, def);
  std::vector<sim::SweepRecord> records;
  for (auto& [run, rec] : all) {
    if (!sim::PendingRuns(collect_out_, {run}).empty()) sim::WriteRecord(collect_out_, def, rec);
    records.push_back(std::move(rec));
  }
  if (!collect_quiet_)
    sim::Print(stdout, "collected %zu runs from %zu folders\n", records.size(),
               collect_dirs_.size());
  return WriteSweepOutputs(def, records, collect_out_, collect_metric_, band, titles, true,
                           collect_quiet_);
}

namespace {

// The evaluations recorded in `out` for --resume (none for a new tune). A folder holding a tune
// is refused without --resume, and with it when its manifest is another tune's.
std::vector<sim::TuneEvaluation> TuneRecorded(const std::string& out,
                                              const std::vector<sim::ScenarioSource>& sources,
                                              const sim::TuneSettings& s, bool resume) {
  const fs::path manifest = fs::path(out) / "tune.manifest";
  std::error_code ec;
  if (!fs::exists(manifest, ec)) return {};
  std::ifstream in(manifest);
  std::stringstream text;
  text << in.rdbuf();
  const fs::path history = fs::path(out) / "history.csv";
  std::ifstream h(history);
  std::stringstream rows;
  rows << h.rdbuf();
  if (!resume)
    throw std::runtime_error("'" + out + "' holds a tune already; add --resume to continue it, "
                             "or choose another --out");
  const std::string want = sim::TuneManifest(sources, s);
  if (text.str() != want) {
    // Name the first line that differs.
    std::stringstream a(text.str()), b(want);
    std::string la, lb;
    while (std::getline(a, la) && std::getline(b, lb) && la == lb) {
    }
    throw std::runtime_error("--resume: '" + out + "' holds another tune (it has '" + la +
                             "', this one '" + lb + "')");
  }
  return sim::ReadTuneHistory(rows.str(), s);
}

// history.csv as the tune goes: the recorded rows rewritten whole (a torn last line dropped),
// then one row appended and flushed per new evaluation, so a kill keeps every finished one.
class TuneHistoryFile {
 public:
  TuneHistoryFile(std::string path, const sim::TuneSettings& s,
                  const std::vector<sim::TuneStage>& plan,
                  const std::vector<sim::TuneEvaluation>& recorded)
      : path_(std::move(path)), s_(s), plan_(plan), replayed_(recorded.size()) {
    std::string text = sim::TuneHistoryHeader(s);
    for (const sim::TuneEvaluation& e : recorded) text += Row(e);
    sim::WriteFileAtomic(path_, text);
    best_ = std::numeric_limits<double>::infinity();  // counted again as the replay comes
    file_ = std::fopen(path_.c_str(), "ab");
    if (file_ == nullptr)
      throw std::runtime_error("cannot append to '" + path_ + "': " + std::strerror(errno));
  }
  ~TuneHistoryFile() { Close(); }
  TuneHistoryFile(const TuneHistoryFile&) = delete;
  TuneHistoryFile& operator=(const TuneHistoryFile&) = delete;

  void Add(const sim::TuneEvaluation& e) {
    const std::string row = Row(e);
    if (e.index <= replayed_ || file_ == nullptr) return;  // on disk already
    ++added_;
    if (std::fputs(row.c_str(), file_) < 0 || std::fflush(file_) != 0) {
      const std::string why = std::strerror(errno);
      PrintCliError("appending to " + path_ + ": " + why +
                    " (the whole file is written again at the end)");
      std::fclose(file_);
      file_ = nullptr;
    }
  }
  void Close() {
    if (file_ != nullptr) std::fclose(file_);
    file_ = nullptr;
  }
  /// New rows appended so far.
  std::size_t added() const { return added_; }

 private:
  std::string Row(const sim::TuneEvaluation& e) {
    if (e.feasible()) best_ = std::min(best_, e.objective);
    return sim::TuneHistoryRow(s_, plan_, e, best_);
  }
  std::string path_;
  const sim::TuneSettings& s_;
  const std::vector<sim::TuneStage>& plan_;
  std::size_t replayed_, added_ = 0;
  double best_ = std::numeric_limits<double>::infinity();
  std::FILE* file_ = nullptr;
};

// ", search seed N" when a stage of the plan draws random numbers, else "".
std::string TuneSeedNote(const sim::TuneDefinition& def) {
  bool random = false;
  for (const sim::TuneStage& st : def.plan) random = random || sim::IsRandomMethod(st.method);
  return random ? ", search seed " + std::to_string(def.settings.search_seed) : std::string();
}

// "tune FILE: N tunables, C constraints, PLAN, S seeds, J jobs" on stdout.
void PrintTuneHeader(const sim::TuneDefinition& def, const std::string& seed_note, int jobs) {
  const sim::TuneSettings& s = def.settings;
  const std::string file = def.sources.front().file();
  std::string what = file;
  if (def.sources.size() > 1)
    what = std::to_string(def.sources.size()) + " scenarios (" + file + ", ...), " + s.over.Text() +
           " over them";
  else if (s.over.kind != sim::TuneOver::Kind::kMean)
    what += ", " + s.over.Text() + " over the seeds";
  sim::Print(stdout, "tune %s: %zu tunables, %zu constraint%s, %s%s, %zu seeds, %d jobs\n",
             what.c_str(), s.params.size(), s.constraints.size(),
             s.constraints.size() == 1 ? "" : "s", sim::PlanText(def.plan).c_str(),
             seed_note.c_str(), s.seeds.size(), jobs);
  std::fflush(stdout);
}

// The search, each evaluation appended to history.csv as it comes (and shown on a terminal).
// Refused at evaluation 1 (a metric the runs do not have), it leaves no tune to resume.
sim::TuneResult SearchTune(const sim::TuneDefinition& def, sim::TaskPool& pool,
                           TuneHistoryFile& history,
                           const std::vector<sim::TuneEvaluation>& recorded, const std::string& out,
                           bool tty) {
  sim::TuneResult r;
  try {
    r = sim::RunTune(
        def.sources, def.settings, pool,
        [&](const sim::TuneEvaluation& e, const sim::TuneEvaluation& best) {
          history.Add(e);
          if (tty)
            sim::Print(stderr, "\revaluation %zu/%d  objective %-12.6g best %-12.6g", e.index,
                       def.settings.budget, e.objective, best.objective);
        },
        [] { return sim::StopSignal() != 0; }, recorded);
  } catch (...) {
    history.Close();
    if (recorded.empty() && history.added() == 0) {
      std::error_code ec;
      fs::remove(fs::path(out) / "tune.manifest", ec);
      fs::remove(fs::path(out) / "history.csv", ec);
    }
    throw;
  }
  if (tty) ClearStatusLine();
  return r;
}

// What the steps after the search share: the tune, its result, the flags they name, what was
// written and the exit code so far.
struct TuneOutcome {
  const sim::TuneDefinition& def;
  const sim::TuneResult& r;
  const std::string& out;
  const std::string& metric;      ///< --metric as given
  const std::string& seeds_flag;  ///< --seeds as given ("": the scenario's seed)
  const std::string& seed_note;   ///< TuneSeedNote
  TitleMode titles;
  bool quiet;
  std::vector<std::string> wrote = {"history.csv"};
  int rc = 0;
};

// best.yaml (the first scenario) and best_<name>.yaml (each other one, with the same values),
// each headed by a comment saying what it is best at.
void WriteTuneBestScenarios(TuneOutcome& o) {
  const sim::TuneSettings& s = o.def.settings;
  const std::vector<sim::ScenarioSource>& sources = o.def.sources;
  const sim::TuneEvaluation& best = o.r.history[o.r.best];
  std::string subject;
  for (const sim::TuneConstraint& c : s.constraints)
    subject += (subject.empty() ? " subject to " : ", ") + c.Text();
  const std::string over = s.over.kind == sim::TuneOver::Kind::kMean ? "mean" : s.over.Text();
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const std::string name =
        i == 0 ? "best.yaml" : "best_" + fs::path(sources[i].file()).stem().string() + ".yaml";
    const std::string path = (fs::path(o.out) / name).string();
    std::string note;
    std::string text =
        sim::TunedScenarioText(sources[i], sim::TuneOverrides(s, best.values), path, &note);
    text = "# formsim tune: " + o.metric + " = " + sim::FormatDouble(best.objective) + " (" + over +
           " over seeds " + (o.seeds_flag.empty() ? std::to_string(s.seeds[0]) : o.seeds_flag) +
           (sources.size() > 1 ? " of " + std::to_string(sources.size()) + " scenarios" : "") +
           ")" + subject + ", evaluation " + std::to_string(best.index) + " of " +
           std::to_string(o.r.history.size()) + ", " + s.algorithm + o.seed_note + "\n" + text;
    sim::WriteFileAtomic(path, text);
    o.wrote.push_back(name);
    if (!note.empty() && !o.quiet) std::fputs(("note: " + note + "\n").c_str(), stdout);
  }
}

// No best point: says how close the closest came (exit 3) or that nothing succeeded (exit 2).
void ReportNoTuneBest(TuneOutcome& o) {
  const sim::TuneSettings& s = o.def.settings;
  if (o.r.history.empty() || o.r.history[o.r.best].failed()) {
    PrintCliError("no evaluation succeeded; no best.yaml (see history.csv)");
    o.rc = 2;
    return;
  }
  // Runs succeeded, but none met every constraint.
  const sim::TuneEvaluation& e = o.r.history[o.r.best];
  std::string broken;
  for (std::size_t k = 0; k < s.constraints.size(); ++k)
    if (s.constraints[k].Violation(e.constraint_means[k]) > 0)
      broken += (broken.empty() ? "" : ", ") + s.constraints[k].path + " = " +
                sim::FormatSignificant(e.constraint_means[k], 4) + " (wanted " +
                (s.constraints[k].at_most ? "<= " : ">= ") +
                sim::FormatDouble(s.constraints[k].bound) + ")";
  PrintCliError("no evaluation meets every --constraint; no best.yaml. Closest: evaluation " +
                std::to_string(e.index) + " with " + broken + " (see history.csv)");
  o.rc = 3;
}

// A figure (titled as --titles asks); a failed one is reported and the others still written.
void WriteTuneFigure(TuneOutcome& o, PlotData data, const std::string& name) {
  try {
    data.title = TitleFor(data.title, o.titles);
    WriteFigurePng(data, (fs::path(o.out) / name).string());
    o.wrote.push_back(name);
  } catch (const std::exception& e) {
    PrintCliError(name + " could not be written: " + e.what());
    o.rc = o.rc ? o.rc : 4;
  }
}

// One row of the start-and-best table.
void PrintTuneRow(const std::string& label, double start, double best) {
  sim::Print(stdout, "%-40s %14.6g %14.6g\n", label.c_str(), start, best);
}

// The start and the best (or closest) point side by side: tunables, objective, constraints.
void PrintTuneTable(const sim::TuneSettings& s, const sim::TuneResult& r, double wall) {
  const sim::TuneEvaluation& first = r.history.front();
  const sim::TuneEvaluation& best = r.history[r.best];
  sim::Print(stdout, "%zu evaluations in %.1f s (%s)\n", r.history.size(), wall,
             r.stop_reason.c_str());
  sim::Print(stdout, "%-40s %14s %14s\n", "", "start", r.has_best() ? "best" : "closest");
  for (std::size_t i = 0; i < s.params.size(); ++i) {
    const sim::TuneParam& p = s.params[i];
    auto value = [&p](double v) { return p.discrete() ? p.Text(v) : sim::FormatSignificant(v, 6); };
    sim::Print(stdout, "%-40s %14s %14s\n", p.key.c_str(), value(first.values[i]).c_str(),
               value(best.values[i]).c_str());
  }
  PrintTuneRow("objective", first.objective, best.objective);
  for (std::size_t k = 0; k < s.constraints.size(); ++k)
    PrintTuneRow(s.constraints[k].Text(), first.constraint_means[k], best.constraint_means[k]);
}

// Held out: the start and the best point on seeds the search never ran (validation.csv, its
// figure and its summary).
void ValidateTuneOnHoldout(TuneOutcome& o, sim::TaskPool& pool) {
  const sim::TuneSettings& s = o.def.settings;
  const auto v =
      sim::ValidateTune(o.def.sources, s, o.r.history.front().values, o.r.history[o.r.best].values,
                        o.def.holdout, pool, [] { return sim::StopSignal() != 0; });
  if (!v) return;
  sim::WriteFileAtomic((fs::path(o.out) / "validation.csv").string(), sim::TuneValidationCsv(*v));
  o.wrote.push_back("validation.csv");
  WriteTuneFigure(o, TuneValidationFigure(*v, s, o.r, o.metric), "validation.png");
  if (!o.quiet) std::fputs(sim::TuneValidationText(*v).c_str(), stdout);
}

}  // namespace

int StudyCommands::Tune() {
  const TitleMode titles = ParseTitleMode(tune_titles_, "--titles");  // before anything runs
  // Everything refused before anything runs: the settings, the plan, the holdout seeds.
  const sim::TuneDefinition def = sim::DefineTune(sim::MakeTuneRequest(
      tune_scenario_, tune_scenarios_, tune_sets_, over_, params_, tune_metric_, constraints_,
      tune_->count("--seeds") > 0 ? std::optional<std::string>(tune_seeds_) : std::nullopt, budget_,
      algorithm_, ParseSeedFlag(search_seed_, "--search-seed"),
      tune_->count("--holdout") > 0 ? std::optional<std::string>(holdout_) : std::nullopt));
  const sim::TuneSettings& s = def.settings;
  const int jobs = CheckJobs(tune_jobs_, "--jobs");
  const std::string out = tune_out_.empty()
                              ? "out/tune_" + fs::path(def.sources.front().file()).stem().string()
                              : tune_out_;
  const std::vector<sim::TuneEvaluation> recorded = TuneRecorded(out, def.sources, s, tune_resume_);
  sim::PrepareOutputDir(out);
  sim::WriteFileAtomic((fs::path(out) / "tune.manifest").string(),
                       sim::TuneManifest(def.sources, s));
  TuneHistoryFile history((fs::path(out) / "history.csv").string(), s, def.plan, recorded);
  if (!tune_quiet_ && !recorded.empty())
    sim::Print(stdout, "resuming: %zu evaluations recorded in %s are replayed\n", recorded.size(),
               out.c_str());
  sim::InstallStopSignals();
  sim::TaskPool pool(jobs);
  const std::string seed_note = TuneSeedNote(def);
  if (!tune_quiet_) PrintTuneHeader(def, seed_note, jobs);
  const double t0 = WallSeconds();
  const sim::TuneResult r =
      SearchTune(def, pool, history, recorded, out, !tune_quiet_ && isatty(STDERR_FILENO));
  const double wall = WallSeconds() - t0;

  // history.csv first, whole and synced (the rows were appended as they came): whatever happens
  // next, every evaluation is on disk.
  history.Close();
  sim::WriteFileAtomic((fs::path(out) / "history.csv").string(), sim::TuneHistoryCsv(s, r));
  TuneOutcome o{def, r, out, tune_metric_, tune_seeds_, seed_note, titles, tune_quiet_};
  if (r.has_best())
    WriteTuneBestScenarios(o);
  else
    ReportNoTuneBest(o);
  WriteTuneFigure(o, TuneConvergenceFigure(s, r, tune_metric_), "convergence.png");
  if (s.params.size() == 2)
    WriteTuneFigure(o, TuneLandscapeFigure(s, r, tune_metric_), "landscape.png");
  if (!tune_quiet_ && !r.history.empty()) PrintTuneTable(s, r, wall);
  if (!def.holdout.empty() && r.has_best() && sim::StopSignal() == 0)
    ValidateTuneOnHoldout(o, pool);
  if (!tune_quiet_ && !r.history.empty()) PrintStudyWrote(o.wrote, out);
  if (sim::StopSignal() != 0) {
    sim::Print(
        stderr,
        "formsim: tune interrupted by %s after %zu evaluations; the best so far was written\n",
        sim::StopSignalName(sim::StopSignal()).c_str(), r.history.size());
    return 128 + sim::StopSignal();
  }
  return o.rc;
}

}  // namespace formsim::app
