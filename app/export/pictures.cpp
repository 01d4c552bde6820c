#include "app/export/pictures.hpp"

#include <mutex>
#include <set>
#include <stdexcept>

#include "app/export/figure_data.hpp"
#include "app/export/figure_export.hpp"
#include "app/export/pdf_writer.hpp"
#include "app/export/png_writer.hpp"
#include "app/export/svg_writer.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "app/render/theme.hpp"
#include "app/render/view.hpp"
#include "app/render/world_view.hpp"

namespace formsim::app {
namespace {

// ImGui draws through one current context per process: one offscreen renderer at a time.
std::mutex& PictureMutex() {
  static std::mutex mu;
  return mu;
}

void CheckSide(int pixels, const char* what) {
  // As --size takes them (ParseSize).
  if (pixels < 64 || pixels > 8192)
    throw std::runtime_error(std::string(what) + " " + std::to_string(pixels) +
                             ": must be in 64 ... 8192 pixels");
}

FigureFormat ParseFormat(const std::string& format) {
  for (FigureFormat f : {FigureFormat::kPng, FigureFormat::kSvg, FigureFormat::kPdf})
    if (format == FormatExtension(f)) return f;
  throw std::runtime_error("format '" + format + "': expected png, svg or pdf");
}

}  // namespace

std::vector<std::uint8_t> RenderWorldRgb(const sim::Experiment& exp, int width, int height,
                                         const std::string& theme, const std::string& overlays,
                                         bool legend) {
  CheckSide(width, "width");
  CheckSide(height, "height");
  const Theme& th = GetTheme(ParseTheme(theme, "theme"));
  std::set<std::string> scene = DefaultSceneOverlays();
  if (const std::string err = ParseSceneOverlays(overlays, &scene); !err.empty())
    throw std::runtime_error("overlays '" + overlays + "': " + err);
  std::lock_guard<std::mutex> lock(PictureMutex());
  // A fresh renderer and camera, as the snapshot of a run exported without frames.
  OffscreenRenderer renderer(width, height, th);
  renderer.SetSceneOverlays(&scene, legend);
  View view;
  AutoFit fit;
  fit.set_mode(AutoFit::Mode::kTrack);
  const std::vector<std::uint8_t>& rgba =
      renderer.RenderWorld(exp, view, fit, true, exp.setup().name);
  const std::size_t n = static_cast<std::size_t>(renderer.width()) * renderer.height();
  std::vector<std::uint8_t> rgb(n * 3);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = rgba[i * 4 + c];
  return rgb;
}

std::vector<std::string> FigureNames(const sim::Experiment& exp) {
  std::vector<std::string> names;
  for (const sim::FigureSpec& f : exp.Figures()) names.push_back(f.id);
  return names;
}

PlotData ExportedPlot(const sim::FigureSpec& spec, const sim::Recorder& recorder, TitleMode titles,
                      bool log_y) {
  PlotData data = ResolveFigure(spec, recorder);
  if (!data.error.empty()) throw std::runtime_error("figure '" + spec.id + "': " + data.error);
  data.title = TitleFor(data.title, titles);
  data.log_y = log_y;
  return data;
}

std::string FigureBytes(const sim::Experiment& exp, const std::string& name,
                        const std::string& format, const std::string& theme) {
  const FigureFormat f = ParseFormat(format);
  const Theme& th = GetTheme(ParseTheme(theme, "theme"));
  const std::vector<sim::FigureSpec> figures = exp.Figures();
  const sim::FigureSpec* spec = nullptr;
  std::string names;
  for (const sim::FigureSpec& fig : figures) {
    if (fig.id == name) spec = &fig;
    names += (names.empty() ? "" : ", ") + fig.id;
  }
  if (spec == nullptr)
    throw std::runtime_error("figure '" + name + "': no such figure (the figures of " +
                             exp.setup().name + " now: " + (names.empty() ? "none" : names) + ")");
  // Vector figures too: the drawing code may share state with an ImGui frame being drawn.
  std::lock_guard<std::mutex> lock(PictureMutex());
  const PlotData data = ExportedPlot(*spec, exp.recorder(), TitleMode::kFull, false);
  const FigureSize size;  // --plot-size's default, 960x600 px
  const int w = size.LayoutWidth(), h = size.LayoutHeight();
  if (f == FigureFormat::kSvg) return SvgDocument(RecordPlot(data, w, h, th), size, data.title);
  if (f == FigureFormat::kPdf) return PdfDocument(RecordPlot(data, w, h, th), size, data.title);
  OffscreenRenderer renderer(w, h, th);
  renderer.SetScale(static_cast<float>(size.LayoutScale()));  // 96 dpi
  const std::vector<std::uint8_t>& px = renderer.RenderFigure(data, w, h);
  const std::vector<std::uint8_t> png =
      EncodePng(renderer.width(), renderer.height(), px.data(), 96);
  return std::string(png.begin(), png.end());
}

}  // namespace formsim::app
