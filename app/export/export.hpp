#pragma once
/// \file Headless export for `formsim run`: PNG frames, an MP4 video and a looping GIF while the
/// run goes on, then a final snapshot (PNG, SVG or PDF) and every figure in the chosen formats,
/// rendered offscreen (OSMesa) or recorded as vectors, with the GUI's drawing code and theme.
/// No display needed. The whole interface (--ui) is drawn through UiFrames, which the GUI
/// implements (app/gui/ui_offscreen.hpp): export knows the renderer, never the window.

#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/export/figure_export.hpp"
#include "app/export/figure_size.hpp"
#include "app/export/figure_titles.hpp"
#include "app/render/theme.hpp"
#include "app/render/world_view.hpp"
#include "sim/session/session.hpp"

namespace formsim::app {

class OffscreenRenderer;

struct ExportOptions {
  std::string frames_dir;              ///< frame_00000.png ... at `fps`
  std::vector<std::string> snapshots;  ///< the final view, each .png, .svg or .pdf by extension
  std::string plots_dir;               ///< <figure id>.<format> per figure and format
  std::string video;                   ///< .mp4 (.mkv, .mov) through ffmpeg
  std::string gif;                     ///< looping GIF through ffmpeg with a palette of the run
  double fps = 30.0;
  int width = 1280, height = 720;  ///< frames, video and snapshot, logical pixels
  FigureSize plot_size;            ///< figures (default 960x600 px)
  std::vector<FigureFormat> plot_formats = {FigureFormat::kPng};
  double dpi = 96;  ///< PNG figures and PNG snapshot: dpi / 96 pixels per logical pixel
  ThemeId theme = ThemeId::kLight;
  TitleMode titles = TitleMode::kFull;  ///< --titles: how much of each figure's title is shown
  std::set<std::string> log_y;          ///< --log-y: ids of the figures drawn with a log y axis
  double gif_fps = 15;
  int gif_width = 640;
  bool ui = false;         ///< draw the GUI panels around the world view
  bool whole_run = false;  ///< camera shows everything since the start (default: tracks robots)
  /// Overlays of the scene in frames, video, GIF and snapshot (--overlay); --legend adds the
  /// legend of the marks drawn.
  std::set<std::string> overlays = DefaultSceneOverlays();
  bool legend = false;
  bool any() const {
    return !frames_dir.empty() || !snapshots.empty() || !plots_dir.empty() || !video.empty() ||
           !gif.empty();
  }
};

/// Where the time went (seconds of wall time unless said otherwise).
struct ExportStats {
  long frames = 0, gif_frames = 0, figures = 0, figure_files = 0, snapshots = 0;
  double wall = 0, sim = 0, build = 0, gl = 0, copy = 0, video = 0;
  double png_cpu = 0;      ///< summed over worker threads
  double png_blocked = 0;  ///< main thread waiting for a free queue slot
  double png_drain = 0;    ///< waiting for the last PNGs after the run
  double finish = 0;       ///< after the run: GIF palette pass, snapshot, figures
  int png_threads = 0;
  /// Export failures (a full disk, ffmpeg dying): the simulation went on and its results were
  /// written; partial outputs were removed. Empty when every export succeeded.
  std::string error;
  std::string Report() const;
};

/// What the export is doing, for a progress line.
struct ExportProgress {
  double fraction = 0;                ///< of the simulated duration
  double t = 0;                       ///< simulated time
  long frames = 0, frames_total = 0;  ///< frames (video, --frames and GIF) done and due
  std::string status;  ///< after the run: "writing v.gif", "figure 3/7" ("" while running)
};

/// The whole interface around the world view in --ui frames and snapshot, as RunWithExport
/// needs it: drawn at the session's current step, its camera tracked and refitted.
class UiFrames {
 public:
  virtual ~UiFrames() = default;
  /// Draws the interface as it stands into `renderer` (its size and scale) and returns the pixels.
  virtual const std::vector<std::uint8_t>& Render(OffscreenRenderer& renderer) = 0;
  /// With "whole run" on, adds the experiment's current bounds to the camera's union (a final
  /// snapshot without frames).
  virtual void TrackBounds() = 0;
  /// Fits the camera to the scene at once on the next render.
  virtual void FitNow() = 0;
};

/// Makes the interface of `session` set up from `opt` (theme, overlays, legend, whole run).
/// Called once the renderer's ImGui context exists.
using UiFramesMaker =
    std::function<std::unique_ptr<UiFrames>(sim::Session& session, const ExportOptions& opt)>;

/// Parses "1280x720" for `flag`. Throws std::runtime_error naming the flag on malformed or
/// out-of-range sizes.
void ParseSize(const std::string& text, int* width, int* height,
               const std::string& flag = "--size");

/// Checks the options and creates the output folders, before anything is simulated: a missing
/// ffmpeg, an odd video size, a file name given as a folder (or the reverse), an unknown
/// extension or an unwritable folder fail here. Throws std::runtime_error.
void PrepareExport(const ExportOptions& opt);

/// Number of frames a run of `duration` s gives at `fps` (frames at t = k/fps, t < duration).
long FrameCount(double duration, double dt, double fps);

/// Size of the GIF's frames for `opt`: `gif_width` wide with the aspect of the frames.
void GifFrameSize(const ExportOptions& opt, int* width, int* height);

/// Runs the session's experiment to the end (the same steps as a plain run), writing frames,
/// video and GIF as it goes; then calls `results_ready()` (the caller writes the CSV and
/// summary), then renders the snapshot and figures. An export that fails never stops the
/// simulation or loses its results: it is dropped, its partial file removed, and the failure
/// reported in ExportStats::error. `progress` is called now and then. `advance`, when given,
/// makes one step of the run (applying first whatever is due at that step, as a replay does)
/// and returns false once the run is over; by default the session steps until its experiment
/// has finished. With `opt.ui`, `make_ui` gives the interface drawn into frames and snapshot
/// (std::invalid_argument without it).
ExportStats RunWithExport(sim::Session& session, const ExportOptions& opt,
                          const std::function<void(const ExportProgress&)>& progress = {},
                          const std::function<void()>& results_ready = {},
                          const std::function<bool()>& advance = {},
                          const UiFramesMaker& make_ui = {});

}  // namespace formsim::app
