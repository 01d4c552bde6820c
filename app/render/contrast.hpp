#pragma once
/// \file WCAG 2.1 contrast: relative luminance, contrast ratio, and the smallest change of a
/// colour that gives it a wanted contrast against a background. Themes use it so that every ink
/// they hand out reads: text at least 4.5:1, lines and marks at least 3:1 (WCAG 1.4.3, 1.4.11).

#include "sim/core/draw.hpp"

namespace formsim::app {

/// WCAG 2.1 minimum contrast of text (1.4.3, level AA).
inline constexpr double kTextContrast = 4.5;
/// WCAG 2.1 minimum contrast of lines, marks and other graphical objects (1.4.11).
inline constexpr double kLineContrast = 3.0;

/// Relative luminance of an sRGB colour (alpha ignored), 0 (black) to 1 (white).
double RelativeLuminance(sim::Color c);
/// (L1 + 0.05) / (L2 + 0.05) with L1 the lighter: 1 (same) to 21 (black on white).
double ContrastRatio(sim::Color a, sim::Color b);
/// `c` drawn with its alpha over the opaque `background`: the colour the eye sees.
sim::Color Over(sim::Color c, sim::Color background);
/// `c` (its colour, alpha kept) moved the least way towards black on a light background, or
/// white on a dark one, until its opaque colour has `ratio` against `background`.
sim::Color WithContrast(sim::Color c, sim::Color background, double ratio);

}  // namespace formsim::app
