// RunWithExport: one run of the session with its pictures, from the first step to the last
// figure. The frame streams (video and --frames, the GIF) are written while the run goes on;
// the snapshots and figures after it. A stream that fails is dropped and the run goes on.
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "app/export/export.hpp"
#include "app/export/gif_writer.hpp"
#include "app/export/pictures.hpp"
#include "app/export/png_writer.hpp"
#include "app/export/video_writer.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "app/render/world_view.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/wall_clock.hpp"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

using sim::WallSeconds;
using ExportProgressFn = std::function<void(const ExportProgress&)>;

// Frames of one output stream (video and --frames, or the GIF) fall due at k / fps.
struct ExportFrameClock {
  double fps = 0;
  long next = 0, total = 0;
  bool Due(const sim::Experiment& exp) const {
    return next < total && static_cast<double>(next) / fps <= exp.time() + 0.5 * exp.dt();
  }
};

// The renderer, the writers and the interface of one RunWithExport, in the order they are
// used: Simulate, CloseStreams, (the results are written), WriteSnapshots, WriteFigures, Finish.
class ExportRun {
 public:
  ExportRun(sim::Session& session, const ExportOptions& opt, const ExportProgressFn& progress,
            const UiFramesMaker& make_ui);
  // Steps the run to its end (through `advance` when given), writing the frames due.
  void Simulate(const std::function<bool()>& advance);
  // Waits for the frames' PNGs and closes the video and the GIF.
  void CloseStreams();
  void WriteSnapshots();
  void WriteFigures();
  // Waits for the last PNGs and returns the statistics (times from `t_start`, `t_finish`).
  ExportStats Finish(double t_start, double t_finish);

 private:
  void OpenStreams();
  const std::vector<std::uint8_t>& Render(bool first);
  const std::vector<std::uint8_t>& RenderGif(bool first);
  void Fail(const std::string& what);
  void StopFrames(const std::string& why);
  void StopGif(const std::string& why);
  void EmitDueFrames();
  bool EmitMainFrames();
  void WriteMainFrame();
  void EmitGifFrames();
  bool Step(const std::function<bool()>& advance);
  void TrackWholeRun();
  void Report(const std::string& status);
  void WritePngSnapshot(const std::string& snap, float png_scale, bool jump, bool& framed);
  void WriteVectorSnapshot(const std::string& snap, FigureFormat format, bool jump, bool& framed);
  void WriteFigure(const sim::FigureSpec& fig);

  sim::Session& session_;
  const ExportOptions& opt_;
  const ExportProgressFn& progress_;
  ExportStats st_;
  const Theme& theme_;
  OffscreenRenderer renderer_;
  PngPool pool_;
  std::unique_ptr<VideoWriter> video_;
  int gif_w_ = 0, gif_h_ = 0;
  std::unique_ptr<GifWriter> gif_;
  std::unique_ptr<UiFrames> ui_;
  // Each stream has its own camera (the GIF's frames are smaller and come at another rate).
  View view_, gif_view_;
  AutoFit fit_, gif_fit_;
  std::string caption_;
  sim::Experiment* exp_ = nullptr;
  long ui_rendered_step_ = -1;  // --ui: one render serves both streams at the same step
  bool want_frames_ = false;
  ExportFrameClock main_clock_, gif_clock_;
  ExportProgress pr_;
};

ExportRun::ExportRun(sim::Session& session, const ExportOptions& opt,
                     const ExportProgressFn& progress, const UiFramesMaker& make_ui)
    : session_(session),
      opt_(opt),
      progress_(progress),
      theme_(GetTheme(opt.theme)),
      renderer_(opt.width, opt.height, theme_) {
  renderer_.SetSceneOverlays(&opt.overlays, opt.legend);
  st_.png_threads = pool_.threads();
  OpenStreams();
  for (AutoFit* f : {&fit_, &gif_fit_})
    f->set_mode(opt.whole_run ? AutoFit::Mode::kGrow : AutoFit::Mode::kTrack);
  caption_ = session.exp().setup().name;
  if (opt.ui) {
    ui_ = make_ui(session, opt);
    ui_->Render(renderer_);  // warm-up: ImGui lays windows out on their first frame
  }
  exp_ = &session.exp();
  want_frames_ = !opt.frames_dir.empty() || video_ != nullptr;
  const double duration = exp_->setup().duration, dt = exp_->dt();
  main_clock_ = {opt.fps, 0, want_frames_ ? FrameCount(duration, dt, opt.fps) : 0};
  gif_clock_ = {opt.gif_fps, 0, gif_ ? FrameCount(duration, dt, opt.gif_fps) : 0};
}

