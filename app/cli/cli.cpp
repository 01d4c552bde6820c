#include "app/cli/cli.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include "app/cli/cli_messages.hpp"
#include "app/cli/cli_reference.hpp"
#include "app/cli/doctor_command.hpp"
#include "app/cli/figures_command.hpp"
#include "app/cli/lessons_cli.hpp"
#include "app/cli/progress.hpp"
#include "app/cli/replay_command.hpp"
#include "app/cli/reproduce_cli.hpp"
#include "app/cli/study_cli.hpp"
#include "app/export/app_icon.hpp"
#include "app/export/export.hpp"
#include "app/export/figure_requests.hpp"
#include "app/gui/command_table.hpp"
#include "app/gui/gui.hpp"
#include "app/gui/ui_offscreen.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/stop_signal.hpp"
#include "sim/core/thread_pool.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"

namespace formsim::app {

namespace {

struct RunOptions {
  std::string scenario;
  std::string seed;  ///< empty: the scenario's
  std::string max_steps;  ///< empty: the scenario's (default 1e8)
  std::vector<std::string> sets;
  std::string out_dir;
  bool quiet = false;
  ExportOptions exp;  // --frames, --snapshot, --plots, --video, --gif, --fps, --size, --ui
  std::string size = "1280x720";
  std::string plot_size = "960x600";
  std::string plot_format = "png";
  std::string snapshot;
  std::string theme = "light";
  std::string titles = "full";
  std::string log_y;  // --log-y NAME,...
  bool timing = false;
};


// Stops `exp` when a stop signal arrived. Returns true when it did.
bool CheckStopSignal(sim::Experiment& exp) {
  const int sig = sim::StopSignal();
  if (sig == 0) return false;
  exp.Interrupt("interrupted by " + sim::StopSignalName(sig) +
                " at t = " + std::to_string(exp.time()) + " s");
  return true;
}

// The overrides of the command line: every --set in order, then --seed.
std::vector<sim::Override> Overrides(const std::vector<std::string>& sets, const std::string& seed) {
  std::vector<sim::Override> out = sim::CliOverrides(sets, -1);
  if (!seed.empty()) out.push_back({"seed", seed, "--seed", -1});
  return out;
}

// An empty file or folder name given to an option (`--frames ""`, most often a shell variable
// that was not set) is refused by name, in every command: it used to mean "not given", so the
// run went on without the frames, video or output folder and said nothing.
void RefuseEmptyNames(const CLI::App& app) {
  static const char* kNames[] = {"--out", "--frames",     "--snapshot", "--plots",  "--video",
                                 "--gif", "--screenshot", "--script",   "--session"};
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (!sub->parsed()) continue;
    for (const CLI::Option* o : sub->get_options())
      for (const char* name : kNames)
        if (o->check_name(name) && o->count() > 0)
          for (const std::string& v : o->results())
            if (v.empty())
              throw std::runtime_error(std::string(name) +
                                       " '': an empty name (an unset shell variable?); give a "
                                       "file or folder name, or leave the option out");
    RefuseEmptyNames(*sub);
  }
}

// "wrote OUT/timeseries.csv and OUT/summary.json, ..." naming every file `formsim run` wrote.
std::string RunWroteLine(const RunOptions& opt, const std::string& out, const ExportStats& st) {
  std::string line = WroteRunOutputsText(out);
  if (!opt.exp.frames_dir.empty())
    sim::AppendSprintf(line, ", %ld frames in %s", st.frames, opt.exp.frames_dir.c_str());
  if (!opt.exp.plots_dir.empty())
    sim::AppendSprintf(line, ", %ld figures (%ld files) in %s", st.figures, st.figure_files,
                       opt.exp.plots_dir.c_str());
  if (!opt.exp.video.empty() && st.error.empty())
    sim::AppendSprintf(line, ", %s (%ld frames)", opt.exp.video.c_str(), st.frames);
  if (!opt.exp.gif.empty() && st.error.empty())
    sim::AppendSprintf(line, ", %s (%ld frames)", opt.exp.gif.c_str(), st.gif_frames);
  if (!opt.snapshot.empty() && st.error.empty()) line += ", " + opt.snapshot;
  return line + "\n";
}

// Says on stderr why the run did not end well and returns its exit code: 2 bad input or
// unwritable results, 3 the run stopped early (numerical fault), 4 an export failed (results
// written), 130 / 143 interrupted (results written).
int RunExitCode(const sim::Experiment& exp, const ExportStats& st, const std::string& write_error) {
  int rc = 0;
  if (!st.error.empty()) {
    PrintExportFailed(st.error);
    rc = 4;
  }
  if (exp.status() == "numerical_fault") {
    sim::Print(stderr,
               "formsim: error: the run stopped at t = %g s: %s; everything up to it was written\n",
               exp.time(), exp.stop_reason().c_str());
    rc = 3;
  } else if (exp.status() == "interrupted") {
    std::fputs(("formsim: " + exp.stop_reason() +
                "; the results so far were written and marked interrupted\n")
                   .c_str(),
               stderr);
    rc = 128 + sim::StopSignal();
  }
  if (!write_error.empty()) {
    PrintCliError(write_error);
    rc = 2;
  }
  return rc;
}

// `formsim run`: the one load path (sim::Session, as the GUI), then the same steps with or
// without pictures.
int RunCommand(RunOptions opt) {
  const std::string file = sim::ResolveScenario(opt.scenario);
  const std::string out =
      opt.out_dir.empty() ? "out/" + std::filesystem::path(file).stem().string() : opt.out_dir;
  if (!opt.snapshot.empty()) opt.exp.snapshots = {opt.snapshot};
  ParseSize(opt.size, &opt.exp.width, &opt.exp.height, "--size");
  opt.exp.plot_size = ParseFigureSize(opt.plot_size, "--plot-size");
  opt.exp.plot_formats = ParseFigureFormats(opt.plot_format, "--plot-format");
  opt.exp.dpi = ParseDpi(opt.exp.dpi);
  opt.exp.theme = ParseTheme(opt.theme, "--theme");
  opt.exp.titles = ParseTitleMode(opt.titles, "--titles");
  std::vector<sim::Override> overrides = Overrides(opt.sets, opt.seed);
  if (!opt.max_steps.empty()) overrides.push_back({"max_steps", opt.max_steps, "--max-steps", -1});
  if (!opt.log_y.empty()) opt.exp.log_y = ParseFigureNames(opt.log_y, "--log-y");
  sim::Session session(file, overrides);
  // The figures' markup and the --log-y names, before simulating (figures from a first step).
  if (!opt.exp.plots_dir.empty())
    CheckFigureRequests(ProbeFigures(file, overrides), opt.exp.log_y);
  else if (!opt.exp.log_y.empty())
    throw std::runtime_error("--log-y needs --plots DIR");
  sim::PrepareOutputDir(out);  // fail before simulating, not after
  if (opt.exp.any()) PrepareExport(opt.exp);  // a missing ffmpeg fails before simulating too
  // Rows go to disk as they are recorded; memory keeps a bounded history for the figures.
  sim::Recorder& rec = session.exp().mutable_recorder();
  rec.StreamTo(sim::CsvPath(out));
  rec.SetHistoryLimit(sim::kRunHistoryRows);
  sim::InstallStopSignals();

  ProgressLine bar(!opt.quiet);
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
        [&](const ExportProgress& p) {
          if (!p.status.empty()) {
            bar.Status(p.status);
          } else {
            std::string d = ProgressTimeText(p.t);
            if (p.frames_total > 0)
              d += "  " + std::to_string(p.frames) + "/" + std::to_string(p.frames_total) +
                   " frames";
            bar.Update(p.fraction, d);
          }
          CheckStopSignal(session.exp());
        },
        write_results, {}, MakeUiFrames);
  } else {
    sim::Experiment& exp = session.exp();
    const double duration = exp.setup().duration;
    while (!exp.finished()) {
      exp.Step();
      if ((exp.steps() & 63) == 0) {
        bar.Update(exp.time() / duration, ProgressTimeText(exp.time()));
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
    sim::Print(stdout, "%ld steps, %.2f s simulated in %.3f s wall (%.0fx real time)\n",
               exp.steps(), exp.time(), wall, wall > 0 ? exp.time() / wall : 0.0);
    if (write_error.empty()) std::fputs(RunWroteLine(opt, out, st).c_str(), stdout);
  }
  if (opt.timing && opt.exp.any()) std::fputs(st.Report().c_str(), stderr);
  return RunExitCode(exp, st, write_error);
}

// `formsim list --names [scenarios|lessons|all]`: bare names, one a line (the bash completion
// and scripts read them).
int ListNames(const std::string& which) {
  if (which != "scenarios" && which != "lessons" && which != "all")
    throw std::runtime_error("--names '" + which + "': expected scenarios, lessons or all");
  if (which != "lessons")
    for (const auto& file : sim::ShippedScenarios())
      std::fputs((std::filesystem::path(file).stem().string() + "\n").c_str(), stdout);
  if (which != "scenarios")
    for (const auto& file : sim::ShippedLessons())
      std::fputs((std::filesystem::path(file).stem().string() + "\n").c_str(), stdout);
  return 0;
}

int ListCommand() {
  for (const auto& file : sim::ShippedScenarios()) {
    const sim::ScenarioListing s = sim::DescribeScenario(file);
    sim::Print(stdout, "%-34s %-11s %s\n", s.name.c_str(), s.type.c_str(), s.description.c_str());
  }
  // Lessons: scenarios with a text (formsim gui --lesson NAME); run and sweep take them by name.
  // Grouped by the paper they teach (the scenario's type), in the order of the kinds.
  const auto lessons = sim::ShippedLessons();
  if (!lessons.empty()) std::fputs("\nlessons (formsim gui --lesson NAME), by paper:\n", stdout);
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> by_paper;
  for (const auto& file : lessons) {
    const sim::ScenarioListing l = sim::DescribeLesson(file);
    by_paper[l.type].emplace_back(l.name, l.description);
  }
  for (const auto& [paper, list] : by_paper) {
    std::fputs(("  " + paper + ":\n").c_str(), stdout);
    for (const auto& [stem, title] : list)
      sim::Print(stdout, "    %-32s %s\n", stem.c_str(), title.c_str());
  }
  return 0;
}

// The help texts two commands share.
constexpr const char* kCliOverlayHelp =
    "Overlays of the world view, comma-separated: slots, control_points, links, measured, "
    "errors, triangles, velocity, covariance, graph (all, none, default, -NAME removes; "
    "default: slots,control_points,links,covariance)";
constexpr const char* kCliThreadsHelp =
    "Threads for the work inside a step (default: all cores); results are identical for any N";

// The flags of the commands defined in this file (study, reproduce, replay and lessons keep
// their own), and those commands.
struct CliFlags {
  RunOptions run;
  std::string run_overlay;
  int threads = 0;  // 0: all cores (run and gui)
  std::string list_names;
  bool list_commands = false, list_markdown = false;
  std::string ref_format = "markdown";
  std::string icon_svg, icon_png;
  int icon_px = 256;
  FiguresOptions figs;
  GuiOptions gui;
  std::string gui_size = "1600x900", gui_speed = "1", gui_theme = "light", gui_overlay;
  CLI::App* run_cmd = nullptr;
  CLI::App* list_cmd = nullptr;
  CLI::App* ref_cmd = nullptr;
  CLI::App* icon_cmd = nullptr;
  CLI::App* figs_cmd = nullptr;
  CLI::App* gui_cmd = nullptr;
};

// `formsim run`'s flags: the run, then its pictures.
void AddRunCommand(CLI::App& app, CliFlags& f) {
  RunOptions& run = f.run;
  CLI::App* cmd = f.run_cmd =
      app.add_subcommand("run", "Run a scenario headless and write CSV + summary");
  cmd->add_option("scenario", run.scenario, "Scenario name (see `formsim list`) or YAML path")
      ->required();
  cmd->add_option("--seed", run.seed, "Random seed 0 ... 2^64-1 (overrides the scenario's)");
  cmd->add_option("--set", run.sets, "Override a scenario value: path.to.key=value")->take_all();
  cmd->add_option("--out", run.out_dir, "Output folder (default out/<scenario>)");
  cmd->add_option("--max-steps", run.max_steps,
                  "Allow runs of up to N world steps (default 1e8; longer runs are refused)");
  cmd->add_flag("--quiet,-q", run.quiet, "Print nothing but errors");

  cmd->add_option("--frames", run.exp.frames_dir, "Write PNG frames frame_00000.png... here");
  cmd->add_option("--fps", run.exp.fps, "Frames per second of simulated time (default 30)");
  cmd->add_option("--size", run.size, "Frame size WIDTHxHEIGHT (default 1280x720)");
  cmd->add_option("--snapshot", run.snapshot,
                  "Write the final view: F.png, F.svg or F.pdf (format by extension)");
  cmd->add_option("--plots", run.exp.plots_dir,
                  "Write every figure into this folder (file = figure id, see --plot-format)");
  cmd->add_option("--plot-format", run.plot_format,
                  "Figure formats: any of png,svg,pdf, comma-separated (default png)");
  cmd->add_option("--plot-size", run.plot_size,
                  "Figure size WIDTHxHEIGHT in px, cm, mm or in (default 960x600, e.g. "
                  "8.5cmx6cm)");
  cmd->add_option("--dpi", run.exp.dpi,
                  "Pixels per inch of PNG figures and snapshot (default 96: one pixel per "
                  "px; 300 for print)");
  cmd->add_option(
      "--theme", run.theme,
      std::string("Colours of frames, snapshot and figures: ") + ThemeNames() + " (default light)");
  cmd->add_option("--titles", run.titles, TitleModeHelp());
  cmd->add_option("--log-y", run.log_y,
                  "Figures (ids, comma-separated) drawn with a logarithmic y axis; values "
                  "<= 0 are left out with a note");
  cmd->add_option("--video", run.exp.video,
                  "Write an MP4 video (.mp4, .mkv or .mov; needs ffmpeg on PATH)");
  cmd->add_option("--gif", run.exp.gif,
                  "Write a looping animated GIF for slides (needs ffmpeg on PATH)");
  cmd->add_option("--gif-fps", run.exp.gif_fps, "Frames per second of the GIF (default 15)");
  cmd->add_option("--gif-width", run.exp.gif_width,
                  "Width of the GIF in pixels (default 640; height keeps --size's aspect)");
  cmd->add_flag("--ui", run.exp.ui, "Draw the GUI panels into frames and snapshot");
  cmd->add_option("--overlay", f.run_overlay, kCliOverlayHelp);
  cmd->add_flag("--legend", run.exp.legend, "Draw a legend of every mark in the world view");
  cmd->add_flag("--whole-run", run.exp.whole_run,
                "Camera keeps everything since the start in view (default: tracks the robots)");
  cmd->add_flag("--timing", run.timing, "Print where the export time went (stderr)");
  cmd->add_option("--threads", f.threads, kCliThreadsHelp)->check(CLI::Range(1, 1024));
}

// `formsim list` and `formsim doctor`, and the hidden `reference` and `icon` the build uses.
void AddListAndToolCommands(CLI::App& app, CliFlags& f) {
  f.list_cmd = app.add_subcommand("list", "List the shipped scenarios and lessons");
  f.list_cmd
      ->add_option("--names", f.list_names,
                   "Print bare names only, one a line: scenarios, lessons or all")
      ->expected(0, 1)
      ->default_str("all");

  app.add_subcommand("doctor",
                     "Say where the assets were found and which optional parts (Python module, "
                     "ffmpeg, NLopt, Cairo, GL renderer, display) are present; exit 1 when "
                     "something formsim needs is missing");
  // Hidden (no group): the build makes the man page, the bash completion and the icon with these.
  f.ref_cmd = app.add_subcommand(
      "reference", "Print the command-line reference generated from these definitions");
  f.ref_cmd->group("");
  f.ref_cmd->add_option("--format", f.ref_format, "man, bash or markdown")->required();
  f.icon_cmd = app.add_subcommand("icon", "Draw the application icon");
  f.icon_cmd->group("");
  f.icon_cmd->add_option("--svg", f.icon_svg, "SVG file");
  f.icon_cmd->add_option("--png", f.icon_png, "PNG file");
  f.icon_cmd->add_option("--png-size", f.icon_px, "PNG width and height in pixels");
}

void AddFiguresCommand(CLI::App& app, CliFlags& f) {
  FiguresOptions& figs = f.figs;
  CLI::App* cmd = f.figs_cmd = app.add_subcommand(
      "figures", "Render every figure of scenarios (default: all shipped) on all cores");
  cmd->add_option("scenarios", figs.scenarios, "Scenario names or YAML paths");
  cmd->add_option("--out", figs.out_dir, "Output folder: DIR/<scenario>/<figure>.<format>")
      ->required();
  cmd->add_option("--plot-format", figs.formats,
                  "Formats: any of png,svg,pdf, comma-separated (default png)");
  cmd->add_option("--plot-size", figs.plot_size,
                  "Figure size WIDTHxHEIGHT in px, cm, mm or in (default 960x600)");
  cmd->add_option("--size", figs.size, "World view size WIDTHxHEIGHT (default 1280x720)");
  cmd->add_option("--dpi", figs.dpi, "Pixels per inch of PNG files (default 96)");
  cmd->add_option("--theme", figs.theme,
                  std::string("Colours: ") + ThemeNames() + " (default light)");
  cmd->add_option("--titles", figs.titles, TitleModeHelp());
  cmd->add_option("--log-y", figs.log_y,
                  "Figures (ids, comma-separated) drawn with a logarithmic y axis in every "
                  "scenario that has them");
  cmd->add_option("--jobs,-j", figs.jobs, "Scenarios at once (default: one per core)");
  cmd->add_flag("--quiet,-q", figs.quiet, "Print nothing but errors");
}

void AddGuiCommand(CLI::App& app, CliFlags& f) {
  GuiOptions& gui = f.gui;
  CLI::App* cmd = f.gui_cmd =
      app.add_subcommand("gui", "Open the interactive window (live tuning)");
  cmd->add_option("scenario", gui.scenario,
                  "Scenario name or YAML path (default: first formation_*)");
  cmd->add_option("--lesson", gui.lesson,
                  "Open a lesson (assets/lessons/NAME.yaml, see `formsim list`) on its Lesson tab");
  cmd->add_option("--seed", gui.seed, "Random seed 0 ... 2^64-1 (overrides the scenario's)");
  cmd->add_option("--set", gui.sets, "Override a scenario value: path.to.key=value")->take_all();
  cmd->add_option("--size", f.gui_size, "Window size WIDTHxHEIGHT (default 1600x900)");
  cmd->add_option("--screenshot", gui.screenshot, "PNG written by 's' and after the last frame");
  cmd->add_option("--exit-after", gui.exit_after, "Exit after N frames");
  cmd->add_flag("--exit-when-finished", gui.exit_when_finished,
                "Exit when the run reaches its duration");
  cmd->add_flag("--paused", gui.paused, "Start paused");
  cmd->add_option("--speed", f.gui_speed, "Speed: 0.1, 0.25, 0.5, 1, 2, 5, 10 or max");
  cmd->add_option("--edit", gui.edits, "Scripted edit FRAME:key=value, as if made with a slider")
      ->take_all();
  cmd->add_option(
      "--script", gui.script,
      "Run scripted actions, one per line: FRAME ACTION [ARGS]. Actions: " + CommandUsageList());
  CLI::Option* list_opt = cmd->add_flag(
      "--list-commands", f.list_commands,
      "Print every command of the window (name, keys, menu path, arguments) and exit");
  cmd->add_flag("--markdown", f.list_markdown,
                "With --list-commands: as the Markdown table of docs/window.md")
      ->needs(list_opt);
  cmd->add_option("--out", gui.out_dir, "Write timeseries.csv and summary.json here on exit");
  cmd->add_option("--session", gui.session_file,
                  "Record the session (edits with their steps, resets, seeds, loads, pins, "
                  "branches) into this file on exit; replay it with `formsim replay`");
  cmd->add_option("--theme", f.gui_theme,
                  std::string("Colours of the panels, world view and plots: ") + ThemeNames() +
                      " (default light)");
  cmd->add_option("--overlay", f.gui_overlay, kCliOverlayHelp);
  cmd->add_flag("--timing", gui.timing, "Print frame-time statistics on exit (stderr)");
  cmd->add_option("--threads", f.threads, kCliThreadsHelp)->check(CLI::Range(1, 1024));
}

// --overlay TEXT over the default overlays.
void ParseOverlayFlag(const std::string& text, std::set<std::string>* out) {
  *out = DefaultSceneOverlays();
  if (const std::string err = ParseSceneOverlays(text, out); !err.empty())
    throw std::runtime_error("--overlay '" + text + "': " + err);
}

// `formsim reference --format man|bash|markdown`.
int ReferenceCommand(const CLI::App& app, const std::string& format) {
  const std::vector<CommandDoc> docs = DescribeCommands(app);
  const std::string version = FORMSIM_VERSION_NUMBER;
  if (format == "man")
    std::fputs(ManPage(docs, version).c_str(), stdout);
  else if (format == "bash")
    std::fputs(BashCompletion(docs).c_str(), stdout);
  else if (format == "markdown")
    std::fputs(CliMarkdown(docs, version).c_str(), stdout);
  else
    throw std::runtime_error("--format '" + format + "': expected man, bash or markdown");
  return 0;
}

// `formsim gui`: the window's flags read, then the window (or, with --list-commands, its table).
int GuiCommand(CliFlags& f) {
  if (f.list_commands) {
    std::fputs(f.list_markdown ? CommandTableMarkdown().c_str() : CommandListText().c_str(),
               stdout);
    return 0;
  }
  GuiOptions& gui = f.gui;
  ParseSize(f.gui_size, &gui.width, &gui.height, "--size");
  gui.theme = ParseTheme(f.gui_theme, "--theme");
  if (f.gui_speed == "max") {
    gui.speed = 0.0;
  } else {
    char* end = nullptr;
    gui.speed = std::strtod(f.gui_speed.c_str(), &end);
    if (end == f.gui_speed.c_str() || *end != 0 || !(gui.speed > 0 && gui.speed <= 10))
      throw std::runtime_error("--speed '" + f.gui_speed + "': expected 0.1 ... 10 or max");
  }
  if (!f.gui_overlay.empty()) {
    ParseOverlayFlag(f.gui_overlay, &gui.overlays);
    gui.overlays_given = true;
  }
  return RunGui(gui);
}

// The commands other files define, each adding itself to the app.
struct CliFileCommands {
  explicit CliFileCommands(CLI::App& app) : study(app), reproduce(app), replay(app), lessons(app) {}
  StudyCommands study;  // sweep, sweep collect, tune
  ReproduceCommand reproduce;
  ReplayCommand replay;
  LessonsCommand lessons;
};

// Runs the command given on the command line. Returns its exit code; throws on bad input.
int RunGivenCommand(const CLI::App& app, CliFlags& f, CliFileCommands& more) {
  RefuseEmptyNames(app);
  if (f.threads > 0) sim::ThreadPool::SetDefaultThreads(f.threads);
  if (f.run_cmd->parsed()) {
    if (!f.run_overlay.empty()) ParseOverlayFlag(f.run_overlay, &f.run.exp.overlays);
    return RunCommand(f.run);
  }
  if (f.list_cmd->parsed())
    return f.list_cmd->count("--names") > 0 ? ListNames(f.list_names.empty() ? "all" : f.list_names)
                                            : ListCommand();
  if (app.got_subcommand("doctor")) return DoctorCommand();
  if (f.ref_cmd->parsed()) return ReferenceCommand(app, f.ref_format);
  if (f.icon_cmd->parsed()) {
    if (f.icon_svg.empty() && f.icon_png.empty())
      throw std::runtime_error("icon: give --svg or --png");
    WriteAppIcon(f.icon_svg, f.icon_png, f.icon_px);
    return 0;
  }
  if (more.study.parsed()) return more.study.Run();
  if (more.reproduce.parsed()) return more.reproduce.Run();
  if (more.replay.parsed()) return more.replay.Run();
  if (more.lessons.parsed()) return more.lessons.Run();
  if (f.figs_cmd->parsed()) return FiguresCommand(f.figs);
  if (f.gui_cmd->parsed()) return GuiCommand(f);
  return 0;
}

}  // namespace

int Main(int argc, char** argv) {
  CLI::App app{"formsim: multi-robot formation control and navigation simulator"};
  app.require_subcommand(1);
  app.set_version_flag("--version", VersionLine(),
                       "Print the version, the git commit and the build type, and exit");
  // The order of the commands in --help, the man page and docs/cli.md.
  CliFlags flags;
  AddRunCommand(app, flags);
  AddListAndToolCommands(app, flags);
  AddFiguresCommand(app, flags);
  AddGuiCommand(app, flags);
  CliFileCommands more(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return RunGivenCommand(app, flags, more);
  } catch (const std::exception& e) {
    PrintCliError(e.what());
    return 2;
  }
}

}  // namespace formsim::app
