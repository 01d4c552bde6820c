#pragma once
/// \file The small label markup of figure texts (titles, axis labels, legend entries) turned into
/// the text drawn: `\phi` and the other Greek letters by name become the letter, `x_{l}` and
/// `\sigma^{2}` become Unicode sub- and superscripts where every character has one in the font
/// atlas (U+2070-U+209F), else `x_l` / `x^a` without braces. Unknown `\names` stay as written.

#include <string>

namespace formsim::app {

/// The drawn text of a label written with markup; text without markup comes back unchanged.
std::string MarkupText(const std::string& label);

}  // namespace formsim::app
