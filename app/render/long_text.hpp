#pragma once
/// \file Text of any length shown within ImGui's budget. ImGui draws a window's text into one
/// draw list of 16-bit indices (65,536 vertices, four per glyph), and formats "%s" into a 3 kB
/// buffer: a scenario description, lesson text, robot name or message of 100,000 characters
/// would abort the window (Debian's ImGui keeps its assertions) or be cut silently. These
/// helpers cut a long text with "…" and show the whole of it in a scrolling child that draws
/// only its visible lines.

#include <cstddef>
#include <string>

namespace formsim::app {

/// Texts up to this many bytes are drawn as they are.
constexpr std::size_t kInlineTextBytes = 1200;

/// `text` cut to at most `max_bytes` bytes (at a UTF-8 character boundary) with "…" added when
/// it was cut.
std::string Shorten(const std::string& text, std::size_t max_bytes);

/// Wrapped text, at spaces only (a number such as "0.99" never breaks): a short one as it is; a long one cut with "…", plus a "whole text (N
/// characters)" node opening a scrolling child of its lines (only the visible ones drawn).
/// `id` must be unique in the window.
void LongTextWrapped(const char* id, const std::string& text,
                     std::size_t inline_bytes = kInlineTextBytes);

/// A tooltip of any text (cut to a few thousand bytes).
void SafeTooltip(const std::string& text);

}  // namespace formsim::app
