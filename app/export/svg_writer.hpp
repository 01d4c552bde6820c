#pragma once
/// \file SVG from a recorded figure, written by us rather than by Cairo: Cairo's SVG surface
/// turns every glyph into an outline, and a figure's text must stay text (selectable,
/// searchable, editable). Lines are <path> elements, text <text> in DejaVu Sans.

#include <string>

#include "app/export/figure_size.hpp"
#include "app/render/vector_canvas.hpp"

namespace formsim::app {

/// `raw` as an XML id: every character but ASCII letters, digits, '-', '_' and '.' becomes '_',
/// and a '_' goes first unless it starts with a letter or '_' ("robot-R 1" -> "robot-R_1").
/// SvgDocument names groups so (a repeated id gets "-2", "-3"...).
std::string XmlId(const std::string& raw);

/// The SVG document of `fig`, `size` giving its physical width and height.
std::string SvgDocument(const VectorFigure& fig, const FigureSize& size, const std::string& title);

/// Writes SvgDocument atomically to `path`. Throws std::runtime_error naming the file.
void WriteSvg(const VectorFigure& fig, const FigureSize& size, const std::string& title,
              const std::string& path);

}  // namespace formsim::app
