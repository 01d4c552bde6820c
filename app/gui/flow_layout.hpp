#pragma once
/// \file Rows of widgets that wrap instead of running off a panel's edge: the width a button,
/// checkbox or text will take, and "on this line if it fits, else on the next". At UI scale 2 a
/// panel is half as wide in font units, so every row of a panel goes through these (issue 24).

namespace formsim::app {

/// Width of ImGui::Button(label) at its natural size (the text after "##" not counted).
float ButtonWidth(const char* label);
/// Width of ImGui::Checkbox(label): the box, the inner spacing and the text.
float CheckboxWidth(const char* label);
/// Width of ImGui::Text(text).
float TextWidth(const char* text);

/// Call between two items instead of ImGui::SameLine(): keeps the next item, `width` wide, on the
/// current line when it fits before the window's right edge, else starts a new line. Returns
/// whether it stayed on the line.
bool SameLineIfFits(float width);

}  // namespace formsim::app
