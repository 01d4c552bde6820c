#pragma once
/// \file What a frame's layout cut off: after the widgets of a frame are built (before
/// ImGui::Render), the windows whose items reach past the width they show (a label or button
/// clipped at the right edge), with the text that shows at the cut, read back from the glyphs
/// the frame drew. The script action `layout-report` writes it (issue 24 item 5).

#include <string>
#include <vector>

namespace formsim::app {

/// One place where text is cut off.
struct ClippedText {
  std::string widget;     ///< the ImGui window (and line) it is in
  std::string text;       ///< the line's text as far as it shows
  float available = 0;    ///< the width the window shows, px
  float needed = 0;       ///< the width its items take, px
};

/// Every window of the current frame whose items are wider than it shows (and that cannot
/// scroll sideways), one entry per cut line.
std::vector<ClippedText> FindClippedText();

}  // namespace formsim::app
