#pragma once
/// \file The one name of a tunable in the window, shared by the Parameters panel and the
/// command palette so that they always agree: its declared label written as label markup
/// (app/render/label_markup.hpp) with the papers' subscripts, "k l1" as k_{l1} (kₗ₁), "φ desired"
/// as φ_{des}, "σ x,y" as σ_{x,y}; and an ImGui text item that draws such markup with its
/// subscripts (Unicode ones where the font has them, else smaller and lowered).

#include <string>

#include <imgui.h>

namespace formsim::sim {
struct Param;
}  // namespace formsim::sim

namespace formsim::app {

/// A declared tunable label as markup: a symbol and a short index ("k l1", "q θ", "v max") become
/// the symbol with the index as its subscript; "X desired" becomes X_{des}; a symbol with
/// digits ("R0", "l2") gets the digits as a subscript; "v_ref" becomes v_{ref}. Every other part
/// is kept as written (escaped, so it draws exactly as declared).
std::string TunableLabelMarkup(const std::string& label);

/// The name of tunable `p` as markup: TunableLabelMarkup of its label (its key when it has none).
std::string TunableLabel(const sim::Param& p);

/// Width of `markup` drawn by MarkupTextItem with the current font.
float MarkupTextWidth(const std::string& markup);
/// A text item drawing `markup` with its sub- and superscripts, in `color` (the style's text
/// colour when alpha is 0). Hover works on it as on ImGui::TextUnformatted.
void MarkupTextItem(const std::string& markup, ImVec4 color = ImVec4(0, 0, 0, 0));
/// `name` (markup) followed by the plain `suffix` (" [m]"), fitted to `width`: the name cut with
/// "…" first, the suffix kept whole (as the tables' headers are). Returns markup.
std::string FitMarkupLabel(const std::string& name, const std::string& suffix, float width);

}  // namespace formsim::app
