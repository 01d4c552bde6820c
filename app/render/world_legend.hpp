#pragma once
/// \file The world view's legend: a sample and a label for each kind of mark drawn this frame,
/// compact (two columns where they fit), collapsible, never more than 15% of the view, in the
/// corner that covers the fewest robots and trail points (re-chosen at most once a second, and
/// at once when a robot comes under it).

#include <string>
#include <vector>

#include "app/render/canvas.hpp"
#include "app/render/canvas_draw_sink.hpp"
#include "app/render/theme.hpp"
#include "app/render/view.hpp"

namespace formsim::app {

/// The largest share of the view's area the legend takes.
inline constexpr float kLegendMaxShare = 0.15f;

/// The legend's state between frames (the window keeps one; a frame drawn alone passes none).
struct LegendState {
  bool collapsed = false;     ///< only its title tab is drawn
  int corner = -1;            ///< 0 top left, 1 top right, 2 bottom left, 3 bottom right; -1 unset
  double chosen_at = -1e300;  ///< clock (s) when the corner was last chosen
  /// The layout chosen with the corner: entries shown (0: the title tab alone) and columns.
  /// Where every corner would cover a robot, fewer entries (or one column) that cover none.
  int shown = -1, columns = 1;
  int entries = -1;               ///< how many entries there were when chosen
  bool chosen_collapsed = false;  ///< whether it was folded when chosen
  ImVec2 toggle_min, toggle_max;  ///< where a click collapses or opens it (screen pixels)
  ImVec2 box_min, box_max;        ///< the legend's box as last drawn
};

/// Whether a legend drawn at `clock` with `state` (may be null) chooses its corner anew: with
/// no corner yet, a second after the last choice, or when the clock went back.
inline bool LegendCornerDue(const LegendState* state, double clock) {
  return state == nullptr || state->corner < 0 || clock - state->chosen_at >= 1.0 ||
         clock < state->chosen_at;
}

/// What the legend should not cover, on screen: robots first, then trail points.
struct LegendAvoid {
  std::vector<ImVec2> bodies, trails;
  /// The robots' radii in pixels, as `bodies` (missing: 0): a robot counts when its body reaches
  /// under the legend, not only its centre.
  std::vector<float> body_radii;
};

/// Where this frame's legend goes, chosen before the scene's labels are placed so that they keep
/// off it (PlanWorldLegend), and drawn after them (DrawPlannedWorldLegend).
struct WorldLegendPlan {
  bool drawn = false;  ///< false: no entries, or nowhere to put it
  ImVec2 lo, hi;       ///< its box on screen
  int columns = 1, rows = 0, shown = 0;
  float col_w = 0, row_h = 0, w = 0, h = 0;
  std::string title;  ///< "legend  -" or "legend  +" (folded)
};

/// Chooses the place of the legend of `entries` in `view`, away from `avoid`, and records the
/// choice in `state` (may be null: a fresh choice), as DrawWorldLegend does, without drawing.
WorldLegendPlan PlanWorldLegend(Canvas& cv, const View& view,
                                const std::vector<CanvasDrawSink::LegendEntry>& entries,
                                const LegendAvoid& avoid, LegendState* state, double clock,
                                float top_reserved, float bottom_reserved);
/// Draws the legend `plan` placed; `state` (may be null) learns its box and title tab.
void DrawPlannedWorldLegend(Canvas& cv, const Theme& theme,
                            const std::vector<CanvasDrawSink::LegendEntry>& entries,
                            const WorldLegendPlan& plan, LegendState* state);

/// Draws the legend of `entries` in `view`, placed away from `avoid`. `state` (may be null: a
/// fresh choice) keeps the corner for a second of `clock` and says whether it is collapsed.
/// `top_reserved` / `bottom_reserved`: pixels at the top and bottom taken by other labels.
void DrawWorldLegend(Canvas& cv, const View& view, const Theme& theme,
                     const std::vector<CanvasDrawSink::LegendEntry>& entries,
                     const LegendAvoid& avoid, LegendState* state, double clock, float top_reserved,
                     float bottom_reserved);

}  // namespace formsim::app