void ExportRun::OpenStreams() {
  if (!opt_.video.empty())
    video_ = std::make_unique<VideoWriter>(opt_.video, opt_.width, opt_.height, opt_.fps);
  // The GIF is drawn at its own size (text stays legible at 640 px); with --ui it is the
  // interface scaled down by ffmpeg.
  GifFrameSize(opt_, &gif_w_, &gif_h_);
  if (opt_.gif.empty()) return;
  gif_ = opt_.ui ? std::make_unique<GifWriter>(opt_.gif, opt_.width, opt_.height, opt_.gif_fps,
                                               opt_.gif_width)
                 : std::make_unique<GifWriter>(opt_.gif, gif_w_, gif_h_, opt_.gif_fps, gif_w_);
}

const std::vector<std::uint8_t>& ExportRun::Render(bool first) {
  renderer_.Resize(opt_.width, opt_.height);
  if (ui_) {
    if (ui_rendered_step_ == exp_->steps()) return renderer_.pixels();
    ui_rendered_step_ = exp_->steps();
    return ui_->Render(renderer_);
  }
  return renderer_.RenderWorld(*exp_, view_, fit_, first, caption_);
}

const std::vector<std::uint8_t>& ExportRun::RenderGif(bool first) {
  if (ui_) return Render(first);
  renderer_.Resize(gif_w_, gif_h_);
  return renderer_.RenderWorld(*exp_, gif_view_, gif_fit_, first, caption_);
}

void ExportRun::Fail(const std::string& what) {
  st_.error += (st_.error.empty() ? "" : "; ") + what;
}

// Drops the frame outputs after a failure: the run goes on, the video file is removed.
void ExportRun::StopFrames(const std::string& why) {
  Fail(why);
  want_frames_ = false;
  main_clock_.total = main_clock_.next;
  if (!video_) return;
  try {
    video_->Close();
  } catch (const std::exception&) {
  }
  video_.reset();
  std::error_code ec;
  fs::remove(opt_.video, ec);
}

void ExportRun::StopGif(const std::string& why) {
  Fail(why);
  gif_.reset();  // the writer removes its temporary files; no GIF is written
  gif_clock_.total = gif_clock_.next;
}

// A failing main stream skips the GIF's frames of this step (they come at the next one).
void ExportRun::EmitDueFrames() {
  if (EmitMainFrames()) EmitGifFrames();
}

bool ExportRun::EmitMainFrames() {
  while (want_frames_ && main_clock_.Due(*exp_)) {
    try {
      WriteMainFrame();
    } catch (const std::exception& e) {
      StopFrames(std::string("frames stopped at t = ") + std::to_string(exp_->time()) +
                 " s: " + e.what());
      return false;
    }
    ++main_clock_.next;
    ++st_.frames;
  }
  return true;
}

void ExportRun::WriteMainFrame() {
  const auto& px = Render(main_clock_.next == 0);
  const double t0 = WallSeconds();
  if (video_) video_->Write(px);
  const double t1 = WallSeconds();
  if (!opt_.frames_dir.empty()) {
    const std::string name = sim::Sprintf("/frame_%05ld.png", main_clock_.next);
    // The world's frame is handed to the encoder as rendered (the renderer takes a written
    // image's buffer for the next one); a --ui frame may serve the GIF too.
    std::vector<std::uint8_t> copy = ui_ ? pool_.Copy(px) : renderer_.TakePixels(pool_.Spare());
    st_.copy += WallSeconds() - t1;
    pool_.Submit(opt_.frames_dir + name, renderer_.width(), renderer_.height(), std::move(copy));
  }
  st_.video += t1 - t0;
}

