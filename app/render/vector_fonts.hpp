#pragma once
/// \file The figure fonts for vector output (SVG, PDF): the same TTF files as ImGui's atlas, read
/// with FreeType, measured the way ImGui measures (unhinted advances, size = ascent + descent),
/// so a recorded figure lays out exactly as its PNG twin. Loaded once, then read-only and safe
/// to use from any thread.

#include <string>
#include <vector>

#include "app/render/fonts.hpp"

typedef struct _cairo_font_face cairo_font_face_t;

namespace formsim::app {

class VectorFonts {
 public:
  /// The process-wide fonts. Throws std::runtime_error when DejaVu Sans is not installed.
  static const VectorFonts& Get();

  /// Advance width of UTF-8 `text` in logical pixels (ImGui's CalcTextSize width).
  float Width(FontRole role, const std::string& text) const;
  /// From the top of the line box to the baseline, logical pixels (ImGui's rounded ascent).
  float Baseline(FontRole role) const;
  /// The em size in logical pixels: what SVG font-size and Cairo's font size mean.
  float EmSize(FontRole role) const;
  /// The face for Cairo (owned here, valid for the whole process).
  cairo_font_face_t* CairoFace(FontRole role) const;

  VectorFonts(const VectorFonts&) = delete;
  VectorFonts& operator=(const VectorFonts&) = delete;

 private:
  struct Face {
    std::string path;
    double units_per_em = 2048, ascent = 0, descent = 0;  ///< font units (hhea)
    std::vector<float> advance;  ///< font units per code point below kCodes; < 0: no glyph
    float fallback = 0;          ///< advance of '?', drawn by ImGui for missing glyphs
    cairo_font_face_t* cairo = nullptr;
  };
  VectorFonts();
  const Face& FaceOf(FontRole role) const;
  std::vector<Face> faces_;  ///< regular, bold, mono
};

}  // namespace formsim::app
