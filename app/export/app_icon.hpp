#pragma once
/// \file The application icon (menus, the desktop entry, AppStream): a three-robot cascade
/// formation on a rounded square, drawn with the figure canvas, so the SVG and the PNG are made
/// by formsim's own renderer at build time (`formsim icon`), never by hand.

#include <string>

#include "app/render/vector_canvas.hpp"

namespace formsim::app {

/// The icon on a `size` x `size` canvas (logical pixels).
VectorFigure RecordAppIcon(float size = 256.0f);

/// Writes the icon as SVG to `svg_path` and as a `png_px` square PNG (Cairo) to `png_path`;
/// an empty path is skipped. Throws std::runtime_error naming the file.
void WriteAppIcon(const std::string& svg_path, const std::string& png_path, int png_px);

}  // namespace formsim::app
