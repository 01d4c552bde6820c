#pragma once
/// \file The fonts of the GUI, the world view and the exported figures: DejaVu Sans at a few pixel
/// sizes, with Greek and the math symbols our labels use (φ, α, θ, σ, ω, ², ⁻¹, ×, −, ≈).

#include <string>

struct ImFont;

namespace formsim::app {

struct Fonts {
  ImFont* ui = nullptr;     ///< panels, 15 px
  ImFont* small = nullptr;  ///< world-view labels, tick labels, 14 px
  ImFont* label = nullptr;  ///< axis labels and legends, 16 px
  ImFont* title = nullptr;  ///< figure titles, 17 px bold
  ImFont* mono = nullptr;   ///< summary tables, 14 px monospaced
  std::string source;       ///< the TTF file used, or "ImGui default" (no Greek glyphs)
};

/// Adds the fonts to the current ImGui context's atlas (before the atlas is built). Looks for
/// DejaVuSans.ttf in $FORMSIM_ASSETS/fonts, the source tree's assets/fonts, then
/// /usr/share/fonts/truetype/dejavu; falls back to ImGui's built-in font with a warning.
Fonts LoadFonts();

/// The fonts loaded in the current ImGui context (set by LoadFonts).
const Fonts& CurrentFonts();

}  // namespace formsim::app
