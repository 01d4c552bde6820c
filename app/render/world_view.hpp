#pragma once
/// \file The world view: background, metre grid with coordinates, scale bar, simulated time, then
/// everything the experiment draws through sim::DrawSink, onto any Canvas in any theme.

#include <set>
#include <string>

#include "app/render/camera.hpp"
#include "app/render/canvas.hpp"
#include "app/render/theme.hpp"
#include "app/render/view.hpp"
#include "app/render/world_legend.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

/// Another run drawn faded over the one in view (a pinned run), with a legend entry.
struct WorldOverlay {
  const sim::Experiment* exp = nullptr;
  std::string label;  ///< "pin 1: k_l 0.15 -> 0.4"
  sim::Color color;   ///< of its legend entry
};

/// What a drawing of the world view placed, for the layout report (issue 24 item 5).
struct WorldViewReport {
  int labels = 0;                 ///< scene labels drawn
  int overlapping_labels = 0;     ///< drawn labels that overlap another drawn label or a robot body
  double formation_fraction = 0;  ///< FormationFraction() of the robots in this view
  ImVec4 scale_bar_box;           ///< the scale bar's backdrop (x0, y0, x1, y1); empty: none
  /// The robots as drawn (screen centre and circumscribed radius), for the layout report.
  struct Robot {
    std::string name;
    ImVec2 centre;
    float radius = 0;
  };
  std::vector<Robot> robots;
  ImVec4 legend_box;  ///< the legend's box as drawn (x0, y0, x1, y1); empty: none
};

struct WorldViewOptions {
  bool grid = true;
  bool scale_bar = true;
  bool time_label = true;
  bool coordinates = true;             ///< grid values along the left and bottom edges
  std::string caption;                 ///< drawn under the time (scenario name)
  std::vector<WorldOverlay> overlays;  ///< drawn faded after the experiment, listed top right
  std::string time_note;               ///< after the time label, e.g. "(timeline; live at 7.00 s)"
  /// Overlays of the scene to draw (sim::Overlays() names); nullptr: the defaults.
  const std::set<std::string>* scene_overlays = nullptr;
  bool legend = false;  ///< a legend of every kind of mark drawn (app/render/world_legend.hpp)
  LegendState* legend_state = nullptr;  ///< the legend's corner and collapse between frames
  double clock = 0.0;                   ///< seconds, for the legend's once-a-second corner choice
  bool degrees = true;                  ///< angles in the scene's labels in degrees (else radians)
  WorldViewReport* report = nullptr;    ///< when set, filled with what this drawing placed
  /// Screen boxes (x0, y0, x1, y1) drawn over the view by others (presentation mode's bar):
  /// scene labels keep off them.
  std::vector<ImVec4> keep_clear;
  /// FocusOf(exp, kFocusTrailSeconds) when the caller has it for this frame (else computed).
  const FocusSet* focus = nullptr;
  /// Level of detail for the window's frame rate: shapes under 12 px (a zoomed-out swarm's
  /// robots) are drawn without thin anti-aliasing triangles (CanvasDrawSink::SetLevelOfDetail),
  /// and the grid has one minor line between major lines instead of four (each one-pixel line
  /// costs a software rasteriser ~0.07 ms at 1920x1080). Off for files: exported frames and
  /// figures keep their pixels.
  bool level_of_detail = false;
};

/// The overlays on by default (sim::Overlays()).
std::set<std::string> DefaultSceneOverlays();
/// Applies "name,name,..." to `out` in order: a name adds an overlay, "-name" removes it, "all",
/// "none" and "default" set them all. Returns "" or why not (an unknown name, with the known
/// ones); `out` is then unchanged.
std::string ParseSceneOverlays(const std::string& text, std::set<std::string>* out);

/// Draws the experiment into `view`'s rectangle of `canvas` (clipped to it).
void DrawWorldView(Canvas& canvas, const View& view, const sim::Experiment& exp, const Theme& theme,
                   const WorldViewOptions& opt = {});

/// Grid spacing in metres for a zoom: 1-2-5 steps at least `min_px` pixels apart.
double GridStep(double pixels_per_metre, double min_px);

/// Points `view` at the experiment in a `width` x `height` frame: the camera `fit` moves towards
/// the experiment's bounds (at once when `jump`, else smoothly, as frames of a video do).
void FrameWorldView(const sim::Experiment& exp, float width, float height, View& view, AutoFit& fit,
                    bool jump);

/// Where the pointer's coordinates (text of size `ext`) are written in `view`: bottom left, above
/// the grid's values; above the scale bar's backdrop `bar` (WorldViewReport::scale_bar_box) where
/// the two would meet (a narrow view, a large UI scale); above the `legend`'s box when that
/// holds the bottom left corner.
ImVec2 CoordinateReadoutPos(const View& view, ImVec2 ext, const ImVec4& bar,
                            const ImVec4& legend = ImVec4());

}  // namespace formsim::app
