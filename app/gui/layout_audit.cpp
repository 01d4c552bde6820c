#include "app/gui/layout_audit.hpp"

#include <imgui.h>
#include <imgui_internal.h>

#include "app/gui/atlas_glyphs.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace formsim::app {
namespace {

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
std::vector<std::pair<float, float>> BandsPast(const ImDrawList& dl, float right, float work_left,
                                               float work_right) {
  std::vector<std::pair<float, float>> bands;
  for (const ImDrawCmd& cmd : dl.CmdBuffer) {
    if (cmd.UserCallback || std::abs(cmd.ClipRect.z - right) > 1.0f) continue;
    for (unsigned k = 0; k + 2 < cmd.ElemCount; k += 3) {
      float x1 = -1e30f, y0 = 1e30f, y1 = -1e30f;
      float x0 = 1e30f;
      for (unsigned v = 0; v < 3; ++v) {
        const ImDrawVert& p = dl.VtxBuffer[cmd.VtxOffset + dl.IdxBuffer[cmd.IdxOffset + k + v]];
        x0 = std::min(x0, p.pos.x), x1 = std::max(x1, p.pos.x);
        y0 = std::min(y0, p.pos.y), y1 = std::max(y1, p.pos.y);
      }
      // A full-width frame (a collapsing header) spans from the left edge to the clip edge by
      // design (ImGui widens it by half the padding): nothing of it is cut.
      if (x0 <= work_left + 1.0f && x1 <= right + 1.5f) continue;
      // Nor is its right border, a few pixels wide, drawn up to that edge.
      if (x1 - x0 <= 4.0f && x1 <= right + 1.5f) continue;
      // An anti-aliased frame's border and fringe reach a pixel and a half past an item that
      // fits; more than that belongs to an item cut there.
      if (x1 > work_right + 1.5f && y1 > y0) bands.push_back({y0, y1});
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
  const auto by_uv = AtlasGlyphsByUv();
  for (ImGuiWindow* w : g.Windows) {
    if (!w->Active || w->Hidden || w->ScrollbarX) continue;
    if (w->Flags & (ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_AlwaysAutoResize)) continue;
    const float left = w->InnerClipRect.Min.x, right = w->InnerClipRect.Max.x;
    // Only a window whose items reach past its visible width has anything cut.
    // (ImGui rounds item sizes: a pixel over is not a cut.)
    if (w->DC.CursorMaxPos.x <= right + 1.5f) continue;
    const std::vector<Glyph> glyphs = Glyphs(*w->DrawList, by_uv);
    // Each band grown to the glyphs it meets (a frame's thin top border stands for its line);
    // a thin band that meets no glyph is a frame's bottom border, already counted.
    std::vector<std::pair<float, float>> bands;
    for (const auto& band : BandsPast(*w->DrawList, right, w->WorkRect.Min.x, w->WorkRect.Max.x)) {
      float top = band.first, bottom = band.second;  // (a lambda below cannot take a binding)
      // (A frame's padding lies between its border and its text.)
      const float pad = ImGui::GetStyle().FramePadding.y + 1.0f;
      auto meets = [&](const Glyph& gl) { return gl.y1 > top - pad && gl.y0 < bottom + pad; };
      bool met = false;
      for (const Glyph& gl : glyphs) met = met || meets(gl);
      if (!met && bottom - top < 4.0f) continue;
      float grown_top = top, grown_bottom = bottom;
      for (const Glyph& gl : glyphs)
        if (meets(gl)) grown_top = std::min(grown_top, gl.y0), grown_bottom = std::max(grown_bottom, gl.y1);
      top = grown_top, bottom = grown_bottom;
      if (!bands.empty() && top <= bands.back().second)
        bands.back().second = std::max(bands.back().second, bottom);
      else
        bands.push_back({top, bottom});
    }
    for (const auto& [top, bottom] : bands) {
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
