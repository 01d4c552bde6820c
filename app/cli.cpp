#include "app/cli.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "app/export.hpp"
#include "app/gui.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/scenario.hpp"
#include "sim/core/scenario_files.hpp"
#include "sim/core/session.hpp"
#include "sim/core/thread_pool.hpp"

namespace formsim::app {
namespace {

struct RunOptions {
  std::string scenario;
  std::string seed;  ///< empty: the scenario's
  std::vector<std::string> sets;
  std::string out_dir;
  bool quiet = false;
  ExportOptions exp;  // --frames, --snapshot, --plots, --video, --fps, --size, --ui
  std::string size = "1280x720";
  std::string plot_size = "960x600";
  bool timing = false;
};

// Draws "[=====>    ] 42% t=4.20 s" on stderr, only when stderr is a terminal.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}
  void Update(double fraction, double t) {
    if (!enabled_) return;
    const int pct = static_cast<int>(fraction * 100.0);
    if (pct == last_pct_) return;
    last_pct_ = pct;
    const int width = 30, filled = static_cast<int>(fraction * width);
    std::fprintf(stderr, "\r[%s%s] %3d%% t=%.2f s", std::string(filled, '=').c_str(),
                 std::string(width - filled, ' ').c_str(), pct, t);
    std::fflush(stderr);
  }
  void Done() {
    if (enabled_) std::fprintf(stderr, "\r%60s\r", "");
  }

