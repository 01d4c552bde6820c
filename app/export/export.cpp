#include "app/export/export.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "app/export/gif_writer.hpp"
#include "app/export/pictures.hpp"
#include "app/export/png_writer.hpp"
#include "app/export/video_writer.hpp"
#include "app/gui/offscreen_renderer.hpp"
#include "app/gui/ui.hpp"
#include "app/render/vector_fonts.hpp"
#include "app/render/world_view.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/wall_clock.hpp"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

using sim::WallSeconds;

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

// Frames of one output stream (video and --frames, or the GIF) fall due at k / fps.
struct FrameClock {
  double fps = 0;
  long next = 0, total = 0;
  bool Due(const sim::Experiment& exp) const {
    return next < total && static_cast<double>(next) / fps <= exp.time() + 0.5 * exp.dt();
  }
};

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
  char buf[1024];
  const double per = frames > 0 ? 1e3 / frames : 0;
  std::snprintf(
      buf, sizeof(buf),
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
  return buf;
}

ExportStats RunWithExport(sim::Session& session, const ExportOptions& opt,
                          const std::function<void(const ExportProgress&)>& progress,
                          const std::function<void()>& results_ready,
                          const std::function<bool()>& advance) {
  PrepareExport(opt);
  ExportStats st;
  const double t_start = WallSeconds();
  const Theme& theme = GetTheme(opt.theme);
  OffscreenRenderer renderer(opt.width, opt.height, theme);
  renderer.SetSceneOverlays(&opt.overlays, opt.legend);
  PngPool pool;
  st.png_threads = pool.threads();
  std::unique_ptr<VideoWriter> video;
  if (!opt.video.empty())
    video = std::make_unique<VideoWriter>(opt.video, opt.width, opt.height, opt.fps);
  // The GIF is drawn at its own size (text stays legible at 640 px); with --ui it is the
  // interface scaled down by ffmpeg.
  int gif_w = 0, gif_h = 0;
  GifFrameSize(opt, &gif_w, &gif_h);
  std::unique_ptr<GifWriter> gif;
  if (!opt.gif.empty())
    gif = opt.ui ? std::make_unique<GifWriter>(opt.gif, opt.width, opt.height, opt.gif_fps,
                                               opt.gif_width)
                 : std::make_unique<GifWriter>(opt.gif, gif_w, gif_h, opt.gif_fps, gif_w);
  std::unique_ptr<AppUi> ui;
  // Each stream has its own camera (the GIF's frames are smaller and come at another rate).
  View view, gif_view;
  AutoFit fit, gif_fit;
  for (AutoFit* f : {&fit, &gif_fit})
    f->set_mode(opt.whole_run ? AutoFit::Mode::kGrow : AutoFit::Mode::kTrack);
  const std::string caption = session.exp().setup().name;
  if (opt.ui) {
    ui = std::make_unique<AppUi>(session);
    ui->state().playing = false;
    ui->state().whole_run = opt.whole_run;
    ui->state().theme = opt.theme;
    ui->state().plots_every_frame = true;
    ui->state().overlays = opt.overlays;
    ui->state().legend = opt.legend;
    renderer.RenderUi(*ui);  // warm-up: ImGui lays windows out on their first frame
  }
  sim::Experiment& exp = session.exp();
  long ui_rendered_step = -1;  // --ui: one render serves both streams at the same step
  auto render = [&](bool first) -> const std::vector<std::uint8_t>& {
    renderer.Resize(opt.width, opt.height);
    if (ui) {
      if (ui_rendered_step == exp.steps()) return renderer.pixels();
      ui_rendered_step = exp.steps();
      return renderer.RenderUi(*ui);
    }
    return renderer.RenderWorld(exp, view, fit, first, caption);
  };
  auto render_gif = [&](bool first) -> const std::vector<std::uint8_t>& {
    if (ui) return render(first);
    renderer.Resize(gif_w, gif_h);
    return renderer.RenderWorld(exp, gif_view, gif_fit, first, caption);
  };

  const bool frames_wanted = !opt.frames_dir.empty() || video != nullptr;
  bool want_frames = frames_wanted;
  FrameClock main_clock{opt.fps, 0,
                        want_frames ? FrameCount(exp.setup().duration, exp.dt(), opt.fps) : 0};
  FrameClock gif_clock{opt.gif_fps, 0,
                       gif ? FrameCount(exp.setup().duration, exp.dt(), opt.gif_fps) : 0};
  auto fail = [&](const std::string& what) { st.error += (st.error.empty() ? "" : "; ") + what; };
  // Drops the frame outputs after a failure: the run goes on, the video file is removed.
  auto stop_frames = [&](const std::string& why) {
    fail(why);
    want_frames = false;
    main_clock.total = main_clock.next;
    if (video) {
      try {
        video->Close();
      } catch (const std::exception&) {
      }
      video.reset();
      std::error_code ec;
      fs::remove(opt.video, ec);
    }
  };
  auto stop_gif = [&](const std::string& why) {
    fail(why);
    gif.reset();  // the writer removes its temporary files; no GIF is written
    gif_clock.total = gif_clock.next;
  };
  auto emit_due_frames = [&]() {
    while (want_frames && main_clock.Due(exp)) {
      try {
        const auto& px = render(main_clock.next == 0);
        const double t0 = WallSeconds();
        if (video) video->Write(px);
        const double t1 = WallSeconds();
        if (!opt.frames_dir.empty()) {
          char name[32];
          std::snprintf(name, sizeof(name), "/frame_%05ld.png", main_clock.next);
          // The world's frame is handed to the encoder as rendered (the renderer takes a
          // written image's buffer for the next one); a --ui frame may serve the GIF too.
          std::vector<std::uint8_t> copy = ui ? pool.Copy(px) : renderer.TakePixels(pool.Spare());
          st.copy += WallSeconds() - t1;
          pool.Submit(opt.frames_dir + name, renderer.width(), renderer.height(), std::move(copy));
        }
        st.video += t1 - t0;
      } catch (const std::exception& e) {
        stop_frames(std::string("frames stopped at t = ") + std::to_string(exp.time()) +
                    " s: " + e.what());
        return;
      }
      ++main_clock.next;
      ++st.frames;
    }
    while (gif && gif_clock.Due(exp)) {
      try {
        gif->Write(render_gif(gif_clock.next == 0));
      } catch (const std::exception& e) {
        stop_gif(std::string("GIF stopped at t = ") + std::to_string(exp.time()) +
                 " s: " + e.what());
        return;
      }
      ++gif_clock.next;
      ++st.gif_frames;
    }
  };
  ExportProgress pr;
  auto report = [&](const std::string& status) {
    if (!progress) return;
    pr.t = exp.time();
    pr.fraction = exp.setup().duration > 0 ? exp.time() / exp.setup().duration : 1.0;
    pr.frames = main_clock.next + gif_clock.next;
    pr.frames_total = main_clock.total + gif_clock.total;
    pr.status = status;
    progress(pr);
  };

  emit_due_frames();
  auto step = [&] {
    if (advance) return advance();
    if (exp.finished()) return false;
    session.Step();
    return true;
  };
  while (true) {
    const double t0 = WallSeconds();
    if (!step()) break;
    st.sim += WallSeconds() - t0;
    emit_due_frames();
    // A whole-run snapshot without frames still needs the extent of the whole run.
    if (opt.whole_run && !want_frames && !opt.snapshots.empty() && exp.steps() % 10 == 0) {
      if (ui) {
        ui->TrackBounds();
      } else {
        Vec2 lo, hi;
        exp.Bounds(lo, hi);
        fit.Include(lo, hi);
      }
    }
    if ((exp.steps() & 31) == 0) report("");
  }
  const double t_finish = WallSeconds();
  try {
    pool.Wait();  // frames written before the results are reported
  } catch (const std::exception& e) {
    stop_frames(e.what());
  }
  if (video) {
    try {
      video->Close();
    } catch (const std::exception& e) {
      stop_frames(e.what());
    }
  }
  if (gif) {
    try {
      report("writing " + opt.gif + " (palette pass)");
      gif->Close();
    } catch (const std::exception& e) {
      stop_gif(e.what());
    }
  }
  // The results are safe on disk before any picture of the end is drawn.
  if (results_ready) results_ready();
  const float png_scale = static_cast<float>(opt.dpi / 96.0);
  // Every snapshot shows the same view: the camera moves once, then each format draws it.
  const bool jump = st.frames == 0;  // no frames before: fit at once
  bool framed = false;
  for (const std::string& snap : opt.snapshots) {
    try {
      report("writing " + snap);
      if (FormatOfFile(snap, "--snapshot") == FigureFormat::kPng) {
        const bool rescaled = renderer.scale() != png_scale;
        renderer.SetScale(png_scale);
        if (ui && jump && !framed) ui->state().fit_now = true;
        if (ui && rescaled) {
          renderer.Resize(opt.width, opt.height);
          renderer.RenderUi(*ui);  // a first frame at the new scale lays the windows out
        }
        ui_rendered_step = -1;
        const std::vector<std::uint8_t>* px = nullptr;
        if (!framed || ui) {
          px = &render(jump && !framed);
        } else {
          renderer.Resize(opt.width, opt.height);
          px = &renderer.RenderWorldAs(exp, view, caption);
        }
        framed = true;
        WritePng(snap, renderer.width(), renderer.height(), px->data(), opt.dpi);
        ++st.snapshots;
      } else {
        if (!framed)
          FrameWorldView(exp, static_cast<float>(opt.width), static_cast<float>(opt.height), view,
                         fit, jump);
        framed = true;
        FigureSize size;
        size.width = {static_cast<double>(opt.width), "px"};
        size.height = {static_cast<double>(opt.height), "px"};
        WriteVectorFigure(RecordWorld(exp, view, theme, caption, &opt.overlays, opt.legend), FormatOfFile(snap, "--snapshot"),
                          size, caption, snap);
        ++st.snapshots;
      }
    } catch (const std::exception& e) {
      fail(e.what());
    }
  }
  if (!opt.plots_dir.empty()) {
    const auto figures = exp.Figures();
    // Laid out at the layout size; the PNG has dpi / 96 pixels per printed pixel.
    const int w = opt.plot_size.LayoutWidth(), h = opt.plot_size.LayoutHeight();
    const float plot_scale = static_cast<float>(opt.dpi / 96.0 * opt.plot_size.LayoutScale());
    for (std::size_t i = 0; i < figures.size(); ++i) {
      const sim::FigureSpec& fig = figures[i];
      try {
        report("figure " + std::to_string(i + 1) + "/" + std::to_string(figures.size()));
        const PlotData data = ExportedPlot(fig, exp.recorder(), opt.titles, opt.log_y.count(fig.id) > 0);
        const std::string stem = opt.plots_dir + "/" + fig.id + ".";
        for (FigureFormat f : opt.plot_formats) {
          if (f == FigureFormat::kPng) {
            renderer.SetScale(plot_scale);
            const auto& px = renderer.RenderFigure(data, w, h);
            // Written at once (not through the frame pool, whose failure may be sticky).
            WritePng(stem + "png", renderer.width(), renderer.height(), px.data(), opt.dpi);
          } else {
            WriteVectorFigure(RecordPlot(data, w, h, theme), f, opt.plot_size, data.title,
                              stem + FormatExtension(f));
          }
          ++st.figure_files;
        }
        ++st.figures;
      } catch (const std::exception& e) {
        fail(e.what());
        break;
      }
    }
  }
  const double t_drain = WallSeconds();
  try {
    pool.Wait();
  } catch (const std::exception& e) {
    fail(e.what());
  }
  st.png_drain = WallSeconds() - t_drain;
  st.finish = WallSeconds() - t_finish;
  st.build = renderer.times().build;
  st.gl = renderer.times().gl;
  st.png_cpu = pool.encode_seconds();
  st.png_blocked = pool.blocked_seconds();
  st.wall = WallSeconds() - t_start;
  return st;
}

}  // namespace formsim::app
