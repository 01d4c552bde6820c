#pragma once
/// \file The glyphs of the current ImGui font atlas, found by the UV of a quad's top-left
/// corner: how the layout audits read back the text a frame drew (app/gui/layout_audit.hpp,
/// app/gui/frame_audit.hpp).

#include <map>
#include <string>
#include <utility>

namespace formsim::app {

/// One glyph of the atlas.
struct AtlasGlyph {
  float u1, v1;                   ///< its bottom-right UV
  unsigned code;                  ///< its code point
  float x0, y0, x1, y1, advance;  ///< its box and advance in the atlas font's pixels
  float space;                    ///< the advance of its font's space
  float font_size;                ///< the atlas font's size
};

/// Every glyph of every font of the current context's atlas, by (U0, V0).
std::map<std::pair<float, float>, AtlasGlyph> AtlasGlyphsByUv();

/// Appends code point `c` to `s` as UTF-8.
void AppendUtf8(std::string& s, unsigned c);

}  // namespace formsim::app
