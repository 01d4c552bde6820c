#pragma once
/// \file The whole interface drawn offscreen, without a window: `formsim run --ui` frames and
/// snapshot. The renderer (app/render) knows ImGui frames, export (app/export) knows UiFrames;
/// this file joins them to AppUi.

#include <cstdint>
#include <memory>
#include <vector>

#include "app/export/export.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "sim/session/session.hpp"

namespace formsim::app {

class AppUi;

/// The whole interface, as in the GUI window, without input, at the renderer's size and scale.
const std::vector<std::uint8_t>& RenderUi(OffscreenRenderer& renderer, AppUi& ui);

/// RunWithExport's interface for --ui: an AppUi on `session`, paused, its plots redrawn every
/// frame, with the theme, overlays, legend and whole-run camera of `opt`.
std::unique_ptr<UiFrames> MakeUiFrames(sim::Session& session, const ExportOptions& opt);

}  // namespace formsim::app