void ExportRun::EmitGifFrames() {
  while (gif_ && gif_clock_.Due(*exp_)) {
    try {
      gif_->Write(RenderGif(gif_clock_.next == 0));
    } catch (const std::exception& e) {
      StopGif(std::string("GIF stopped at t = ") + std::to_string(exp_->time()) +
              " s: " + e.what());
      return;
    }
    ++gif_clock_.next;
    ++st_.gif_frames;
  }
}

bool ExportRun::Step(const std::function<bool()>& advance) {
  if (advance) return advance();
  if (exp_->finished()) return false;
  session_.Step();
  return true;
}

// A whole-run snapshot without frames still needs the extent of the whole run.
void ExportRun::TrackWholeRun() {
  if (ui_) {
    ui_->TrackBounds();
    return;
  }
  Vec2 lo, hi;
  exp_->Bounds(lo, hi);
  fit_.Include(lo, hi);
}

void ExportRun::Report(const std::string& status) {
  if (!progress_) return;
  pr_.t = exp_->time();
  pr_.fraction = exp_->setup().duration > 0 ? exp_->time() / exp_->setup().duration : 1.0;
  pr_.frames = main_clock_.next + gif_clock_.next;
  pr_.frames_total = main_clock_.total + gif_clock_.total;
  pr_.status = status;
  progress_(pr_);
}

void ExportRun::Simulate(const std::function<bool()>& advance) {
  EmitDueFrames();
  while (true) {
    const double t0 = WallSeconds();
    if (!Step(advance)) break;
    st_.sim += WallSeconds() - t0;
    EmitDueFrames();
    if (opt_.whole_run && !want_frames_ && !opt_.snapshots.empty() && exp_->steps() % 10 == 0)
      TrackWholeRun();
    if ((exp_->steps() & 31) == 0) Report("");
  }
}

void ExportRun::CloseStreams() {
  try {
    pool_.Wait();  // frames written before the results are reported
  } catch (const std::exception& e) {
    StopFrames(e.what());
  }
  if (video_) {
    try {
      video_->Close();
    } catch (const std::exception& e) {
      StopFrames(e.what());
    }
  }
  if (gif_) {
    try {
      Report("writing " + opt_.gif + " (palette pass)");
      gif_->Close();
    } catch (const std::exception& e) {
      StopGif(e.what());
    }
  }
}

// Every snapshot shows the same view: the camera moves once, then each format draws it.
void ExportRun::WriteSnapshots() {
  const float png_scale = static_cast<float>(opt_.dpi / 96.0);
  const bool jump = st_.frames == 0;  // no frames before: fit at once
  bool framed = false;
  for (const std::string& snap : opt_.snapshots) {
    try {
      Report("writing " + snap);
      const FigureFormat format = FormatOfFile(snap, "--snapshot");
      if (format == FigureFormat::kPng)
        WritePngSnapshot(snap, png_scale, jump, framed);
      else
        WriteVectorSnapshot(snap, format, jump, framed);
      ++st_.snapshots;
    } catch (const std::exception& e) {
      Fail(e.what());
    }
  }
}

void ExportRun::WritePngSnapshot(const std::string& snap, float png_scale, bool jump,
                                 bool& framed) {
  const bool rescaled = renderer_.scale() != png_scale;
  renderer_.SetScale(png_scale);
  if (ui_ && jump && !framed) ui_->FitNow();
  if (ui_ && rescaled) {
    renderer_.Resize(opt_.width, opt_.height);
    ui_->Render(renderer_);  // a first frame at the new scale lays the windows out
  }
  ui_rendered_step_ = -1;
  const std::vector<std::uint8_t>* px = nullptr;
  if (!framed || ui_) {
    px = &Render(jump && !framed);
  } else {
    renderer_.Resize(opt_.width, opt_.height);
    px = &renderer_.RenderWorldAs(*exp_, view_, caption_);
  }
  framed = true;
  WritePng(snap, renderer_.width(), renderer_.height(), px->data(), opt_.dpi);
}

