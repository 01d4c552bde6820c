#pragma once
/// \file PDF from a recorded figure through Cairo: one page of the figure's physical size, text
/// as text in embedded (subset) TrueType fonts with Unicode maps, so it can be selected,
/// searched and extracted; lines as vector paths.

#include <cstdint>
#include <string>
#include <vector>

#include "app/export/figure_size.hpp"
#include "app/render/vector_canvas.hpp"

namespace formsim::app {

/// The PDF bytes of `fig`, the same bytes for the same figure (a fixed creation date). Throws
/// std::runtime_error with Cairo's reason on failure.
std::string PdfDocument(const VectorFigure& fig, const FigureSize& size, const std::string& title);

/// Writes PdfDocument atomically to `path`. Throws std::runtime_error naming the file.
void WritePdf(const VectorFigure& fig, const FigureSize& size, const std::string& title,
              const std::string& path);

/// `fig` rasterised by Cairo into a `width` x `height` RGBA image (straight alpha, top row first):
/// the same drawing as the PDF, for pictures that must not need a GL context (the icon).
std::vector<std::uint8_t> RasterRgba(const VectorFigure& fig, int width, int height);

}  // namespace formsim::app
