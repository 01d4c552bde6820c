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
};
std::map<std::pair<float, float>, AtlasGlyph> GlyphsByUv() {
  std::map<std::pair<float, float>, AtlasGlyph> out;
  for (const ImFont* font : ImGui::GetIO().Fonts->Fonts)
    for (const ImFontGlyph& g : font->Glyphs) out[{g.U0, g.V0}] = {g.U1, g.V1, g.Codepoint};
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
    if (b.uv.x != ag.u1 || b.uv.y != a.uv.y || c.uv.x != ag.u1 || c.uv.y != ag.v1 ||
        d.uv.x != a.uv.x || d.uv.y != ag.v1)
      continue;
    if (!(c.pos.x > a.pos.x && c.pos.y > a.pos.y)) continue;
    out.push_back({a.pos.x, a.pos.y, c.pos.x, c.pos.y, ag.code});
    i += 3;
  }
  return out;
}

}  // namespace

std::vector<ClippedText> FindClippedText() {
  std::vector<ClippedText> out;
  ImGuiContext& g = *ImGui::GetCurrentContext();
  const auto by_uv = GlyphsByUv();
  for (ImGuiWindow* w : g.Windows) {
    if (!w->Active || w->Hidden || w->ScrollbarX) continue;
    if (w->Flags & (ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_AlwaysAutoResize)) continue;
    const float right = w->InnerClipRect.Max.x;
    const float overflow = w->DC.CursorMaxPos.x - right;
    // The glyphs cut at the right edge, grouped by line.
    // Glyphs of a line differ in their tops and bottoms (ascenders, descenders): a line is the
    // glyphs whose vertical middles lie within half a glyph's height of its first one.
    std::vector<Glyph> all = Glyphs(*w->DrawList, by_uv);
    std::sort(all.begin(), all.end(), [](const Glyph& a, const Glyph& b) {
      return a.y0 + a.y1 < b.y0 + b.y1;
    });
    std::map<float, std::vector<Glyph>> lines;
    float line_mid = -1e30f;
    for (const Glyph& gl : all) {
      const float mid = 0.5f * (gl.y0 + gl.y1);
      if (mid - line_mid > 0.5f * (gl.y1 - gl.y0)) line_mid = mid;
      lines[line_mid].push_back(gl);
    }
    for (auto& [y, glyphs] : lines) {
      bool cut = false;
      for (const Glyph& gl : glyphs) cut = cut || (gl.x1 > right + 0.5f && gl.x0 < right);
      if (!cut && !(overflow > 0.5f && !glyphs.empty() &&
                    std::max_element(glyphs.begin(), glyphs.end(),
                                     [](const Glyph& a, const Glyph& b) { return a.x1 < b.x1; })
                            ->x1 > right - 2))
        continue;
      std::sort(glyphs.begin(), glyphs.end(), [](const Glyph& a, const Glyph& b) { return a.x0 < b.x0; });
      ClippedText c;
      c.widget = std::string(w->Name) + " @y" + std::to_string(static_cast<int>(y - w->Pos.y));
      float prev = glyphs.front().x0;
      for (const Glyph& gl : glyphs) {
        if (gl.x0 - prev > 0.5f * (gl.y1 - gl.y0)) c.text += ' ';
        AppendUtf8(c.text, gl.code);
        prev = gl.x1;
      }
      c.available = right - w->InnerClipRect.Min.x;
      c.needed = std::max(c.available, w->DC.CursorMaxPos.x - w->InnerClipRect.Min.x);
      out.push_back(std::move(c));
    }
  }
  return out;
}

}  // namespace formsim::app
