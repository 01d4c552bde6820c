#include "app/gui/frame_audit.hpp"

#include <imgui_internal.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "app/gui/atlas_glyphs.hpp"
#include "app/render/contrast.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

ImVec4 BoxIntersect(const ImVec4& a, const ImVec4& b) {
  return ImVec4(std::max(a.x, b.x), std::max(a.y, b.y), std::min(a.z, b.z), std::min(a.w, b.w));
}
float BoxWidth(const ImVec4& r) { return r.z - r.x; }
float BoxHeight(const ImVec4& r) { return r.w - r.y; }
bool BoxContains(const ImVec4& r, ImVec2 p) { return p.x >= r.x && p.x <= r.z && p.y >= r.y && p.y <= r.w; }

sim::Color ColorOfU32(ImU32 c) {
  const ImVec4 v = ImGui::ColorConvertU32ToFloat4(c);
  return {v.x, v.y, v.z, v.w};
}

// A glyph quad as drawn.
struct DrawnGlyph {
  ImVec4 box;        ///< its quad, logical
  unsigned code;
  float pen, next;   ///< where its pen started and moved to
  float space;       ///< a space's advance at this size
  float line_top;    ///< the top of its line (the quad's top less the glyph's offset)
  float size;        ///< the font's size as drawn, logical
  bool trimmed;      ///< cut short at a clip edge by ImGui itself
  ImU32 col;
  ImVec4 clip;       ///< its command's clip rectangle, within the window
  int list;
  long order;        ///< draw order in the frame
};

// A solid (not anti-aliasing fringe) untextured triangle.
struct SolidFill {
  ImVec2 a, b, c;
  ImVec4 box, clip;
  sim::Color col;
  int list;
  long order;
};

// A run of glyphs read as one piece of text.
struct TextRun {
  std::string text;
  ImVec4 box, clip;
  float size = 0;
  ImU32 col = 0;
  int list = 0;
  long first = 0, last = 0;
  std::vector<float> glyph_mid_x;
  bool cut = false;
};

bool InFillTriangle(ImVec2 p, const SolidFill& f) {
  auto side = [](ImVec2 a, ImVec2 b, ImVec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
  const float d1 = side(f.a, f.b, p), d2 = side(f.b, f.c, p), d3 = side(f.c, f.a, p);
  const bool neg = d1 < 0 || d2 < 0 || d3 < 0, pos = d1 > 0 || d2 > 0 || d3 > 0;
  return !(neg && pos);
}

// The fills bucketed by 32-unit cells, each cell's list in draw order.
class SolidFillGrid {
 public:
  SolidFillGrid(const std::vector<SolidFill>& fills, ImVec2 size) : fills_(fills) {
    nx_ = std::max(1, static_cast<int>(size.x / kCell) + 1);
    ny_ = std::max(1, static_cast<int>(size.y / kCell) + 1);
    cells_.resize(static_cast<std::size_t>(nx_) * ny_);
    for (std::size_t i = 0; i < fills.size(); ++i) {
      const ImVec4& b = fills[i].box;
      const int x0 = CellX(b.x), x1 = CellX(b.z), y0 = CellY(b.y), y1 = CellY(b.w);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) cells_[static_cast<std::size_t>(y) * nx_ + x].push_back(i);
    }
  }
  /// The colour behind point `p` before draw order `before`, over `clear`; `last_opaque` gets
  /// the list and order of the last opaque fill there (-1: none).
  sim::Color Behind(ImVec2 p, long before, sim::Color clear, int* opaque_list, long* opaque_order) const {
    sim::Color bg = clear;
    *opaque_list = -1;
    *opaque_order = -1;
    for (std::size_t i : cells_[static_cast<std::size_t>(CellY(p.y)) * nx_ + CellX(p.x)]) {
      const SolidFill& f = fills_[i];
      if (f.order >= before) break;
      if (!BoxContains(f.box, p) || !BoxContains(f.clip, p) || !InFillTriangle(p, f)) continue;
      bg = Over(f.col, bg);
      if (f.col.a >= 0.99f) *opaque_list = f.list, *opaque_order = f.order;
    }
    return bg;
  }

 private:
  static constexpr float kCell = 32.0f;
  int CellX(float x) const { return std::clamp(static_cast<int>(x / kCell), 0, nx_ - 1); }
  int CellY(float y) const { return std::clamp(static_cast<int>(y / kCell), 0, ny_ - 1); }
  const std::vector<SolidFill>& fills_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
};

