#pragma once
/// \file Screen-space polyline simplification: drops points that lie within a fraction of a pixel
/// of the line through their neighbours. A smooth curve keeps its look with a few points per
/// bend, a flat line becomes one segment; the software rasteriser then draws far fewer triangles.

#include <imgui.h>

#include <vector>

namespace formsim::app {

/// Reumann-Witkam simplification (one pass): a point is dropped while it stays within
/// `tolerance_px` of the line from the last kept point along the current direction.
/// The first and last points are always kept.
std::vector<ImVec2> SimplifyPolyline(const std::vector<ImVec2>& pts, float tolerance_px = 0.35f);

}  // namespace formsim::app
