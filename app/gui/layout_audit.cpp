#include "app/gui/layout_audit.hpp"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace formsim::app {
namespace {

// The code point of every glyph of the atlas, by the UV of its top-left corner.
struct AtlasGlyph {
  float u1, v1;
  unsigned code;
  float x0, x1, advance;  ///< the glyph's box and advance in font pixels
  float space;            ///< the advance of its font's space
};
std::map<std::pair<float, float>, AtlasGlyph> GlyphsByUv() {
  std::map<std::pair<float, float>, AtlasGlyph> out;
  for (const ImFont* font : ImGui::GetIO().Fonts->Fonts) {
    const ImFontGlyph* sp = font->FindGlyphNoFallback(' ');
    const float space = sp ? sp->AdvanceX : 0.5f * font->FontSize;
    for (const ImFontGlyph& g : font->Glyphs)
      out[{g.U0, g.V0}] = {g.U1, g.V1, g.Codepoint, g.X0, g.X1, g.AdvanceX, space};
  }
  return out;
}

void AppendUtf8(std::string& s, unsigned c) {
  char buf[5] = {};
  ImTextCharToUtf8(buf, c);
  s += buf;
}

// A glyph quad of a draw list: 4 vertices in PrimRectUV's order (a, b, c, d).
struct Glyph {
  float x0, y0, x1, y1;
  unsigned code;
  float pen, next, space;  ///< on screen: where its pen started and moved to, a space's width
};

std::vector<Glyph> Glyphs(const ImDrawList& dl,
                          const std::map<std::pair<float, float>, AtlasGlyph>& by_uv) {
  std::vector<Glyph> out;
  const ImVec2 white = ImGui::GetIO().Fonts->TexUvWhitePixel;
  for (int i = 0; i + 3 < dl.VtxBuffer.Size; ++i) {
    const ImDrawVert& a = dl.VtxBuffer[i];
    if (a.uv.x == white.x && a.uv.y == white.y) continue;
    const auto it = by_uv.find({a.uv.x, a.uv.y});
    if (it == by_uv.end()) continue;
    // A glyph quad: b = (U1, V0), c = (U1, V1), d = (U0, V1) of the same glyph.
    const ImDrawVert& b = dl.VtxBuffer[i + 1];
    const ImDrawVert& c = dl.VtxBuffer[i + 2];
    const ImDrawVert& d = dl.VtxBuffer[i + 3];
    const AtlasGlyph& ag = it->second;
    // (A glyph trimmed at a clip edge keeps its top-left UV but ends short of U1.)
    if (b.uv.x > ag.u1 || b.uv.x <= a.uv.x || b.uv.y != a.uv.y || c.uv.x != b.uv.x ||
        c.uv.y != d.uv.y || d.uv.x != a.uv.x || d.uv.y > ag.v1 || d.uv.y <= a.uv.y)
      continue;
    if (!(c.pos.x > a.pos.x && c.pos.y > a.pos.y)) continue;
    // The quad's scale over the atlas glyph (a glyph trimmed at the left edge has none).
    const float scale = ag.x1 > ag.x0 && b.uv.x == ag.u1 ? (c.pos.x - a.pos.x) / (ag.x1 - ag.x0) : 1;
    const float pen = a.pos.x - ag.x0 * scale;
    out.push_back({a.pos.x, a.pos.y, c.pos.x, c.pos.y, ag.code, pen, pen + ag.advance * scale,
                   ag.space * scale});
    i += 3;
  }
  return out;
}

// The vertical bands (top, bottom) of the triangles that the commands clipped at the window's
// edge `right` drew past `work_right`, the right end of its content region (where full-width
// items end; the strip between them is padding no laid-out item reaches). ImGui drops glyphs
// wholly outside the clip rectangle, so a checkbox whose label starts past the edge leaves only
// its box, ending in that strip.
std::vector<std::pair<float, float>> BandsPast(const ImDrawList& dl, float right, float work_right) {
  std::vector<std::pair<float, float>> bands;
  for (const ImDrawCmd& cmd : dl.CmdBuffer) {
    if (cmd.UserCallback || std::abs(cmd.ClipRect.z - right) > 1.0f) continue;
    for (unsigned k = 0; k + 2 < cmd.ElemCount; k += 3) {
      float x1 = -1e30f, y0 = 1e30f, y1 = -1e30f;
      for (unsigned v = 0; v < 3; ++v) {
        const ImDrawVert& p = dl.VtxBuffer[cmd.VtxOffset + dl.IdxBuffer[cmd.IdxOffset + k + v]];
        x1 = std::max(x1, p.pos.x), y0 = std::min(y0, p.pos.y), y1 = std::max(y1, p.pos.y);
      }
      // An anti-aliased fill's fringe reaches half a pixel past an item that fits; a square
      // frame that reaches a pixel past the content region belongs to an item cut there.
      if (x1 > work_right + 0.75f && y1 > y0) bands.push_back({y0, y1});
    }
  }
  // Merged where they overlap: one band per cut line.
  std::sort(bands.begin(), bands.end());
  std::vector<std::pair<float, float>> merged;
  for (const auto& b : bands) {
    if (!merged.empty() && b.first <= merged.back().second)
      merged.back().second = std::max(merged.back().second, b.second);
    else
      merged.push_back(b);
  }
  return merged;
}

}  // namespace

std::vector<ClippedText> FindClippedText() {
  std::vector<ClippedText> out;
  ImGuiContext& g = *ImGui::GetCurrentContext();
  const auto by_uv = GlyphsByUv();
  for (ImGuiWindow* w : g.Windows) {
    if (!w->Active || w->Hidden || w->ScrollbarX) continue;
    if (w->Flags & (ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_AlwaysAutoResize)) continue;
    const float left = w->InnerClipRect.Min.x, right = w->InnerClipRect.Max.x;
    // Only a window whose items reach past its visible width has anything cut.
    // (ImGui rounds item sizes: a pixel over is not a cut.)
    if (w->DC.CursorMaxPos.x <= right + 1.5f) continue;
    const std::vector<Glyph> glyphs = Glyphs(*w->DrawList, by_uv);
    for (const auto& [top, bottom] : BandsPast(*w->DrawList, right, w->WorkRect.Max.x)) {
      if (bottom < w->InnerClipRect.Min.y || top > w->InnerClipRect.Max.y) continue;  // not shown
      // The line's text as it shows: the glyphs whose middles lie in the band, left to right.
      std::vector<Glyph> line;
      for (const Glyph& gl : glyphs) {
        const float mid = 0.5f * (gl.y0 + gl.y1);
        if (mid >= top && mid <= bottom) line.push_back(gl);
      }
      std::sort(line.begin(), line.end(), [](const Glyph& a, const Glyph& b) { return a.x0 < b.x0; });
      ClippedText c;
      c.widget = std::string(w->Name) + " @y" + std::to_string(static_cast<int>(top - w->Pos.y));
      // A gap of half a space or more between one glyph's advance and the next one's pen is a
      // space (or the gap between two widgets).
      float prev = line.empty() ? 0 : line.front().pen;
      for (const Glyph& gl : line) {
        if (gl.pen - prev > 0.5f * gl.space) c.text += ' ';
        AppendUtf8(c.text, gl.code);
        prev = gl.next;
      }
      c.available = right - left;
      c.needed = w->DC.CursorMaxPos.x - left;
      out.push_back(std::move(c));
    }
  }
  return out;
}

}  // namespace formsim::app
