#include "app/gui/atlas_glyphs.hpp"

#include <imgui.h>
#include <imgui_internal.h>

namespace formsim::app {

std::map<std::pair<float, float>, AtlasGlyph> AtlasGlyphsByUv() {
  std::map<std::pair<float, float>, AtlasGlyph> out;
  for (const ImFont* font : ImGui::GetIO().Fonts->Fonts) {
    const ImFontGlyph* sp = font->FindGlyphNoFallback(' ');
    const float space = sp ? sp->AdvanceX : 0.5f * font->FontSize;
    for (const ImFontGlyph& g : font->Glyphs)
      out[{g.U0, g.V0}] = {g.U1, g.V1, g.Codepoint, g.X0, g.Y0, g.X1, g.Y1, g.AdvanceX, space,
                           font->FontSize};
  }
  return out;
}

void AppendUtf8(std::string& s, unsigned c) {
  char buf[5] = {};
  ImTextCharToUtf8(buf, c);
  s += buf;
}

}  // namespace formsim::app
