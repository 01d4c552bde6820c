#pragma once
/// \file Colour themes of frames, figures and the GUI (`--theme light|dark|print|high-contrast`):
/// the backgrounds and inks of the world view and the plot widget, how an experiment's own
/// colours are shown, and how plot series are told apart (print: dash patterns and greys).

#include <string>
#include <vector>

#include "app/render/canvas.hpp"
#include "sim/core/draw.hpp"

namespace formsim::app {

enum class ThemeId { kLight, kDark, kPrint, kHighContrast };

/// Colours of sim::PaletteColor before it repeats: the series colour cycle (Okabe-Ito without
/// its black and yellow, then Tol's muted; colour-blind safe, pairwise ΔE*ab above 20).
constexpr int kPaletteSize = 12;

/// Marks along a line or of a scatter (the print theme tells series apart by them).
enum class MarkerShape {
  kNone,
  kCircle,
  kSquare,
  kTriangle,
  kDiamond,
  kTriangleDown,
  kPlus,
  kCross
};

/// How one plot series is drawn in a theme.
struct SeriesLook {
  sim::Color color;
  LineDash dash;
  /// Print: a marker of its own on every series (spaced along lines); other themes: none (a
  /// scatter draws circles).
  MarkerShape marker = MarkerShape::kNone;
  bool hollow_markers = false;  ///< print: every other series has open markers
};

struct Theme {
  ThemeId id;
  const char* name;       ///< "light", "dark", "print", "high-contrast"
  sim::Color background;  ///< figures and the world view
  // Plot widget
  sim::Color text, axis, grid, legend_fill, legend_border, reference, marker, cursor, error;
  // World view
  sim::Color world_minor, world_major, world_axis, coordinates, backdrop;
  /// Multiplies line widths (high-contrast draws thicker lines).
  float line_scale = 1.0f;
  /// True for dark backgrounds (the GUI's ImGui style follows).
  bool dark = false;

  /// An experiment's colour (robot, trail, mark) as shown on this theme's background: dark
  /// inks become light on dark themes, print turns colours to greys; the result has at least
  /// 3:1 contrast against the background (WCAG 2.1 for lines and marks; alpha kept).
  sim::Color Ink(sim::Color c) const;
  /// Ink() of a label: opaque, with at least 4.5:1 contrast against the background (WCAG 2.1
  /// for text).
  sim::Color TextInk(sim::Color c) const;
  /// Ink() of a filled area (a robot's body): mapped to the theme but not pushed away from the
  /// background, since its outline carries the contrast.
  sim::Color Fill(sim::Color c) const;
  /// The ink of a robot's heading arrow on a body of colour `body` (before the theme, its alpha
  /// the body's): sim::HeadingInk of the body as this theme shows it (Fill() over the
  /// background), white or near-black, opaque. The world view and its legend both draw with it.
  sim::Color HeadingInk(sim::Color body) const;
  /// Colour, dash and marker of a plot series with palette index `index` (dashed: the figure
  /// asks for a dashed line, e.g. a reference path). Colour themes: past the palette's
  /// kPaletteSize colours, series repeat colours and differ by dash pattern. Print: series
  /// differ by dash pattern (6), marker (7) and grey; the (dash, marker) pair repeats only after
  /// 42 series.
  SeriesLook Series(sim::Color color, int index, bool dashed) const;
};

/// What a colour of a theme's table is for, and so the contrast it needs (app/render/contrast).
enum class InkUse {
  kText,        ///< text: 4.5:1 against the background
  kLine,        ///< lines and marks: 3:1
  kDecoration,  ///< grid lines and fills behind the content (WCAG 1.4.11 exempts them)
};
/// One colour of a theme's table.
struct ThemeInk {
  const char* name;  ///< the member's name, e.g. "coordinates"
  sim::Color Theme::*member;
  InkUse use;
};
/// Every colour of the theme tables but the background, with its use: what the contrast test
/// checks (tests/app/contrast_test.cpp).
const std::vector<ThemeInk>& ThemeInks();

/// The theme called `id`.
const Theme& GetTheme(ThemeId id);
/// Parses "light", "dark", "print" or "high-contrast"; throws std::runtime_error naming `flag`.
ThemeId ParseTheme(const std::string& text, const std::string& flag = "--theme");
/// "light|dark|print|high-contrast", for help texts.
const char* ThemeNames();

/// Sets the current ImGui context's style colours for `theme` (the GUI panels).
void ApplyImGuiTheme(const Theme& theme);

}  // namespace formsim::app