// Reads the glyphs and solid fills of every draw list, in draw order.
void ReadDrawData(const ImDrawData& dd, ImVec2 display, std::vector<DrawnGlyph>* glyphs, std::vector<SolidFill>* fills) {
  const auto atlas = AtlasGlyphsByUv();
  const ImVec2 white = ImGui::GetIO().Fonts->TexUvWhitePixel;
  const ImVec4 screen(0, 0, display.x, display.y);
  long order = 0;
  for (int li = 0; li < dd.CmdListsCount; ++li) {
    const ImDrawList& dl = *dd.CmdLists[li];
    for (const ImDrawCmd& cmd : dl.CmdBuffer) {
      if (cmd.UserCallback) continue;
      const ImVec4 clip = BoxIntersect(cmd.ClipRect, screen);
      const ImDrawIdx* idx = dl.IdxBuffer.Data + cmd.IdxOffset;
      const ImDrawVert* vtx = dl.VtxBuffer.Data + cmd.VtxOffset;
      for (unsigned k = 0; k + 2 < cmd.ElemCount; ++order) {
        const ImDrawVert& a = vtx[idx[k]];
        const bool is_white = a.uv.x == white.x && a.uv.y == white.y;
        if (!is_white && k + 5 < cmd.ElemCount && idx[k + 1] == idx[k] + 1 && idx[k + 2] == idx[k] + 2 &&
            idx[k + 3] == idx[k] && idx[k + 4] == idx[k] + 2 && idx[k + 5] == idx[k] + 3) {
          const auto it = atlas.find({a.uv.x, a.uv.y});
          const ImDrawVert& b = vtx[idx[k] + 1];
          const ImDrawVert& c = vtx[idx[k] + 2];
          k += 6;
          if (it == atlas.end() || !(c.pos.x > a.pos.x && c.pos.y > a.pos.y)) continue;
          const AtlasGlyph& ag = it->second;
          const bool trimmed = b.uv.x < ag.u1 - 1e-7f;
          // The quad's scale over the atlas glyph, from its height (a trimmed glyph keeps it).
          const float scale = ag.y1 > ag.y0 ? (c.pos.y - a.pos.y) / (ag.y1 - ag.y0) : 1.0f;
          const float pen = a.pos.x - ag.x0 * scale;
          glyphs->push_back({ImVec4(a.pos.x, a.pos.y, c.pos.x, c.pos.y), ag.code, pen,
                             pen + ag.advance * scale, ag.space * scale, a.pos.y - ag.y0 * scale,
                             ag.font_size * scale, trimmed, a.col, clip, li, order});
          continue;
        }
        const ImDrawVert& b = vtx[idx[k + 1]];
        const ImDrawVert& c = vtx[idx[k + 2]];
        k += 3;
        if (!is_white || b.uv.x != white.x || c.uv.x != white.x) continue;
        // An anti-aliasing fringe fades to nothing across the triangle: not a fill.
        const ImU32 alpha = a.col & IM_COL32_A_MASK;
        if (alpha == 0 || (b.col & IM_COL32_A_MASK) != alpha || (c.col & IM_COL32_A_MASK) != alpha) continue;
        SolidFill f{a.pos, b.pos, c.pos, ImVec4(), clip, ColorOfU32(a.col), li, order};
        f.box = ImVec4(std::min({a.pos.x, b.pos.x, c.pos.x}), std::min({a.pos.y, b.pos.y, c.pos.y}),
                       std::max({a.pos.x, b.pos.x, c.pos.x}), std::max({a.pos.y, b.pos.y, c.pos.y}));
        if (BoxWidth(BoxIntersect(f.box, clip)) <= 0 || BoxHeight(BoxIntersect(f.box, clip)) <= 0) continue;
        fills->push_back(f);
      }
    }
  }
}

