#pragma once
/// \file The fonts of the GUI, the world view and the exported figures: DejaVu Sans at a few pixel
/// sizes, with Greek and the math symbols our labels use (φ, α, θ, σ, ω, ², ⁻¹, ×, −, ≈). One table
/// (FontSpecOf) gives each role its file and size, for ImGui's atlas and for vector figures alike.

#include <string>

struct ImFont;

namespace formsim::app {

/// What a piece of text is; every canvas maps a role to the same face and size.
enum class FontRole { kUi, kSmall, kLabel, kTitle, kMono };

struct FontSpec {
  const char* file;    ///< TTF file name, e.g. "DejaVuSans.ttf"
  const char* family;  ///< family name for SVG, e.g. "DejaVu Sans"
  bool bold;
  float pixels;  ///< ImGui's size: ascent + descent of the font, in logical pixels
};

/// The face and size of a role: ui 15 px, small (ticks, world labels) 14 px, label (axis labels,
/// legends) 16 px, title 17 px bold, mono (summary tables) 14 px.
const FontSpec& FontSpecOf(FontRole role);

/// Full path of a font file: the assets' fonts folder (sim::AssetDir("fonts"): installed
/// share/formsim/fonts, $FORMSIM_ASSETS/fonts or the source tree's), then Debian's
/// /usr/share/fonts/truetype/dejavu. "" when absent.
std::string FindFont(const std::string& file);

/// The Unicode ranges every font loads (0-terminated pairs): ASCII and Latin-1, Greek,
/// punctuation, super- and subscripts, arrows, math operators, geometric shapes.
const unsigned short* FontGlyphRanges();

struct Fonts {
  ImFont* ui = nullptr;     ///< panels, 15 px
  ImFont* small = nullptr;  ///< world-view labels, tick labels, 14 px
  ImFont* label = nullptr;  ///< axis labels and legends, 16 px
  ImFont* title = nullptr;  ///< figure titles, 17 px bold
  ImFont* mono = nullptr;   ///< summary tables, 14 px monospaced
  std::string source;       ///< the TTF file used, or "ImGui default" (no Greek glyphs)
  /// Pixels of the atlas per logical pixel: fonts are rasterised `scale` times larger and drawn
  /// at their logical size, so a 300 dpi figure has sharp text.
  float scale = 1.0f;
  ImFont* Get(FontRole role) const;
};

/// Adds the fonts to the current ImGui context's atlas (before the atlas is built), rasterised
/// at `scale` times their logical size. Falls back to ImGui's built-in font with a warning.
Fonts LoadFonts(float scale = 1.0f);

/// The fonts loaded in the current ImGui context (set by LoadFonts).
const Fonts& CurrentFonts();

}  // namespace formsim::app
