#include "app/cli/reproduce_cli.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/cli/cli_messages.hpp"
#include "app/cli/progress.hpp"
#include "app/export/figure_data.hpp"
#include "app/export/figure_export.hpp"
#include "app/export/figure_titles.hpp"
#include "app/export/study_figures.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/stop_signal.hpp"
#include "sim/study/reproduction.hpp"
#include "sim/study/reproduction_registry.hpp"
#include "sim/study/sweep_spec.hpp"

namespace fs = std::filesystem;

namespace formsim::app {

namespace {

// "formation, agv, inspection or velocity": the registered papers.
std::string PaperNames() {
  const auto& papers = sim::ReproPapers();
  std::string out;
  for (std::size_t i = 0; i < papers.size(); ++i)
    out += (i == 0 ? "" : i + 1 == papers.size() ? " or " : ", ") + papers[i].name;
  return out;
}

}  // namespace

ReproduceCommand::ReproduceCommand(CLI::App& app) {
  cmd_ = app.add_subcommand("reproduce",
                            "Run a paper's cases over seeds, print its tables (as docs/papers/ shows them) and write "
                            "its figures (PNG, SVG, PDF)");
  cmd_->add_option("paper", paper_, PaperNames())->required();
  cmd_->add_option("--seeds", seeds_, "Seeds: 1..10 (default), 1,2,5 or a mixture");
  cmd_->add_option("--out", out_, "Output folder (default out/reproduce_<paper>)");
  cmd_->add_option("--tables", tables_, "Only these tables (comma-separated ids; default: all)");
  cmd_->add_option("--set", sets_,
                   "Override for every case, after its own: path.to.key=value (e.g. duration)")
      ->take_all();
  cmd_->add_option("--jobs,-j", jobs_, "Runs at once (default: every core)");
  cmd_->add_option("--titles", titles_, TitleModeHelp());
  cmd_->add_flag("--quiet,-q", quiet_, "Print the tables only (no progress, no summary lines)");
}

int ReproduceCommand::Run() {
  const sim::ReproPaper paper = sim::SelectTables(sim::FindReproPaper(paper_), tables_);
  const std::vector<std::uint64_t> seeds = sim::ParseSeeds(seeds_);
  const TitleMode titles = ParseTitleMode(titles_, "--titles");
  if (jobs_ < 0 || jobs_ > 1024) throw std::runtime_error("--jobs must be in 1 ... 1024");
  const int jobs = jobs_ == 0 ? sim::TaskPool::HardwareThreads() : jobs_;
  const std::string out = out_.empty() ? "out/reproduce_" + paper.name : out_;
  CheckFolderName(out, "--out", "a folder for the cases' sweeps, tables and figures");
  sim::PrepareOutputDir(out);

  sim::InstallStopSignals();
  sim::TaskPool pool(jobs);
  ProgressLine bar(!quiet_);
  const auto t0 = std::chrono::steady_clock::now();
  const sim::ReproResults res = sim::RunPaper(
      paper, seeds, seeds_, sets_, out, pool,
      [&](std::size_t done, std::size_t failed, std::size_t total) {
        bar.Update(static_cast<double>(done) / static_cast<double>(total),
                   std::to_string(done) + "/" + std::to_string(total) + " runs" +
                       (failed ? ", " + std::to_string(failed) + " failed" : ""));
      },
      [] { return sim::StopSignal() != 0; });
  bar.Done();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (sim::StopSignal() != 0) {
    std::fputs(("formsim: reproduce interrupted by " + sim::StopSignalName(sim::StopSignal()) +
                "; the runs so far are in " + out + "\n")
                   .c_str(),
               stderr);
    return 128 + sim::StopSignal();
  }

  // The tables, printed and written, and each cell with its source.
  const std::string text = sim::ReproTablesText(paper, res);
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  sim::WriteFileAtomic((fs::path(out) / "tables.md").string(), text);
  sim::WriteFileAtomic((fs::path(out) / "cells.csv").string(), sim::ReproCellsCsv(paper, res));

  int rc = 0;
  std::vector<std::string> wrote = {"tables.md", "cells.csv"};
  for (const sim::ReproFigure& f : paper.figures) {
    PlotData data = ResolveFigure(sim::ReproBarFigure(f, res), sim::Recorder());
    data.title = TitleFor(data.title, titles);
    try {
      const std::string stem = (fs::path(out) / f.id).string();
      WriteFigurePng(data, stem + ".png");
      wrote.push_back(f.id + ".png");
      const VectorFigure vector = RecordPlot(data, 960, 600, GetTheme(ThemeId::kLight));
      for (const FigureFormat format : {FigureFormat::kSvg, FigureFormat::kPdf}) {
        const std::string ext = std::string(".") + FormatExtension(format);
        WriteVectorFigure(vector, format, FigureSize{}, data.title, stem + ext);
        wrote.push_back(f.id + ext);
      }
    } catch (const std::exception& e) {
      PrintCliError("figure " + f.id + " not written (the tables were): " + e.what());
      rc = 4;
    }
  }
  // Failed runs are left out of the statistics; say which.
  for (const auto& [id, runs] : res.cases)
    for (const sim::SweepRecord& r : runs.records)
      if (r.failed())
        sim::Print(stderr, "formsim: case %s, seed %llu: %s%s\n", id.c_str(),
                   static_cast<unsigned long long>(runs.def.SeedOf(r.run)), r.status.c_str(),
                   r.message.empty() ? "" : (": " + r.message).c_str());
  if (res.failed > 0 && rc == 0) rc = 3;
  if (!quiet_) {
    std::size_t runs = 0;
    for (const auto& [id, c] : res.cases) runs += c.records.size();
    sim::Print(stderr, "%zu runs of %zu cases in %.1f s wall on %d jobs; wrote %zu files in %s\n",
               runs, res.cases.size(), wall, jobs, wrote.size(), out.c_str());
  }
  return rc;
}

}  // namespace formsim::app
