#include "app/render/clear_hoist.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "app/render/gl_api.hpp"
#include "app/render/imgui_canvas.hpp"

namespace formsim::app {
namespace {

// Whether a pixel `cmd` draws may lie in the framebuffer rectangle `r`. A triangle can only
// cover pixels whose centres lie in its bounding box (cut by the clip rectangle); the box is
// widened by 1/64 pixel for the rasteriser's snapping of vertices.
bool MayReach(const ImDrawData& dd, const ImDrawList& list, const ImDrawCmd& cmd,
              const BackgroundClear& r) {
  const ImVec2 off = dd.DisplayPos, sc = dd.FramebufferScale;
  constexpr double kSnap = 1.0 / 64.0;
  // Nothing is drawn outside the clip rectangle: most commands (another panel's) stop here.
  if (std::floor((cmd.ClipRect.z - off.x) * sc.x + kSnap - 0.5) < r.x0 ||
      std::ceil((cmd.ClipRect.x - off.x) * sc.x - kSnap - 0.5) >= r.x1 ||
      std::floor((cmd.ClipRect.w - off.y) * sc.y + kSnap - 0.5) < r.y0 ||
      std::ceil((cmd.ClipRect.y - off.y) * sc.y - kSnap - 0.5) >= r.y1)
    return false;
  for (unsigned k = 0; k + 2 < cmd.ElemCount; k += 3) {
    float lo_x = cmd.ClipRect.z, lo_y = cmd.ClipRect.w, hi_x = cmd.ClipRect.x,
          hi_y = cmd.ClipRect.y;
    for (unsigned q = 0; q < 3; ++q) {
      const ImVec2 p = list.VtxBuffer[cmd.VtxOffset + list.IdxBuffer[cmd.IdxOffset + k + q]].pos;
      lo_x = std::min(lo_x, p.x);
      lo_y = std::min(lo_y, p.y);
      hi_x = std::max(hi_x, p.x);
      hi_y = std::max(hi_y, p.y);
    }
    lo_x = std::max(lo_x, cmd.ClipRect.x);
    lo_y = std::max(lo_y, cmd.ClipRect.y);
    hi_x = std::min(hi_x, cmd.ClipRect.z);
    hi_y = std::min(hi_y, cmd.ClipRect.w);
    if (!(hi_x > lo_x && hi_y > lo_y)) continue;
    // Pixels i with lo <= i + 0.5 <= hi.
    const double x0 = std::ceil((lo_x - off.x) * sc.x - kSnap - 0.5);
    const double x1 = std::floor((hi_x - off.x) * sc.x + kSnap - 0.5);
    const double y0 = std::ceil((lo_y - off.y) * sc.y - kSnap - 0.5);
    const double y1 = std::floor((hi_y - off.y) * sc.y + kSnap - 0.5);
    if (x0 < r.x1 && r.x0 <= x1 && y0 < r.y1 && r.y0 <= y1) return true;
  }
  return false;
}

bool Overlap(const BackgroundClear& a, const BackgroundClear& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

bool Inside(const BackgroundClear& a, const BackgroundClear& b) {
  return a.x0 >= b.x0 && a.y0 >= b.y0 && a.x1 <= b.x1 && a.y1 <= b.y1;
}

// Whether a command of `dd` before `until` may change a pixel of `r`: a triangle that reaches it,
// a clear that was kept and overlaps it, or any other callback.
bool ChangedBefore(const ImDrawData& dd, const ImDrawCmd* until, const BackgroundClear& r) {
  for (int i = 0; i < dd.CmdListsCount; ++i) {
    const ImDrawList& list = *dd.CmdLists[i];
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      if (&cmd == until) return false;
      BackgroundClear other;
      if (DecodeBackgroundClear(dd, cmd, &other)) {
        if (Overlap(other, r)) return true;
      } else if (cmd.UserCallback != nullptr) {
        if (cmd.UserCallback != ImDrawCallback_ResetRenderState && !IsSkippedBackgroundClear(cmd))
          return true;
      } else if (MayReach(dd, list, cmd, r)) {
        return true;
      }
    }
  }
  return false;
}

// A colour channel in [0, 1] as the 8 bits a clear writes, or -1 where rounding could go either
// way (the GL's conversion need not round a tie as we would).
int ClearedByte(float v) {
  const float x = std::clamp(v, 0.0f, 1.0f) * 255.0f;
  const float k = std::round(x);
  return std::abs(x - k) < 0.25f ? static_cast<int>(k) : -1;
}

// Skips each background clear of `dd` that would write the colour its rectangle already has:
// `under` everywhere, or `hoisted.rgba` inside `hoisted` when `hoisted` is set, and nothing drawn
// before it changed. Returns how many.
int SkipRedundantClears(ImDrawData& dd, int fb_width, int fb_height, std::uint32_t under,
                        const BackgroundClear* hoisted) {
  int skipped = 0;
  for (int i = 0; i < dd.CmdListsCount; ++i) {
    for (ImDrawCmd& cmd : dd.CmdLists[i]->CmdBuffer) {
      BackgroundClear c;
      if (!DecodeBackgroundClear(dd, cmd, &c)) continue;
      c.x0 = std::max(c.x0, 0);
      c.y0 = std::max(c.y0, 0);
      c.x1 = std::min(c.x1, fb_width);
      c.y1 = std::min(c.y1, fb_height);
      if (!(c.x1 > c.x0 && c.y1 > c.y0)) continue;
      std::uint32_t before = under;
      if (hoisted && Inside(c, *hoisted))
        before = hoisted->rgba;
      else if (hoisted && Overlap(c, *hoisted))
        continue;  // two colours under it
      if (before != c.rgba || ChangedBefore(dd, &cmd, c)) continue;
      SkipBackgroundClear(cmd);
      ++skipped;
    }
  }
  return skipped;
}

}  // namespace

bool ClearForFrame(ImDrawData& dd, int fb_width, int fb_height, float r, float g, float b,
                   int* skipped) {
  // The first background clear, and whether anything before it reaches its rectangle.
  ImDrawCmd* first = nullptr;
  BackgroundClear c;
  bool reached = false;
  for (int i = 0; i < dd.CmdListsCount && !first && !reached; ++i) {
    ImDrawList& list = *dd.CmdLists[i];
    for (ImDrawCmd& cmd : list.CmdBuffer) {
      if (DecodeBackgroundClear(dd, cmd, &c)) {
        first = &cmd;
        break;
      }
      // Another callback may draw anything; the first clear's rectangle is needed to judge
      // geometry, so a command before it is checked once it is known (below).
      if (cmd.UserCallback != nullptr && cmd.UserCallback != ImDrawCallback_ResetRenderState) {
        reached = true;
        break;
      }
    }
  }
  if (first && !reached) {
    c.x0 = std::max(c.x0, 0);
    c.y0 = std::max(c.y0, 0);
    c.x1 = std::min(c.x1, fb_width);
    c.y1 = std::min(c.y1, fb_height);
    const double area = static_cast<double>(c.x1 - c.x0) * (c.y1 - c.y0);
    const double strips = static_cast<double>(fb_width) * fb_height - area;
    reached = !(c.x1 > c.x0 && c.y1 > c.y0) || strips > 0.5 * area;
    for (int i = 0; i < dd.CmdListsCount && !reached; ++i) {
      const ImDrawList& list = *dd.CmdLists[i];
      bool done = false;
      for (const ImDrawCmd& cmd : list.CmdBuffer) {
        if (&cmd == first) {
          done = true;
          break;
        }
        if (MayReach(dd, list, cmd, c)) {
          reached = true;
          break;
        }
      }
      if (done) break;
    }
  }
  // The frame's colour as its clear writes it, when that is sure (else no clear matches it).
  const int br = ClearedByte(r), bg = ClearedByte(g), bb = ClearedByte(b);
  const std::uint32_t under = br < 0 || bg < 0 || bb < 0
                                  ? 0u  // alpha 0: no background clear (opaque only) equals it
                                  : (static_cast<std::uint32_t>(br) << IM_COL32_R_SHIFT) |
                                        (static_cast<std::uint32_t>(bg) << IM_COL32_G_SHIFT) |
                                        (static_cast<std::uint32_t>(bb) << IM_COL32_B_SHIFT) |
                                        IM_COL32_A_MASK;
  if (!first || reached) {
    GlClear(fb_width, fb_height, r, g, b);
    *skipped = SkipRedundantClears(dd, fb_width, fb_height, under, nullptr);
    return false;
  }
  auto channel = [&c](int shift) { return static_cast<float>((c.rgba >> shift) & 0xFF) / 255.0f; };
  GlClear(fb_width, fb_height, channel(IM_COL32_R_SHIFT), channel(IM_COL32_G_SHIFT),
          channel(IM_COL32_B_SHIFT));
  // The strips around the rectangle, in GL's window coordinates (row 0 at the bottom).
  GlClearRect(0, fb_height - c.y0, fb_width, c.y0, r, g, b, 1.0f);                   // above
  GlClearRect(0, 0, fb_width, fb_height - c.y1, r, g, b, 1.0f);                      // below
  GlClearRect(0, fb_height - c.y1, c.x0, c.y1 - c.y0, r, g, b, 1.0f);                // left
  GlClearRect(c.x1, fb_height - c.y1, fb_width - c.x1, c.y1 - c.y0, r, g, b, 1.0f);  // right
  GlScissorOff();
  SkipBackgroundClear(*first);
  *skipped = 1 + SkipRedundantClears(dd, fb_width, fb_height, under, &c);
  return true;
}

}  // namespace formsim::app
