#pragma once
/// \file Pictures of a run in memory, for the Python module (Sim.render, Sim.figure): the world
/// view as `formsim run --snapshot FILE.png` draws it and a figure's file as `--plots` writes it,
/// through the same offscreen renderer and vector writers, returned instead of written. No
/// display needed.

#include <cstdint>
#include <string>
#include <vector>

#include "app/export/figure_titles.hpp"
#include "app/render/plot.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

/// The world view of `exp` now, `width` x `height` pixels, top row first, 3 bytes (RGB) a
/// pixel: the pixels of `formsim run --snapshot F.png --size WxH --theme THEME --overlay
/// OVERLAYS [--legend]` when the run is where `exp` is (a camera that tracks the robots, framed
/// at once). `overlays` is --overlay's text ("" keeps the defaults). Throws std::runtime_error
/// naming width, height, theme or overlays when one is refused. Safe from any thread: pictures
/// are drawn one at a time in a process (ImGui has one current context).
std::vector<std::uint8_t> RenderWorldRgb(const sim::Experiment& exp, int width, int height,
                                         const std::string& theme, const std::string& overlays,
                                         bool legend);

/// The names of `exp`'s figures now (`--plots` writes NAME.png ...), in its order.
std::vector<std::string> FigureNames(const sim::Experiment& exp);

/// The figure `spec` ready to draw as an exported figure: its series read from `recorder`, the
/// title as `titles` shows it, a log y axis when `log_y`. Throws std::runtime_error naming the
/// figure when a series cannot be resolved.
PlotData ExportedPlot(const sim::FigureSpec& spec, const sim::Recorder& recorder, TitleMode titles,
                      bool log_y);

/// The bytes of figure `name` of `exp` in `format` ("png", "svg" or "pdf"): the file `formsim
/// run --plots DIR --plot-format FORMAT --theme THEME` writes as DIR/NAME.FORMAT (default size
/// 960x600, 96 dpi, full titles, linear axes). Throws std::runtime_error for an unknown name
/// (listing the figures there are), format or theme. Safe from any thread, as RenderWorldRgb.
std::string FigureBytes(const sim::Experiment& exp, const std::string& name,
                        const std::string& format, const std::string& theme);

}  // namespace formsim::app
