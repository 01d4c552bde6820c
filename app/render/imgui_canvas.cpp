#include "app/render/imgui_canvas.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <vector>

#include "app/render/gl_api.hpp"

namespace formsim::app {
namespace {

double SignedArea(const ImVec2* p, int n) {
  double a = 0;
  for (int i = 0, j = n - 1; i < n; j = i++)
    a += static_cast<double>(p[j].x) * p[i].y - static_cast<double>(p[i].x) * p[j].y;
  return 0.5 * a;
}

bool IsConvex(const ImVec2* p, int n) {
  int sign = 0;
  for (int i = 0; i < n; ++i) {
    const ImVec2 &a = p[i], &b = p[(i + 1) % n], &c = p[(i + 2) % n];
    const double cross =
        static_cast<double>(b.x - a.x) * (c.y - b.y) - static_cast<double>(b.y - a.y) * (c.x - b.x);
    if (std::abs(cross) < 1e-9) continue;
    const int s = cross > 0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

bool PointInTriangle(ImVec2 p, ImVec2 a, ImVec2 b, ImVec2 c) {
  auto side = [](ImVec2 p1, ImVec2 p2, ImVec2 p3) {
    return (p1.x - p3.x) * (p2.y - p3.y) - (p2.x - p3.x) * (p1.y - p3.y);
  };
  const float d1 = side(p, a, b), d2 = side(p, b, c), d3 = side(p, c, a);
  const bool neg = d1 < 0 || d2 < 0 || d3<0, pos = d1> 0 || d2 > 0 || d3 > 0;
  return !(neg && pos);
}

}  // namespace

ImGuiCanvas::ImGuiCanvas(ImDrawList* list, const Fonts& fonts) : dl_(list), fonts_(fonts) {
  // Anti-aliasing fringes of one device pixel, however much the atlas (and frame) is scaled.
  dl_->_FringeScale = 1.0f / fonts_.scale;
}

void ImGuiCanvas::FillRect(ImVec2 min, ImVec2 max, sim::Color color, float rounding) {
  dl_->AddRectFilled(min, max, ToImColor(color), rounding);
}

namespace {

// The clear behind FillBackground: the command's clip rectangle (the background's rectangle,
// on whole pixels) cleared to the colour packed into the callback's data.
void ClearRectCallback(const ImDrawList*, const ImDrawCmd* cmd) {
  BackgroundClear c;
  if (!DecodeBackgroundClear(*ImGui::GetDrawData(), *cmd, &c)) return;
  const int fb_h = static_cast<int>(ImGui::GetDrawData()->DisplaySize.y *
                                    ImGui::GetDrawData()->FramebufferScale.y);
  GlClearRect(c.x0, fb_h - c.y1, c.x1 - c.x0, c.y1 - c.y0, c.rgba);
}

void SkippedClearCallback(const ImDrawList*, const ImDrawCmd*) {}

bool OnWholePixels(ImVec2 p, float scale) {
  return std::floor(p.x * scale) == p.x * scale && std::floor(p.y * scale) == p.y * scale;
}

}  // namespace

bool DecodeBackgroundClear(const ImDrawData& dd, const ImDrawCmd& cmd, BackgroundClear* out) {
  if (cmd.UserCallback != &ClearRectCallback) return false;
  const ImVec2 off = dd.DisplayPos, sc = dd.FramebufferScale;
  out->x0 = static_cast<int>((cmd.ClipRect.x - off.x) * sc.x);
  out->y0 = static_cast<int>((cmd.ClipRect.y - off.y) * sc.y);
  out->x1 = static_cast<int>((cmd.ClipRect.z - off.x) * sc.x);
  out->y1 = static_cast<int>((cmd.ClipRect.w - off.y) * sc.y);
  out->rgba = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(cmd.UserCallbackData));
  return true;
}

void SkipBackgroundClear(ImDrawCmd& cmd) {
  if (cmd.UserCallback == &ClearRectCallback) cmd.UserCallback = &SkippedClearCallback;
}

bool IsSkippedBackgroundClear(const ImDrawCmd& cmd) {
  return cmd.UserCallback == &SkippedClearCallback;
}

void ImGuiCanvas::FillBackground(ImVec2 min, ImVec2 max, sim::Color color) {
  // The rectangle as the quad would be clipped: the current clip rectangle, all on whole
  // framebuffer pixels (else the quad's edge pixels could differ from the clear's).
  const ImVec4 clip = dl_->_CmdHeader.ClipRect;
  const ImVec2 lo(std::max(min.x, clip.x), std::max(min.y, clip.y));
  const ImVec2 hi(std::min(max.x, clip.z), std::min(max.y, clip.w));
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
  const ImU32 col = ToImColor(color);
  if (!clear_backgrounds_ || (col >> IM_COL32_A_SHIFT) != 0xFF || !(hi.x > lo.x && hi.y > lo.y) ||
      ImGui::GetIO().DisplayFramebufferScale.y != scale || !OnWholePixels(min, scale) ||
      !OnWholePixels(max, scale) || !OnWholePixels(ImVec2(clip.x, clip.y), scale) ||
      !OnWholePixels(ImVec2(clip.z, clip.w), scale)) {
    FillRect(min, max, color, 0);
    return;
  }
  dl_->PushClipRect(lo, hi, false);
  dl_->AddCallback(ClearRectCallback, reinterpret_cast<void*>(static_cast<std::uintptr_t>(col)));
  dl_->PopClipRect();
}

float ImGuiCanvas::StrokeWidth(float width) const {
  // Only where ImGui's textured lines apply: a fringe of one logical pixel (framebuffer scale 1).
  if (!whole_pixel_lines_ || fonts_.scale != 1.0f || !(width < 63.0f)) return width;
  return std::max(1.0f, std::round(width));
}

void ImGuiCanvas::StrokeRect(ImVec2 min, ImVec2 max, sim::Color color, float width,
                             float rounding) {
  dl_->AddRect(min, max, ToImColor(color), rounding, 0, StrokeWidth(width));
}

// The dash pattern runs on along the whole polyline (it does not restart at each vertex); each
// dash is one polyline, so dashes that turn a corner keep a smooth join.
void ImGuiCanvas::DashedPolyline(const ImVec2* pts, int n, ImU32 col, float width,
                                 const LineDash& dash) {
  width = StrokeWidth(width);
  float period = 0;
  for (int k = 0; k < dash.count; ++k) period += dash.lengths[k];
  if (!(period > 0.5f)) {
    dl_->AddPolyline(pts, n, col, ImDrawFlags_None, width);
    return;
  }
  int k = 0;                     // current entry of the pattern (even: drawing)
  float left = dash.lengths[0];  // length left in it
  std::vector<ImVec2> run;
  auto flush = [&]() {
    if (run.size() > 1) dl_->AddPolyline(run.data(), static_cast<int>(run.size()), col, 0, width);
    run.clear();
  };
  for (int i = 1; i < n; ++i) {
    ImVec2 a = pts[i - 1];
    const ImVec2 b = pts[i];
    float len = std::hypot(b.x - a.x, b.y - a.y);
    while (len > 0) {
      const float step = std::min(left, len);
      const ImVec2 c(a.x + (b.x - a.x) * step / len, a.y + (b.y - a.y) * step / len);
      const bool drawing = (k % 2) == 0;
      if (drawing) {
        if (run.empty()) run.push_back(a);
        run.push_back(c);
      }
      left -= step;
      len -= step;
      a = c;
      if (left <= 1e-4f) {
        if (drawing) flush();
        k = (k + 1) % dash.count;
        left = dash.lengths[k];
      }
    }
  }
  flush();
}

void ImGuiCanvas::Polyline(const ImVec2* pts, int n, const Stroke& stroke, bool closed) {
  if (n < 2) return;
  const ImU32 col = ToImColor(stroke.color);
  if (stroke.dash.solid()) {
    dl_->AddPolyline(pts, n, col, closed ? ImDrawFlags_Closed : ImDrawFlags_None,
                     StrokeWidth(stroke.width));
    return;
  }
  if (!closed) {
    DashedPolyline(pts, n, col, stroke.width, stroke.dash);
    return;
  }
  std::vector<ImVec2> loop(pts, pts + n);
  loop.push_back(pts[0]);
  DashedPolyline(loop.data(), static_cast<int>(loop.size()), col, stroke.width, stroke.dash);
}

void ImGuiCanvas::FillPolygonAliased(const ImVec2* pts, int n, sim::Color color) {
  const ImDrawListFlags flags = dl_->Flags;
  dl_->Flags &= ~ImDrawListFlags_AntiAliasedFill;
  FillPolygon(pts, n, color);
  dl_->Flags = flags;
}

void ImGuiCanvas::FillFan(const ImVec2* pts, int n, sim::Color color, const std::string&) {
  if (n < 3 || color.a <= 0) return;
  const ImU32 col = ToImColor(color);
  for (int i = 1; i + 1 < n; ++i) {
    ImVec2 tri[3] = {pts[0], pts[i], pts[i + 1]};
    // ImGui's anti-aliased fill wants clockwise points on screen (y down): a positive area.
    if (SignedArea(tri, 3) < 0) std::swap(tri[1], tri[2]);
    dl_->AddConvexPolyFilled(tri, 3, col);
  }
  // The triangles' fringes meet half covered along the inner edges, which would show as a light
  // seam: a one-pixel line along each covers it.
  for (int i = 2; i + 1 < n; ++i) dl_->AddLine(pts[0], pts[i], col, 1.0f);
}

// Concave polygons (floor patches may be any simple polygon) are ear-clipped into triangles;
// convex ones go to ImGui's anti-aliased convex fill.
void ImGuiCanvas::FillPolygon(const ImVec2* pts, int n, sim::Color color) {
  if (n < 3) return;
  const ImU32 col = ToImColor(color);
  if (IsConvex(pts, n)) {
    dl_->AddConvexPolyFilled(pts, n, col);
    return;
  }
  std::vector<ImVec2> p(pts, pts + n);
  if (SignedArea(p.data(), n) < 0) std::reverse(p.begin(), p.end());  // counter-clockwise, y up
  std::vector<int> idx(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) idx[i] = static_cast<int>(i);
  int guard = 0;
  while (idx.size() > 3 && guard++ < 10000) {
    bool clipped = false;
    for (std::size_t i = 0; i < idx.size(); ++i) {
      const ImVec2 a = p[idx[(i + idx.size() - 1) % idx.size()]], b = p[idx[i]],
                   c = p[idx[(i + 1) % idx.size()]];
      const float cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      if (cross <= 0) continue;  // reflex vertex
      bool ear = true;
      for (int k : idx) {
        const ImVec2 q = p[k];
        if ((q.x == a.x && q.y == a.y) || (q.x == b.x && q.y == b.y) || (q.x == c.x && q.y == c.y))
          continue;
        if (PointInTriangle(q, a, b, c)) {
          ear = false;
          break;
        }
      }
      if (!ear) continue;
      dl_->AddTriangleFilled(a, b, c, col);
      idx.erase(idx.begin() + static_cast<long>(i));
      clipped = true;
      break;
    }
    if (!clipped) break;  // degenerate input: draw what is left as a fan
  }
  for (std::size_t i = 1; i + 1 < idx.size(); ++i)
    dl_->AddTriangleFilled(p[idx[0]], p[idx[i]], p[idx[i + 1]], col);
}

// ImGui fills convex polygons only, and an ear-clipped band outline showed the triangles' anti-
// aliased edges as streaks (or, when clipping failed on a band of zero width, a wedge across the
// plot). So a band is filled as one convex piece per pair of neighbouring x, a trapezoid (its
// sides are vertical) or two triangles meeting where the curves cross, without anti-aliasing so
// the pieces meet without seams. Each piece is clockwise on screen (top-left first).
void ImGuiCanvas::FillBetween(const ImVec2* upper, const ImVec2* lower, int n, sim::Color color) {
  const ImU32 col = ToImColor(color);
  const ImDrawListFlags flags = dl_->Flags;
  dl_->Flags &= ~ImDrawListFlags_AntiAliasedFill;
  for (int i = 0; i + 1 < n; ++i) {
    const ImVec2 u0 = upper[i], l0 = lower[i], u1 = upper[i + 1], l1 = lower[i + 1];
    if (!(u1.x > u0.x)) continue;  // no width
    const float d0 = l0.y - u0.y, d1 = l1.y - u1.y;
    if (d0 * d1 < 0) {
      const float t = d0 / (d0 - d1);
      const ImVec2 cross(u0.x + t * (u1.x - u0.x), u0.y + t * (u1.y - u0.y));
      const ImVec2 left[3] = {ImVec2(u0.x, std::min(u0.y, l0.y)), cross,
                              ImVec2(u0.x, std::max(u0.y, l0.y))};
      const ImVec2 right[3] = {cross, ImVec2(u1.x, std::min(u1.y, l1.y)),
                               ImVec2(u1.x, std::max(u1.y, l1.y))};
      dl_->AddConvexPolyFilled(left, 3, col);
      dl_->AddConvexPolyFilled(right, 3, col);
      continue;
    }
    if (d0 == 0 && d1 == 0) continue;  // no height
    const ImVec2 quad[4] = {ImVec2(u0.x, std::min(u0.y, l0.y)), ImVec2(u1.x, std::min(u1.y, l1.y)),
                            ImVec2(u1.x, std::max(u1.y, l1.y)), ImVec2(u0.x, std::max(u0.y, l0.y))};
    dl_->AddConvexPolyFilled(quad, 4, col);
  }
  dl_->Flags = flags;
}

void ImGuiCanvas::FillCircle(ImVec2 center, float radius, sim::Color color) {
  // num_segments 0: ImGui picks enough segments for a smooth circle at this radius.
  dl_->AddCircleFilled(center, radius, ToImColor(color), radius < 4.0f ? 8 : 0);
}

void ImGuiCanvas::StrokeCircle(ImVec2 center, float radius, sim::Color color, float width) {
  dl_->AddCircle(center, radius, ToImColor(color), 0, StrokeWidth(width));
}

float ImGuiCanvas::FontSize(FontRole font) const {
  return fonts_.Get(font)->FontSize / fonts_.scale;
}

ImVec2 ImGuiCanvas::TextSize(FontRole font, const std::string& text) const {
  ImFont* f = fonts_.Get(font);
  return f->CalcTextSizeA(f->FontSize / fonts_.scale, FLT_MAX, 0.0f, text.c_str());
}

void ImGuiCanvas::Text(ImVec2 pos, FontRole font, sim::Color color, const std::string& text) {
  ImFont* f = fonts_.Get(font);
  // Whole device pixels: glyphs are sharp.
  const float s = fonts_.scale;
  dl_->AddText(f, f->FontSize / s, ImVec2(std::round(pos.x * s) / s, std::round(pos.y * s) / s),
               ToImColor(color), text.c_str());
}

void ImGuiCanvas::DrawVertical(ImVec2 center, FontRole font, sim::Color color,
                               const std::string& text, ImVec2 ext, bool markup) {
  dl_->PushClipRect(ImVec2(-1e5f, -1e5f), ImVec2(1e5f, 1e5f), false);  // no culling before rotating
  const int v0 = dl_->VtxBuffer.Size;
  const ImVec2 flat(center.x - ext.x / 2, center.y - ext.y / 2);
  if (markup)
    Label(flat, font, color, text);
  else
    Text(flat, font, color, text);
  for (int i = v0; i < dl_->VtxBuffer.Size; ++i) {
    const ImVec2 p = dl_->VtxBuffer[i].pos;
    dl_->VtxBuffer[i].pos = ImVec2(center.x + (p.y - center.y), center.y - (p.x - center.x));
  }
  dl_->PopClipRect();
}

float MarkupRunsWidth(ImFont* f, float size, const std::string& markup) {
  float w = 0;
  for (const MarkupRun& run : AtlasRuns(markup))
    w += f->CalcTextSizeA(PlacementOf(run.kind).scale * size, FLT_MAX, 0.0f, run.text.c_str()).x;
  return w;
}

void DrawMarkupRuns(ImDrawList* dl, ImFont* f, float size, ImVec2 pos, ImU32 col,
                    const std::string& markup, float snap, bool snap_x) {
  // A run's top so that its baseline is the line's, moved by its shift (ascents scale with size).
  const float ascent = f->Ascent / f->FontSize;
  float x = pos.x;
  for (const MarkupRun& run : AtlasRuns(markup)) {
    const RunPlacement place = PlacementOf(run.kind);
    const float run_size = place.scale * size;
    const float y = pos.y + ascent * size + place.shift_em * size - ascent * run_size;
    dl->AddText(f, run_size,
                ImVec2(snap_x ? std::round(x * snap) / snap : x, std::round(y * snap) / snap), col,
                run.text.c_str());
    x += f->CalcTextSizeA(run_size, FLT_MAX, 0.0f, run.text.c_str()).x;
  }
}

ImVec2 ImGuiCanvas::LabelSize(FontRole font, const std::string& markup) const {
  ImFont* f = fonts_.Get(font);
  const float size = f->FontSize / fonts_.scale;
  return ImVec2(MarkupRunsWidth(f, size, markup), size);
}

void ImGuiCanvas::Label(ImVec2 pos, FontRole font, sim::Color color, const std::string& markup) {
  ImFont* f = fonts_.Get(font);
  DrawMarkupRuns(dl_, f, f->FontSize / fonts_.scale, pos, ToImColor(color), markup, fonts_.scale,
                 true);
}

void ImGuiCanvas::PushClip(ImVec2 min, ImVec2 max) {
  dl_->PushClipRect(min, max, true);
}

void ImGuiCanvas::PopClip() {
  dl_->PopClipRect();
}

}  // namespace formsim::app
