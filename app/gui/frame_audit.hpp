#pragma once
/// \file What a person sees of a frame, measured from its draw data (after ImGui::Render): the
/// text runs it drew (read back from the font atlas's glyph quads) over the solid fills behind
/// them. `layout-report` writes it (issue 46 item 3):
/// - text cut at a clip edge (a glyph reaching past it, or trimmed at it);
/// - text overlapping other text, or a robot glyph of the world view;
/// - text under 18 px at UI scale 2 or more;
/// - text under WCAG's 4.5:1 contrast against what is drawn behind it;
/// - plots whose data area is under 120 px on a side;
/// - the world view's share of the window.
/// The draw data alone cannot name the robots, the world view or the plots: the window says
/// where it put them (AuditMarks).

#include <imgui.h>

#include <string>
#include <vector>

namespace formsim::app {

/// The smallest text at UI scale 2 and more, in physical pixels (font size: ascent + descent).
inline constexpr float kLectureTextPx = 18.0f;
/// The smallest plot data area, physical pixels on its shorter side.
inline constexpr float kSmallestPlotPx = 120.0f;

/// What the window placed in this frame that its draw data cannot name; rectangles are in
/// ImGui's logical units (x0, y0, x1, y1).
struct AuditMarks {
  float pixel_scale = 1.0f;  ///< physical pixels per logical unit (DisplayFramebufferScale)
  float ui_scale = 1.0f;     ///< the window's UI scale (the small-text rule applies from 2)
  ImVec2 display;            ///< the window's size, logical
  ImVec4 world_view;         ///< the world view's drawing area; zero size: none shown
  ImVec4 clear_colour = ImVec4(1, 1, 1, 1);  ///< what the frame is cleared to before drawing
  struct Robot {
    std::string name;
    ImVec2 centre;
    float radius = 0;  ///< the body's circumscribed radius, logical
  };
  std::vector<Robot> robots;  ///< the world view's robots as drawn
  struct Box {
    std::string name;
    ImVec4 rect;
  };
  std::vector<Box> over_world;  ///< boxes drawn over the world view (the legend)
  std::vector<Box> plots;       ///< the data areas of the plots shown
};

/// One finding, with the text (or item) it concerns and where it is.
struct AuditFinding {
  std::string window;  ///< the ImGui window that drew it
  std::string text;    ///< the text as it shows (or the item's name)
  std::string other;   ///< what it overlaps, or the colours of a contrast finding
  ImVec4 rect;         ///< its rectangle, physical pixels (x0, y0, x1, y1)
  double value = 0;    ///< px of small text, the contrast ratio, a plot's shorter side in px
};

struct FrameAudit {
  std::vector<AuditFinding> cut;           ///< text cut at a clip edge (no "…")
  std::vector<AuditFinding> overlaps;      ///< text over text or over a robot; boxes over robots
  std::vector<AuditFinding> small_text;    ///< under kLectureTextPx at UI scale >= 2
  std::vector<AuditFinding> low_contrast;  ///< under 4.5:1 against what is behind it
  std::vector<AuditFinding> small_plots;   ///< data area under kSmallestPlotPx
  double world_view_share = 0;             ///< the world view's area over the window's, 0 to 1
  int text_runs = 0;                       ///< text runs read from the frame
  std::vector<AuditFinding> runs;          ///< every text run that shows (value: its px)
};

/// Measures the frame `draw` (the current ImGui context's, after ImGui::Render) with `marks`.
FrameAudit AuditFrame(const ImDrawData& draw, const AuditMarks& marks);

}  // namespace formsim::app
