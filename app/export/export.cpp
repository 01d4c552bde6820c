#include "app/export/export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "app/export/gif_writer.hpp"
#include "app/export/video_writer.hpp"
#include "app/render/vector_fonts.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

void EnsureParent(const std::string& file) {
  const fs::path parent = fs::path(file).parent_path();
  if (!parent.empty()) sim::PrepareOutputDir(parent.string());
}

// A file flag must not name an existing folder.
void CheckFileName(const std::string& file, const std::string& flag) {
  std::error_code ec;
  if (fs::is_directory(file, ec))
    throw std::runtime_error(flag + " '" + file + "': is a folder; give a file name");
}

bool WantsVector(const ExportOptions& opt) {
  if (!opt.plots_dir.empty())
    for (FigureFormat f : opt.plot_formats)
      if (f != FigureFormat::kPng) return true;
  for (const std::string& snap : opt.snapshots)
    if (FormatOfFile(snap, "--snapshot") != FigureFormat::kPng) return true;
  return false;
}

bool WantsPngPlots(const ExportOptions& opt) {
  if (opt.plots_dir.empty()) return false;
  for (FigureFormat f : opt.plot_formats)
    if (f == FigureFormat::kPng) return true;
  return false;
}

}  // namespace

void ParseSize(const std::string& text, int* width, int* height, const std::string& flag) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    throw std::runtime_error(flag + " '" + text + "': expected WIDTHxHEIGHT, e.g. 1280x720");
  if (w < 64 || h < 64 || w > 8192 || h > 8192)
    throw std::runtime_error(flag + " '" + text + "': width and height must be in 64..8192");
  *width = w;
  *height = h;
}

void GifFrameSize(const ExportOptions& opt, int* width, int* height) {
  *width = opt.gif_width;
  *height = std::max(16, static_cast<int>(std::lround(static_cast<double>(opt.gif_width) *
                                                      opt.height / opt.width)));
}

void PrepareExport(const ExportOptions& opt) {
  if (!(opt.fps > 0 && opt.fps <= 1000))
    throw std::runtime_error("--fps must be in (0, 1000], got " + sim::FormatDouble(opt.fps));
  ParseDpi(opt.dpi);
  if (!opt.video.empty()) {
    VideoWriter::CheckAvailable(opt.video, opt.width, opt.height);
    CheckFileName(opt.video, "--video");
    EnsureParent(opt.video);
  }
  if (!opt.gif.empty()) {
    GifWriter::CheckAvailable(opt.gif, opt.gif_fps, opt.gif_width);
    CheckFileName(opt.gif, "--gif");
    EnsureParent(opt.gif);
  }
  for (const std::string& snap : opt.snapshots) {
    const FigureFormat f = FormatOfFile(snap, "--snapshot");
    if (opt.ui && f != FigureFormat::kPng)
      throw std::runtime_error("--snapshot '" + snap +
                               "' with --ui: the interface is a picture of ImGui panels and is "
                               "saved as .png only (without --ui the world view can be .svg or "
                               ".pdf)");
    if (f == FigureFormat::kPng) CheckDeviceSize(opt.width, opt.height, opt.dpi, "--snapshot");
    CheckFileName(snap, "--snapshot");
  }
  if (WantsPngPlots(opt))
    CheckDeviceSize(opt.plot_size.width.Pixels(), opt.plot_size.height.Pixels(), opt.dpi,
                    "--plot-size " + opt.plot_size.Text());
  if (WantsVector(opt)) VectorFonts::Get();  // the fonts SVG and PDF need, before simulating
  if (!opt.frames_dir.empty()) {
    CheckFolderName(opt.frames_dir, "--frames", "PNG frames go into it as frame_00000.png ...");
    sim::PrepareOutputDir(opt.frames_dir);
  }
  if (!opt.plots_dir.empty()) {
    CheckFolderName(opt.plots_dir, "--plots",
                    "one file per figure goes into it; choose formats with --plot-format "
                    "png,svg,pdf");
    sim::PrepareOutputDir(opt.plots_dir);
  }
  for (const std::string& snap : opt.snapshots) EnsureParent(snap);
}

long FrameCount(double duration, double dt, double fps) {
  long n = 0;
  while (static_cast<double>(n) / fps < duration - 0.5 * dt) ++n;
  return n;
}

std::string ExportStats::Report() const {
  const double per = frames > 0 ? 1e3 / frames : 0;
  return sim::Sprintf(
      "export: %ld frames + %ld GIF frames + %ld figures (%ld files) in %.2f s wall (%.1f "
      "frames/s)\n"
      "  per frame: sim %.2f ms, build draw lists %.2f ms, GL raster %.2f ms, copy %.2f ms,"
      " video pipe %.2f ms\n"
      "  PNG: %.2f ms CPU per image on %d threads; main thread blocked %.2f s, final "
      "drain %.2f s\n"
      "  after the run (GIF palette pass, snapshot, figures): %.2f s\n",
      frames, gif_frames, figures, figure_files, wall,
      wall > 0 ? (frames + gif_frames) / wall : 0.0, sim * per, build * per, gl * per, copy * per,
      video * per, (frames + figures) > 0 ? 1e3 * png_cpu / (frames + figures) : 0.0, png_threads,
      png_blocked, png_drain, finish);
}

}  // namespace formsim::app