// Glyphs in a row of one command, of one colour, with pens that follow on (a space or less
// between them), are one run.
std::vector<TextRun> TextRunsOf(const std::vector<DrawnGlyph>& glyphs) {
  std::vector<TextRun> runs;
  const DrawnGlyph* prev = nullptr;
  for (const DrawnGlyph& g : glyphs) {
    const bool joins = prev && prev->list == g.list && prev->col == g.col &&
                       prev->clip.x == g.clip.x && prev->clip.z == g.clip.z &&
                       std::abs(prev->line_top - g.line_top) < 0.5f &&
                       g.pen >= prev->next - 1.0f && g.pen <= prev->next + 1.6f * g.space;
    if (!joins) {
      runs.push_back({});
      TextRun& r = runs.back();
      r.box = g.box, r.clip = g.clip, r.col = g.col, r.list = g.list, r.first = g.order;
    } else if (g.pen - prev->next > 0.5f * g.space) {
      runs.back().text += ' ';
    }
    TextRun& r = runs.back();
    AppendUtf8(r.text, g.code);
    r.box = ImVec4(std::min(r.box.x, g.box.x), std::min(r.box.y, g.box.y), std::max(r.box.z, g.box.z),
                   std::max(r.box.w, g.box.w));
    r.size = std::max(r.size, g.size);
    r.last = g.order;
    r.glyph_mid_x.push_back(0.5f * (g.box.x + g.box.z));
    // Cut: ImGui trimmed it, or it reaches past its clip edge while its middle row shows.
    const float mid_y = 0.5f * (g.box.y + g.box.w);
    if (mid_y >= g.clip.y && mid_y <= g.clip.w && g.code != ' ' &&
        (g.trimmed || (g.box.z > g.clip.z + 0.5f && g.box.x < g.clip.z) ||
         (g.box.x < g.clip.x - 0.5f && g.box.z > g.clip.x)))
      r.cut = true;
    prev = &g;
  }
  return runs;
}

std::string DrawListName(const ImDrawData& dd, int li) {
  const char* n = dd.CmdLists[li]->_OwnerName;
  return n ? n : "";
}

bool CanScrollSideways(const std::string& window) {
  const ImGuiWindow* w = window.empty() ? nullptr : ImGui::FindWindowByName(window.c_str());
  return w && w->ScrollbarX;
}

ImVec4 ToPixels(const ImVec4& r, float s) { return ImVec4(r.x * s, r.y * s, r.z * s, r.w * s); }

// Whether a circle of radius `r` at `c` reaches into rectangle `b`.
bool CircleHitsBox(ImVec2 c, float r, const ImVec4& b) {
  const float dx = c.x - std::clamp(c.x, b.x, b.z), dy = c.y - std::clamp(c.y, b.y, b.w);
  return dx * dx + dy * dy < r * r;
}

std::string ColourHex(sim::Color c) {
  return sim::Sprintf("#%02x%02x%02x", static_cast<int>(std::lround(c.r * 255)),
                      static_cast<int>(std::lround(c.g * 255)),
                      static_cast<int>(std::lround(c.b * 255)));
}

}  // namespace