void ExportRun::WriteVectorSnapshot(const std::string& snap, FigureFormat format, bool jump,
                                    bool& framed) {
  if (!framed)
    FrameWorldView(*exp_, static_cast<float>(opt_.width), static_cast<float>(opt_.height), view_,
                   fit_, jump);
  framed = true;
  FigureSize size;
  size.width = {static_cast<double>(opt_.width), "px"};
  size.height = {static_cast<double>(opt_.height), "px"};
  WriteVectorFigure(RecordWorld(*exp_, view_, theme_, caption_, &opt_.overlays, opt_.legend),
                    format, size, caption_, snap);
}

void ExportRun::WriteFigures() {
  if (opt_.plots_dir.empty()) return;
  const auto figures = exp_->Figures();
  for (std::size_t i = 0; i < figures.size(); ++i) {
    try {
      Report("figure " + std::to_string(i + 1) + "/" + std::to_string(figures.size()));
      WriteFigure(figures[i]);
      ++st_.figures;
    } catch (const std::exception& e) {
      Fail(e.what());
      break;
    }
  }
}

// One figure in every format asked for, laid out at the layout size; the PNG has dpi / 96
// pixels per printed pixel.
void ExportRun::WriteFigure(const sim::FigureSpec& fig) {
  const int w = opt_.plot_size.LayoutWidth(), h = opt_.plot_size.LayoutHeight();
  const float plot_scale = static_cast<float>(opt_.dpi / 96.0 * opt_.plot_size.LayoutScale());
  const PlotData data =
      ExportedPlot(fig, exp_->recorder(), opt_.titles, opt_.log_y.count(fig.id) > 0);
  const std::string stem = opt_.plots_dir + "/" + fig.id + ".";
  for (FigureFormat f : opt_.plot_formats) {
    if (f == FigureFormat::kPng) {
      renderer_.SetScale(plot_scale);
      const auto& px = renderer_.RenderFigure(data, w, h);
      // Written at once (not through the frame pool, whose failure may be sticky).
      WritePng(stem + "png", renderer_.width(), renderer_.height(), px.data(), opt_.dpi);
    } else {
      WriteVectorFigure(RecordPlot(data, w, h, theme_), f, opt_.plot_size, data.title,
                        stem + FormatExtension(f));
    }
    ++st_.figure_files;
  }
}

ExportStats ExportRun::Finish(double t_start, double t_finish) {
  const double t_drain = WallSeconds();
  try {
    pool_.Wait();
  } catch (const std::exception& e) {
    Fail(e.what());
  }
  st_.png_drain = WallSeconds() - t_drain;
  st_.finish = WallSeconds() - t_finish;
  st_.build = renderer_.times().build;
  st_.gl = renderer_.times().gl;
  st_.png_cpu = pool_.encode_seconds();
  st_.png_blocked = pool_.blocked_seconds();
  st_.wall = WallSeconds() - t_start;
  return st_;
}

}  // namespace

ExportStats RunWithExport(sim::Session& session, const ExportOptions& opt,
                          const std::function<void(const ExportProgress&)>& progress,
                          const std::function<void()>& results_ready,
                          const std::function<bool()>& advance, const UiFramesMaker& make_ui) {
  if (opt.ui && !make_ui)
    throw std::invalid_argument("RunWithExport: --ui needs the interface (UiFramesMaker)");
  PrepareExport(opt);
  const double t_start = WallSeconds();
  ExportRun run(session, opt, progress, make_ui);
  run.Simulate(advance);
  const double t_finish = WallSeconds();
  run.CloseStreams();
  // The results are safe on disk before any picture of the end is drawn.
  if (results_ready) results_ready();
  run.WriteSnapshots();
  run.WriteFigures();
  return run.Finish(t_start, t_finish);
}

}  // namespace formsim::app
