#include "app/export/figure_export.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "app/export/pdf_writer.hpp"
#include "app/export/svg_writer.hpp"
#include "app/render/world_view.hpp"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

const char* FormatExtension(FigureFormat format) {
  switch (format) {
    case FigureFormat::kPng:
      return "png";
    case FigureFormat::kSvg:
      return "svg";
    case FigureFormat::kPdf:
      return "pdf";
  }
  return "png";
}

const char* FormatMime(FigureFormat format) {
  switch (format) {
    case FigureFormat::kPng:
      return "image/png";
    case FigureFormat::kSvg:
      return "image/svg+xml";
    case FigureFormat::kPdf:
      return "application/pdf";
  }
  return "application/octet-stream";
}

std::vector<FigureFormat> ParseFigureFormats(const std::string& list, const std::string& flag) {
  std::vector<FigureFormat> out;
  std::stringstream ss(list);
  std::string item;
  bool any = false;
  while (std::getline(ss, item, ',')) {
    item = Lower(item);
    bool known = false;
    for (FigureFormat f : {FigureFormat::kPng, FigureFormat::kSvg, FigureFormat::kPdf})
      if (item == FormatExtension(f)) {
        known = true;
        if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
      }
    if (!known)
      throw std::runtime_error(flag + " '" + list + "': unknown format '" + item +
                               "' (use any of png, svg, pdf, comma-separated)");
    any = true;
  }
  if (!any) throw std::runtime_error(flag + ": give at least one of png, svg, pdf");
  std::sort(out.begin(), out.end());
  return out;
}

FigureFormat FormatOfFile(const std::string& path, const std::string& flag) {
  const std::string ext = Lower(fs::path(path).extension().string());
  for (FigureFormat f : {FigureFormat::kPng, FigureFormat::kSvg, FigureFormat::kPdf})
    if (ext == std::string(".") + FormatExtension(f)) return f;
  throw std::runtime_error(flag + " '" + path + "': the file name must end in .png, .svg or .pdf" +
                           " (the format follows the extension)");
}

void CheckFolderName(const std::string& dir, const std::string& flag, const std::string& hint) {
  static const char* kFileExtensions[] = {".png", ".svg", ".pdf",  ".gif", ".jpg",  ".jpeg", ".mp4",
                                          ".mkv", ".mov", ".webm", ".csv", ".json", ".yaml"};
  const std::string ext = Lower(fs::path(dir).extension().string());
  for (const char* e : kFileExtensions)
    if (ext == e)
      throw std::runtime_error(flag + " '" + dir +
                               "': expects a folder, not a file name ending in " + e +
                               (hint.empty() ? "" : " (" + hint + ")"));
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw std::runtime_error(flag + " '" + dir + "': is an existing file, not a folder");
}

VectorFigure RecordPlot(const PlotData& data, int width, int height, const Theme& theme) {
  VectorCanvas canvas(static_cast<float>(width), static_cast<float>(height));
  DrawPlot(canvas, ImVec2(0, 0), ImVec2(static_cast<float>(width), static_cast<float>(height)),
           data, FigureStyle(theme));
  return canvas.Take();
}

VectorFigure RecordWorld(const sim::Experiment& exp, const View& view, const Theme& theme,
                         const std::string& caption, const std::set<std::string>* overlays,
                         bool legend) {
  VectorCanvas canvas(view.width(), view.height());
  WorldViewOptions opt;
  opt.caption = caption;
  opt.scene_overlays = overlays;
  opt.legend = legend;
  DrawWorldView(canvas, view, exp, theme, opt);
  return canvas.Take();
}

void WriteVectorFigure(const VectorFigure& fig, FigureFormat format, const FigureSize& size,
                       const std::string& title, const std::string& path) {
  if (format == FigureFormat::kSvg)
    WriteSvg(fig, size, title, path);
  else if (format == FigureFormat::kPdf)
#ifdef __EMSCRIPTEN__
    throw std::runtime_error(path + ": PDF needs the desktop build (Cairo); the page writes SVG");
#else
    WritePdf(fig, size, title, path);
#endif
  else
    throw std::logic_error("WriteVectorFigure: PNG is rendered, not recorded");
}

}  // namespace formsim::app
