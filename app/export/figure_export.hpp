#pragma once
/// \file Figures and world views as files: the formats (png, svg, pdf), and the recording of a
/// plot or a world view onto a VectorCanvas with exactly the drawing code of the PNG.

#include <set>
#include <string>
#include <vector>

#include "app/export/figure_size.hpp"
#include "app/render/plot.hpp"
#include "app/render/theme.hpp"
#include "app/render/vector_canvas.hpp"
#include "app/render/view.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

enum class FigureFormat { kPng, kSvg, kPdf };

/// "png", "svg", "pdf".
const char* FormatExtension(FigureFormat format);
/// "image/png", "image/svg+xml", "application/pdf".
const char* FormatMime(FigureFormat format);
/// What the window's "Export figures" writes per figure: SVG and PDF; in the browser page,
/// which has no Cairo, SVG alone.
#ifdef __EMSCRIPTEN__
inline constexpr FigureFormat kGuiFigureFormats[] = {FigureFormat::kSvg};
#else
inline constexpr FigureFormat kGuiFigureFormats[] = {FigureFormat::kSvg, FigureFormat::kPdf};
#endif
/// Parses a comma-separated subset of png,svg,pdf (in that order, duplicates ignored). Throws
/// std::runtime_error naming `flag`.
std::vector<FigureFormat> ParseFigureFormats(const std::string& list, const std::string& flag);
/// The format of a file from its extension (.png, .svg, .pdf). Throws naming `flag`.
FigureFormat FormatOfFile(const std::string& path, const std::string& flag);
/// Throws naming `flag` when `dir` looks like a file name (an image or video extension) or is
/// an existing file: a folder flag given `p.svg` would otherwise create a folder called p.svg.
void CheckFolderName(const std::string& dir, const std::string& flag, const std::string& hint);

/// The plot drawn by DrawPlot onto a `width` x `height` vector canvas, in the figure style.
VectorFigure RecordPlot(const PlotData& data, int width, int height, const Theme& theme);
/// The world view of `exp` through `view` (whose rectangle is the whole figure).
VectorFigure RecordWorld(const sim::Experiment& exp, const View& view, const Theme& theme,
                         const std::string& caption, const std::set<std::string>* overlays = nullptr, bool legend = false);
/// Writes a recorded figure as SVG or PDF (atomically). Throws std::runtime_error.
void WriteVectorFigure(const VectorFigure& fig, FigureFormat format, const FigureSize& size,
                       const std::string& title, const std::string& path);

}  // namespace formsim::app