 private:
  bool enabled_;
  int last_pct_ = -1;
};

// Ctrl-C and SIGTERM: the run stops after the current step and writes what it has.
std::atomic<int> g_signal{0};
extern "C" void OnStopSignal(int sig) { g_signal = sig; }

void InstallStopSignals() {
  struct sigaction sa = {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);  // a closed pipe (ffmpeg, `| head`) is an error, not a death
}

// Stops `exp` when a stop signal arrived. Returns true when it did.
bool CheckStopSignal(sim::Experiment& exp) {
  const int sig = g_signal.load();
  if (sig == 0) return false;
  exp.Interrupt(std::string("interrupted by ") + (sig == SIGINT ? "SIGINT (Ctrl-C)" : "SIGTERM") +
                " at t = " + std::to_string(exp.time()) + " s");
  return true;
}

// Rows kept in memory for the figures of a headless run; the CSV is streamed to disk.
constexpr std::size_t kHistoryRows = 20000;

// The overrides of the command line: every --set in order, then --seed.
std::vector<sim::Override> Overrides(const std::vector<std::string>& sets, const std::string& seed) {
  std::vector<sim::Override> out = sim::CliOverrides(sets, -1);
  if (!seed.empty()) out.push_back({"seed", seed, "--seed", -1});
  return out;
}

// `formsim run`: the one load path (sim::Session, as the GUI), then the same steps with or
// without pictures.
int RunCommand(RunOptions opt) {
  const std::string file = sim::ResolveScenario(opt.scenario);
  const std::string out =
      opt.out_dir.empty() ? "out/" + std::filesystem::path(file).stem().string() : opt.out_dir;
  if (opt.exp.any()) {
    ParseSize(opt.size, &opt.exp.width, &opt.exp.height);
    ParseSize(opt.plot_size, &opt.exp.plot_width, &opt.exp.plot_height);
  }
  sim::Session session(file, Overrides(opt.sets, opt.seed));
  sim::PrepareOutputDir(out);  // fail before simulating, not after
  if (opt.exp.any()) PrepareExport(opt.exp);  // a missing ffmpeg fails before simulating too
  // Rows go to disk as they are recorded; memory keeps a bounded history for the figures.
  sim::Recorder& rec = session.exp().mutable_recorder();
  rec.StreamTo(sim::CsvPath(out));
  rec.SetHistoryLimit(kHistoryRows);
  InstallStopSignals();

  ProgressBar bar(!opt.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  ExportStats st;
  std::string write_error;
  auto write_results = [&] {
    try {
      sim::WriteRunOutputs(session.exp(), out);
    } catch (const std::exception& e) {
      write_error = e.what();
    }
  };
  if (opt.exp.any()) {
    st = RunWithExport(
        session, opt.exp,
        [&](double f, double t) {
          bar.Update(f, t);
          CheckStopSignal(session.exp());
        },
        write_results);
  } else {
    sim::Experiment& exp = session.exp();
    const double duration = exp.setup().duration;
    while (!exp.finished()) {
      exp.Step();
      if ((exp.steps() & 63) == 0) {
        bar.Update(exp.time() / duration, exp.time());
        CheckStopSignal(exp);
      }
    }
    write_results();
  }
  bar.Done();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const sim::Experiment& exp = session.exp();

  if (!opt.quiet) {
    std::cout << exp.SummaryText();
    std::printf("%ld steps, %.2f s simulated in %.3f s wall (%.0fx real time)\n", exp.steps(),
                exp.time(), wall, wall > 0 ? exp.time() / wall : 0.0);
    if (write_error.empty()) {
      std::printf("wrote %s/timeseries.csv and %s/summary.json", out.c_str(), out.c_str());
      if (!opt.exp.frames_dir.empty())
        std::printf(", %ld frames in %s", st.frames, opt.exp.frames_dir.c_str());
      if (!opt.exp.plots_dir.empty())
        std::printf(", %ld figures in %s", st.figures, opt.exp.plots_dir.c_str());
      if (!opt.exp.video.empty() && st.error.empty()) std::printf(", %s", opt.exp.video.c_str());
      if (!opt.exp.snapshot.empty() && st.error.empty()) std::printf(", %s", opt.exp.snapshot.c_str());
      std::printf("\n");
    }
  }
  if (opt.timing && opt.exp.any()) std::fputs(st.Report().c_str(), stderr);
  // Exit codes: 2 bad input or unwritable results, 3 the run stopped early (numerical fault),
  // 4 an export failed (results written), 130 / 143 interrupted (results written).
  int rc = 0;
  if (!st.error.empty()) {
    std::fprintf(stderr, "formsim: error: export failed (the results were written): %s\n",
                 st.error.c_str());
    rc = 4;
  }
  if (exp.status() == "numerical_fault") {
    std::fprintf(stderr, "formsim: error: the run stopped at t = %g s: %s; everything up to it was written\n",
                 exp.time(), exp.stop_reason().c_str());
    rc = 3;
  } else if (exp.status() == "interrupted") {
    std::fprintf(stderr, "formsim: %s; the results so far were written and marked interrupted\n",
                 exp.stop_reason().c_str());
    rc = 128 + g_signal.load();
  }
  if (!write_error.empty()) {
    std::fprintf(stderr, "formsim: error: %s\n", write_error.c_str());
    rc = 2;
  }
  return rc;
}

int ListCommand() {
  for (const auto& file : sim::ShippedScenarios()) {
    const std::string stem = std::filesystem::path(file).stem().string();
    std::string type = "?", description;
    try {
      YAML::Node root = sim::LoadYamlFile(file);
      if (root["type"]) type = root["type"].as<std::string>();
      if (root["description"]) description = root["description"].as<std::string>();
    } catch (const std::exception& e) {
      description = std::string("(unreadable: ") + e.what() + ")";
    }
    std::printf("%-34s %-11s %s\n", stem.c_str(), type.c_str(), description.c_str());
  }
  return 0;
}

}  // namespace

int Main(int argc, char** argv) {
  CLI::App app{"formsim: multi-robot formation control and navigation simulator"};
  app.require_subcommand(1);

  RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "Run a scenario headless and write CSV + summary");
  run_cmd->add_option("scenario", run.scenario, "Scenario name (see `formsim list`) or YAML path")
      ->required();
  run_cmd->add_option("--seed", run.seed, "Random seed 0 ... 2^64-1 (overrides the scenario's)");
  run_cmd->add_option("--set", run.sets, "Override a scenario value: path.to.key=value")
      ->take_all();
  run_cmd->add_option("--out", run.out_dir, "Output folder (default out/<scenario>)");
  run_cmd->add_flag("--quiet,-q", run.quiet, "Print nothing but errors");

