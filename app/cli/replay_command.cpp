#include "app/cli/replay_command.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/cli/cli_messages.hpp"
#include "app/cli/progress.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/session/session_record.hpp"

namespace formsim::app {

ReplayCommand::ReplayCommand(CLI::App& app) {
  cmd_ = app.add_subcommand("replay", "Replay a session recorded by the GUI (--session) headless");
  cmd_->add_option("file", file_, "Session file written by `formsim gui --session` or Save session")
      ->required();
  cmd_->add_option("--out", out_, "Output folder (default out/replay_<file>)");
  cmd_->add_option("--frames", exp_.frames_dir, "Write PNG frames of the last run here");
  cmd_->add_option("--video", exp_.video, "Write an MP4 video of the last run (needs ffmpeg)");
  cmd_->add_option("--plots", exp_.plots_dir, "Write every figure of the last run here");
  cmd_->add_option("--fps", exp_.fps, "Frames per second of simulated time (default 30)");
  cmd_->add_option("--size", size_, "Frame size WIDTHxHEIGHT (default 1280x720)");
  cmd_->add_option("--plot-format", plot_format_, "Figure formats: png,svg,pdf (default png)");
  cmd_->add_option("--plot-size", plot_size_, "Figure size (default 960x600)");
  cmd_->add_option("--theme", theme_, std::string("Colours: ") + ThemeNames() + " (default light)");
  cmd_->add_flag("--quiet,-q", quiet_, "Print nothing but errors");
}

namespace {

// Does one change of a run log to `s` through the session's own calls, as the GUI did: an edit
// batch is asked for and applied together (one Retune), a drag and an action likewise.
void ApplyThroughSession(sim::Session& s, const sim::RunChange& c) {
  std::string err;
  switch (c.kind) {
    case sim::RunChange::Kind::kEdits:
      for (const sim::Override& o : c.edits)
        if (err.empty()) err = s.Edit(o.key, o.value, o.origin);
      break;
    case sim::RunChange::Kind::kMove:
      s.Move(c.name, c.x, c.y);
      break;
    case sim::RunChange::Kind::kAction:
      err = s.Action(c.name, c.origin);
      break;
  }
  if (!err.empty())
    throw std::runtime_error("replay: a change at step " + std::to_string(c.step) +
                             " went otherwise than recorded: " + err);
  s.ApplyPending();
}

}  // namespace

int ReplayCommand::Run() {
  const sim::SessionRecord record = sim::SessionRecord::Read(file_);
  const std::string out =
      out_.empty() ? "out/replay_" + std::filesystem::path(file_).stem().string() : out_;
  ParseSize(size_, &exp_.width, &exp_.height, "--size");
  exp_.plot_size = ParseFigureSize(plot_size_, "--plot-size");
  exp_.plot_formats = ParseFigureFormats(plot_format_, "--plot-format");
  exp_.theme = ParseTheme(theme_, "--theme");
  sim::PrepareOutputDir(out);
  if (exp_.any()) PrepareExport(exp_);

  // The record, event by event at its steps, with the rows of each run streamed to the CSV as
  // the GUI streams them with --out (the same history bound too).
  ProgressLine bar(!quiet_);
  sim::SessionReplay replay(record, [&out](sim::Experiment& e) {
    e.mutable_recorder().SetHistoryLimit(sim::kRunHistoryRows);
    e.mutable_recorder().StreamTo(sim::CsvPath(out));
  });
  long n = 0;
  while (replay.Advance())
    if ((++n & 255) == 0)
      bar.Update(static_cast<double>(replay.done()) / static_cast<double>(replay.total()),
                 "event " + std::to_string(replay.done()) + "/" + std::to_string(replay.total()) +
                     ", " + ProgressTimeText(replay.session().exp().time()));
  sim::Session& s = replay.session();
  sim::WriteRunOutputs(s.exp(), out);

  ExportStats st;
  if (exp_.any()) {
    // Pictures of the last run: replayed once more from its log, through a session (so the
    // export's --ui panels and figures are those of `formsim run`), its changes at their steps.
    const sim::RunLog log = s.run_log();
    const long end = s.exp().steps();
    sim::Session again(s.source(), log.base);
    again.exp().mutable_recorder().SetHistoryLimit(sim::kRunHistoryRows);
    std::size_t next = 0;
    auto advance = [&]() -> bool {
      while (next < log.changes.size() && log.changes[next].step <= again.exp().steps())
        ApplyThroughSession(again, log.changes[next++]);
      if (again.exp().steps() >= end || again.exp().finished()) return false;
      again.Step();
      return true;
    };
    st = RunWithExport(
        again, exp_,
        [&](const ExportProgress& p) {
          if (!p.status.empty())
            bar.Status(p.status);
          else
            bar.Update(p.fraction, "pictures: " + ProgressTimeText(p.t));
        },
        {}, advance);
    if (again.exp().Summary().Dump() != s.exp().Summary().Dump())
      std::fputs("formsim: warning: the pictures' run differs from the replayed one\n", stderr);
  }
  bar.Done();
  if (!quiet_) {
    std::cout << s.exp().SummaryText();
    sim::Print(stdout, "replayed %zu events of %s: the last run stopped at step %ld (t = %.2f s)\n",
               replay.total(), file_.c_str(), s.exp().steps(), s.exp().time());
    std::string wrote = WroteRunOutputsText(out);
    if (!exp_.frames_dir.empty())
      sim::AppendSprintf(wrote, ", %ld frames in %s", st.frames, exp_.frames_dir.c_str());
    if (!exp_.plots_dir.empty())
      sim::AppendSprintf(wrote, ", %ld figures in %s", st.figures, exp_.plots_dir.c_str());
    if (!exp_.video.empty() && st.error.empty()) wrote += ", " + exp_.video;
    std::fputs((wrote + "\n").c_str(), stdout);
  }
  int rc = 0;
  if (!st.error.empty()) {
    PrintExportFailed(st.error);
    rc = 4;
  }
  if (s.exp().status() == "numerical_fault") rc = 3;
  return rc;
}

}  // namespace formsim::app
