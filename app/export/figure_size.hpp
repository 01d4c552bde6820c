#pragma once
/// \file Sizes of exported figures: in pixels ("960x600") or in paper units ("8.5cmx6cm",
/// "3.5inx2.5in", "85mmx60mm"). A pixel is 1/96 inch (CSS); a PNG has `dpi / 96` device pixels per
/// pixel, SVG and PDF keep the physical size. A figure given in pixels is laid out at that size
/// (16 px labels, as on screen); one given in paper units is laid out 4/3 larger and shrunk to
/// fit, so its text prints at journal sizes (labels 9 pt, ticks 7.9 pt, title 9.6 pt).

#include <string>

namespace formsim::app {

struct FigureLength {
  double value = 0;         ///< as given
  std::string unit = "px";  ///< "px", "cm", "mm" or "in"
  /// Logical pixels (1/96 inch).
  double Pixels() const;
  /// "8.5cm", "960px": an SVG length.
  std::string Text() const;
};

struct FigureSize {
  FigureLength width{960, "px"}, height{600, "px"};
  /// Printed pixels per layout pixel: 1 for sizes in px, 0.75 for paper units.
  double LayoutScale() const;
  /// The size the figure is laid out at (fonts keep their pixel sizes there).
  int LayoutWidth() const;
  int LayoutHeight() const;
  /// The size of its PNG at `dpi`.
  int PngWidth(double dpi) const;
  int PngHeight(double dpi) const;
  /// "960pxx600px", "8.5cmx6cm": for messages.
  std::string Text() const;
};

/// Parses WIDTHxHEIGHT where each side is a number with an optional unit (px, cm, mm, in).
/// Throws std::runtime_error naming `flag` when malformed or outside 64 ... 8192 pixels.
FigureSize ParseFigureSize(const std::string& text, const std::string& flag);

/// Parses a dpi for PNG output (24 ... 1200). Throws std::runtime_error naming --dpi.
double ParseDpi(double dpi);

/// Throws std::runtime_error naming `what` and --dpi when a `width` x `height` pixel image at
/// `dpi` exceeds the 8192-pixel limit of the offscreen renderer.
void CheckDeviceSize(double width, double height, double dpi, const std::string& what);

}  // namespace formsim::app
