#pragma once
/// \file Headless export for `formsim run`: PNG frames, a final snapshot, one PNG per figure and
/// an MP4 video, rendered offscreen (OSMesa) with the GUI's drawing code. No display needed.

#include <functional>
#include <string>

#include "sim/core/session.hpp"

namespace formsim::app {

struct ExportOptions {
  std::string frames_dir;  ///< frame_00000.png ... at `fps`
  std::string snapshot;    ///< PNG of the final view
  std::string plots_dir;   ///< <figure id>.png per figure
  std::string video;       ///< .mp4 through ffmpeg
  double fps = 30.0;
  int width = 1280, height = 720;
  int plot_width = 960, plot_height = 600;
  bool ui = false;         ///< draw the GUI panels around the world view
  bool whole_run = false;  ///< camera shows everything since the start (default: tracks robots)
  bool any() const {
    return !frames_dir.empty() || !snapshot.empty() || !plots_dir.empty() || !video.empty();
  }
};

/// Where the time went (seconds of wall time unless said otherwise).
struct ExportStats {
  long frames = 0, figures = 0;
  double wall = 0, sim = 0, build = 0, gl = 0, copy = 0, video = 0;
  double png_cpu = 0;      ///< summed over worker threads
  double png_blocked = 0;  ///< main thread waiting for a free queue slot
  double png_drain = 0;    ///< waiting for the last PNGs after the run
  int png_threads = 0;
  /// Export failures (a full disk, ffmpeg dying): the simulation went on and its results were
  /// written; partial outputs were removed. Empty when every export succeeded.
  std::string error;
  std::string Report() const;
};

/// Parses "1280x720". Throws std::runtime_error on malformed or out-of-range sizes.
void ParseSize(const std::string& text, int* width, int* height);

/// Checks the options and creates the output folders, before anything is simulated: a missing
/// ffmpeg, an odd video size or an unwritable folder fail here. Throws std::runtime_error.
void PrepareExport(const ExportOptions& opt);

/// Number of frames a run of `duration` s gives at `fps` (frames at t = k/fps, t < duration).
long FrameCount(double duration, double dt, double fps);

/// Runs the session's experiment to the end (the same steps as a plain run), writing frames
/// and video as it goes; then calls `results_ready()` (the caller writes the CSV and summary),
/// then renders the snapshot and figures. An export that fails never stops the simulation or
/// loses its results: it is dropped, its partial file removed, and the failure reported in
/// ExportStats::error. `progress(fraction, t)` is called now and then.
ExportStats RunWithExport(sim::Session& session, const ExportOptions& opt,
                          const std::function<void(double, double)>& progress = {},
                          const std::function<void()>& results_ready = {});

}  // namespace formsim::app
