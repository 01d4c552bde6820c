#include "app/export.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "app/figure_data.hpp"
#include "app/offscreen_renderer.hpp"
#include "app/png_writer.hpp"
#include "app/ui.hpp"
#include "app/video_writer.hpp"
#include "sim/core/run_output.hpp"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void EnsureParent(const std::string& file) {
  const fs::path parent = fs::path(file).parent_path();
  if (!parent.empty()) sim::PrepareOutputDir(parent.string());
}

}  // namespace

void ParseSize(const std::string& text, int* width, int* height) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    throw std::runtime_error("--size '" + text + "': expected WIDTHxHEIGHT, e.g. 1280x720");
  if (w < 64 || h < 64 || w > 8192 || h > 8192)
    throw std::runtime_error("--size '" + text + "': width and height must be in 64..8192");
  *width = w;
  *height = h;
}

void PrepareExport(const ExportOptions& opt) {
  if (!(opt.fps > 0 && opt.fps <= 1000))
    throw std::runtime_error("--fps must be in (0, 1000], got " + std::to_string(opt.fps));
  if (!opt.video.empty()) {
    VideoWriter::CheckAvailable(opt.width, opt.height);
    EnsureParent(opt.video);
  }
  if (!opt.frames_dir.empty()) sim::PrepareOutputDir(opt.frames_dir);
  if (!opt.plots_dir.empty()) sim::PrepareOutputDir(opt.plots_dir);
  if (!opt.snapshot.empty()) EnsureParent(opt.snapshot);
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
      "export: %ld frames + %ld figures in %.2f s wall (%.1f frames/s)\n"
      "  per frame: sim %.2f ms, build draw lists %.2f ms, GL raster %.2f ms, copy %.2f ms,"
      " video pipe %.2f ms\n"
      "  PNG: %.2f ms CPU per image on %d threads; main thread blocked %.2f s, final "
      "drain %.2f s\n",
      frames, figures, wall, wall > 0 ? frames / wall : 0.0, sim * per, build * per, gl * per,
      copy * per, video * per, (frames + figures) > 0 ? 1e3 * png_cpu / (frames + figures) : 0.0,
      png_threads, png_blocked, png_drain);
  return buf;
}

ExportStats RunWithExport(sim::Session& session, const ExportOptions& opt,
                          const std::function<void(double, double)>& progress,
                          const std::function<void()>& results_ready) {
  PrepareExport(opt);
  ExportStats st;
  const double t_start = Now();
  OffscreenRenderer renderer(opt.width, opt.height);
  PngPool pool;
  st.png_threads = pool.threads();
  std::unique_ptr<VideoWriter> video;
  if (!opt.video.empty())
    video = std::make_unique<VideoWriter>(opt.video, opt.width, opt.height, opt.fps);
  std::unique_ptr<AppUi> ui;
  View view;
  AutoFit fit;
  fit.set_mode(opt.whole_run ? AutoFit::Mode::kGrow : AutoFit::Mode::kTrack);
  const std::string caption = session.exp().setup().name;
  if (opt.ui) {
    ui = std::make_unique<AppUi>(session);
    ui->state().playing = false;
    ui->state().whole_run = opt.whole_run;
    renderer.RenderUi(*ui);  // warm-up: ImGui lays windows out on their first frame
  }
  auto render = [&](bool first) -> const std::vector<std::uint8_t>& {
    if (ui) return renderer.RenderUi(*ui);
    return renderer.RenderWorld(session.exp(), view, fit, first, caption);
  };

  bool want_frames = !opt.frames_dir.empty() || video != nullptr;
  sim::Experiment& exp = session.exp();
  const long total_frames = want_frames ? FrameCount(exp.setup().duration, exp.dt(), opt.fps) : 0;
  long next = 0;
  auto fail = [&](const std::string& what) {
    st.error += (st.error.empty() ? "" : "; ") + what;
  };
  // Drops the frame outputs after a failure: the run goes on, the video file is removed.
  auto stop_frames = [&](const std::string& why) {
    fail(why);
    want_frames = false;
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
  auto emit_due_frames = [&]() {
    while (want_frames && next < total_frames &&
           static_cast<double>(next) / opt.fps <= exp.time() + 0.5 * exp.dt()) {
      try {
        const auto& px = render(next == 0);
        const double t0 = Now();
        if (video) video->Write(px);
        const double t1 = Now();
        if (!opt.frames_dir.empty()) {
          char name[32];
          std::snprintf(name, sizeof(name), "/frame_%05ld.png", next);
          std::vector<std::uint8_t> copy(px);
          const double t2 = Now();
          st.copy += t2 - t1;
          pool.Submit(opt.frames_dir + name, renderer.width(), renderer.height(), std::move(copy));
        }
        st.video += t1 - t0;
      } catch (const std::exception& e) {
        stop_frames(std::string("frames stopped at t = ") + std::to_string(exp.time()) + " s: " + e.what());
        return;
      }
      ++next;
      ++st.frames;
    }
  };

  emit_due_frames();
  const double duration = exp.setup().duration;
  while (!exp.finished()) {
    const double t0 = Now();
    session.Step();
    st.sim += Now() - t0;
    emit_due_frames();
    // A whole-run snapshot without frames still needs the extent of the whole run.
    if (opt.whole_run && !want_frames && !opt.snapshot.empty() && exp.steps() % 10 == 0) {
      if (ui) {
        ui->TrackBounds();
      } else {
        Vec2 lo, hi;
        exp.Bounds(lo, hi);
        fit.Include(lo, hi);
      }
    }
    if (progress && (exp.steps() & 31) == 0) progress(exp.time() / duration, exp.time());
  }
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
  // The results are safe on disk before any picture of the end is drawn.
  if (results_ready) results_ready();
  if (!opt.snapshot.empty()) {
    try {
      if (ui && st.frames == 0) ui->state().fit_now = true;  // no frames before: fit at once
      const auto& px = render(st.frames == 0);
      WritePng(opt.snapshot, renderer.width(), renderer.height(), px.data());
    } catch (const std::exception& e) {
      fail(e.what());
    }
  }
  if (!opt.plots_dir.empty()) {
    for (const auto& fig : exp.Figures()) {
      try {
        const PlotData data = ResolveFigure(fig, exp.recorder());
        if (!data.error.empty()) throw std::runtime_error("figure '" + fig.id + "': " + data.error);
        const auto& px = renderer.RenderFigure(data, opt.plot_width, opt.plot_height);
        // Written at once (not through the frame pool, whose failure may be sticky).
        WritePng(opt.plots_dir + "/" + fig.id + ".png", opt.plot_width, opt.plot_height, px.data());
        ++st.figures;
      } catch (const std::exception& e) {
        fail(e.what());
        break;
      }
    }
  }
  const double t_drain = Now();
  try {
    pool.Wait();
  } catch (const std::exception& e) {
    fail(e.what());
  }
  st.png_drain = Now() - t_drain;
  st.build = renderer.times().build;
  st.gl = renderer.times().gl;
  st.png_cpu = pool.encode_seconds();
  st.png_blocked = pool.blocked_seconds();
  st.wall = Now() - t_start;
  return st;
}

}  // namespace formsim::app