FrameAudit AuditFrame(const ImDrawData& dd, const AuditMarks& marks) {
  FrameAudit out;
  std::vector<DrawnGlyph> glyphs;
  std::vector<SolidFill> fills;
  ReadDrawData(dd, marks.display, &glyphs, &fills);
  const std::vector<TextRun> runs = TextRunsOf(glyphs);
  out.text_runs = static_cast<int>(runs.size());
  const SolidFillGrid grid(fills, marks.display);
  const sim::Color clear{marks.clear_colour.x, marks.clear_colour.y, marks.clear_colour.z, 1.0f};
  const float px = marks.pixel_scale;
  // A robot's body, for text that would hide it: most of its circumscribed circle.
  constexpr float kBodyShare = 0.8f;

  std::vector<int> opaque_list(runs.size(), -1);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const TextRun& r = runs[i];
    const ImVec4 shown = BoxIntersect(r.box, r.clip);
    if (BoxWidth(shown) <= 0.5f || BoxHeight(shown) <= 0.5f) continue;  // clipped away: nobody sees it
    const std::string window = DrawListName(dd, r.list);
    AuditFinding f{window, r.text, "", ToPixels(r.box, px), 0};
    out.runs.push_back({window, r.text, "", ToPixels(r.box, px), r.size * px});
    if (r.cut && !CanScrollSideways(window)) out.cut.push_back(f);
    // Contrast at the first, middle and last glyph, against what was drawn there before it.
    double worst = 1e9;
    sim::Color worst_fg, worst_bg;
    const float mid_y = 0.5f * (r.box.y + r.box.w);
    const std::size_t n = r.glyph_mid_x.size();
    for (std::size_t k : {std::size_t{0}, n / 2, n - 1}) {
      const ImVec2 p(r.glyph_mid_x[k], mid_y);
      if (!BoxContains(r.clip, p)) continue;
      long opaque_order = -1;
      const sim::Color bg = grid.Behind(p, r.first, clear, &opaque_list[i], &opaque_order);
      const sim::Color fg = Over(ColorOfU32(r.col), bg);
      const double ratio = ContrastRatio(fg, bg);
      if (ratio < worst) worst = ratio, worst_fg = fg, worst_bg = bg;
    }
    if (worst < kTextContrast) {
      AuditFinding c = f;
      c.value = worst;
      c.other = ColourHex(worst_fg) + " on " + ColourHex(worst_bg);
      out.low_contrast.push_back(c);
    }
    if (marks.ui_scale >= 1.99f && r.size * px < kLectureTextPx - 0.01f) {
      AuditFinding s = f;
      s.value = r.size * px;
      out.small_text.push_back(s);
    }
  }

  // Text over text: two runs whose boxes cross where both show, the later not hiding the earlier
  // behind an opaque fill of its own.
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const ImVec4 si = BoxIntersect(runs[i].box, runs[i].clip);
    if (BoxWidth(si) <= 0 || BoxHeight(si) <= 0) continue;
    for (std::size_t j = i + 1; j < runs.size(); ++j) {
      const ImVec4 both = BoxIntersect(si, BoxIntersect(runs[j].box, runs[j].clip));
      const float h = std::min(BoxHeight(runs[i].box), BoxHeight(runs[j].box));
      if (BoxWidth(both) <= 1.0f || BoxHeight(both) <= 0.3f * h) continue;
      int list = -1;
      long order = -1;
      const ImVec2 centre(0.5f * (both.x + both.z), 0.5f * (both.y + both.w));
      grid.Behind(centre, runs[j].first, clear, &list, &order);
      if (order > runs[i].last) continue;  // covered before the later text was drawn
      out.overlaps.push_back({DrawListName(dd, runs[j].list), runs[j].text, runs[i].text, ToPixels(both, px), 0});
    }
  }
  // Text over a robot of the world view (text on a panel over the view is not over a robot),
  // and boxes drawn over the view (the legend) that cover one.
  int world_list = -1;
  for (int li = 0; li < dd.CmdListsCount; ++li)
    if (DrawListName(dd, li).find("###world") != std::string::npos) world_list = li;
  for (const AuditMarks::Robot& rb : marks.robots) {
    if (!BoxContains(marks.world_view, rb.centre)) continue;
    const float r = kBodyShare * rb.radius;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (opaque_list[i] != world_list || runs[i].list != world_list) continue;
      const ImVec4 shown = BoxIntersect(runs[i].box, runs[i].clip);
      if (CircleHitsBox(rb.centre, r, shown))
        out.overlaps.push_back({DrawListName(dd, runs[i].list), runs[i].text, "robot " + rb.name, ToPixels(shown, px), 0});
    }
    for (const AuditMarks::Box& b : marks.over_world)
      if (CircleHitsBox(rb.centre, r, b.rect))
        out.overlaps.push_back({"world view", b.name, "robot " + rb.name, ToPixels(b.rect, px), 0});
  }

  const ImVec4 screen(0, 0, marks.display.x, marks.display.y);
  for (const AuditMarks::Box& p : marks.plots) {
    // A squashed plot's data area may be upside down: its size is then 0.
    const ImVec4 r(std::min(p.rect.x, p.rect.z), std::min(p.rect.y, p.rect.w),
                   std::max(p.rect.x, p.rect.z), std::max(p.rect.y, p.rect.w));
    const ImVec4 shown = BoxIntersect(ImVec4(r.x, r.y, r.z + 1, r.w + 1), screen);
    if (BoxWidth(shown) <= 0 || BoxHeight(shown) <= 0) continue;
    const float side = std::max(0.0f, std::min(p.rect.z - p.rect.x, p.rect.w - p.rect.y)) * px;
    if (side < kSmallestPlotPx) out.small_plots.push_back({"plots", p.name, "", ToPixels(p.rect, px), side});
  }
  const ImVec4 world = BoxIntersect(marks.world_view, screen);
  if (BoxWidth(world) > 0 && BoxHeight(world) > 0 && marks.display.x > 0 && marks.display.y > 0)
    out.world_view_share = BoxWidth(world) * BoxHeight(world) / (marks.display.x * marks.display.y);
  return out;
}

}  // namespace formsim::app
