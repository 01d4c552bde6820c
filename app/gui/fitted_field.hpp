#pragma once
/// \file Fields whose text may be wider than they are (a file path, a scenario's name): while
/// not being edited they show the text cut to fit with "…" (a path keeps its file name) and the
/// whole text as a tooltip, so that nothing is cut off without saying so (issue 46).

#include <cstddef>
#include <string>

namespace formsim::app {

/// The next item's width (for ImGui::SetNextItemWidth) that leaves room for a button labelled
/// `button` on the same line, whatever the font's size.
float WidthBeside(const char* button);

/// `text` cut to `width` pixels of the current font with "…": the end kept (`keep_end`: a
/// path's file name) or the start. Unchanged when it fits.
std::string FitText(const std::string& text, float width, bool keep_end);

/// A one-line text field of the next item's width (ImGui::SetNextItemWidth). While its text
/// fits, or while it is edited, an ImGui::InputText; else a frame showing the text cut to fit
/// (end kept) with the whole text as a tooltip, which a click turns into the field. `id` is an
/// ImGui label (use "##name"). Returns whether the text changed.
bool FittedInputText(const char* id, char* buf, std::size_t size);

/// ImGui::BeginCombo with a preview cut to fit the combo's width (start kept), the whole preview
/// as a tooltip.
bool FittedCombo(const char* id, const std::string& preview);

}  // namespace formsim::app