  run_cmd->add_option("--frames", run.exp.frames_dir, "Write PNG frames frame_00000.png... here");
  run_cmd->add_option("--fps", run.exp.fps, "Frames per second of simulated time (default 30)");
  run_cmd->add_option("--size", run.size, "Frame size WIDTHxHEIGHT (default 1280x720)");
  run_cmd->add_option("--snapshot", run.exp.snapshot, "Write the final view as a PNG");
  run_cmd->add_option("--plots", run.exp.plots_dir, "Write one PNG per figure (file = figure id)");
  run_cmd->add_option("--plot-size", run.plot_size, "Figure size WIDTHxHEIGHT (default 960x600)");
  run_cmd->add_option("--video", run.exp.video, "Write an MP4 video (needs ffmpeg on PATH)");
  run_cmd->add_flag("--ui", run.exp.ui, "Draw the GUI panels into frames and snapshot");
  run_cmd->add_flag("--whole-run", run.exp.whole_run,
                    "Camera keeps everything since the start in view (default: tracks the robots)");
  run_cmd->add_flag("--timing", run.timing, "Print where the export time went (stderr)");
  int threads = 0;  // 0: all cores
  const std::string threads_help =
      "Threads for the work inside a step (default: all cores); results are identical for any N";
  run_cmd->add_option("--threads", threads, threads_help)->check(CLI::Range(1, 1024));

  app.add_subcommand("list", "List the shipped scenarios");

  GuiOptions gui;
  std::string gui_size = "1600x900", gui_speed = "1";
  CLI::App* gui_cmd = app.add_subcommand("gui", "Open the interactive window (live tuning)");
  gui_cmd->add_option("scenario", gui.scenario,
                      "Scenario name or YAML path (default: first formation_*)");
  gui_cmd->add_option("--seed", gui.seed, "Random seed 0 ... 2^64-1 (overrides the scenario's)");
  gui_cmd->add_option("--set", gui.sets, "Override a scenario value: path.to.key=value")
      ->take_all();
  gui_cmd->add_option("--size", gui_size, "Window size WIDTHxHEIGHT (default 1600x900)");
  gui_cmd->add_option("--screenshot", gui.screenshot,
                      "PNG written by 's' and after the last frame");
  gui_cmd->add_option("--exit-after", gui.exit_after, "Exit after N frames");
  gui_cmd->add_flag("--exit-when-finished", gui.exit_when_finished,
                    "Exit when the run reaches its duration");
  gui_cmd->add_flag("--paused", gui.paused, "Start paused");
  gui_cmd->add_option("--speed", gui_speed, "Speed: 0.1, 0.25, 0.5, 1, 2, 5, 10 or max");
  gui_cmd
      ->add_option("--edit", gui.edits, "Scripted edit FRAME:key=value, as if made with a slider")
      ->take_all();
  gui_cmd->add_option("--script", gui.script,
                      "Run scripted actions, one per line: FRAME ACTION [ARGS] (edit k=v, reset, "
                      "reset-seed N, reload, load S, open P, save P, play, pause, step, "
                      "screenshot P, action ID)");
  gui_cmd->add_option("--out", gui.out_dir, "Write timeseries.csv and summary.json here on exit");
  gui_cmd->add_flag("--timing", gui.timing, "Print frame-time statistics on exit (stderr)");
  gui_cmd->add_option("--threads", threads, threads_help)->check(CLI::Range(1, 1024));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (threads > 0) sim::ThreadPool::SetDefaultThreads(threads);
    if (run_cmd->parsed()) return RunCommand(run);
    if (app.got_subcommand("list")) return ListCommand();
    if (gui_cmd->parsed()) {
      ParseSize(gui_size, &gui.width, &gui.height);
      if (gui_speed == "max") {
        gui.speed = 0.0;
      } else {
        char* end = nullptr;
        gui.speed = std::strtod(gui_speed.c_str(), &end);
        if (end == gui_speed.c_str() || *end != 0 || !(gui.speed > 0 && gui.speed <= 10))
          throw std::runtime_error("--speed '" + gui_speed + "': expected 0.1 ... 10 or max");
      }
      return RunGui(gui);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "formsim: error: %s\n", e.what());
    return 2;
  }
  return 0;
}

}  // namespace formsim::app
