#pragma once
/// \file The small label markup of figure texts (titles, axis labels, legend entries), parsed
/// once into runs that every backend draws its own way: `\phi` and the other Greek letters by
/// name become the letter; `x_{l}` and `\sigma^{2}` become subscript / superscript runs (SVG
/// tspans with a baseline shift, smaller shifted Cairo text in PDF, Unicode sub- and
/// superscripts in the window and PNGs where the font atlas has them, else `x_l` / `x^a`).
/// `\\`, `\_`, `\^`, `\{`, `\}` are the characters themselves; a `_` or `^` not followed by `{`
/// is itself (metric names such as max_abs_error stay as written); braces outside a script are
/// themselves. An unknown `\name` or an unclosed script group is an error.

#include <string>
#include <vector>

namespace formsim::app {

/// How a run of a label sits on the line.
enum class ScriptKind { kNormal, kSub, kSuper };

/// A stretch of a label drawn the same way: its text is what is drawn (Greek resolved, escapes
/// removed), UTF-8.
struct MarkupRun {
  ScriptKind kind = ScriptKind::kNormal;
  std::string text;
};

/// A parsed label: its runs (adjacent runs of one kind merged, no empty run) and, for bad
/// markup, what is wrong (the runs then show the bad part as written, so drawing never fails).
struct ParsedMarkup {
  std::vector<MarkupRun> runs;
  std::string error;
};

/// Parses `label`. Never throws.
ParsedMarkup ParseMarkup(const std::string& label);

/// What the markup accepts, for error messages: the commands and the script forms.
std::string MarkupAccepted();

/// "" when `label` is good markup, else the problem and what is accepted, e.g.
/// "unknown markup command '\foo' (accepted: ...)".
std::string MarkupError(const std::string& label);

/// `text` as markup that draws exactly `text` (user-given names: a backslash, `_{`, `^{` and
/// braces escaped).
std::string EscapeMarkup(const std::string& text);

/// A label as plain text without markers (a document's title, searchable text): the atlas runs'
/// text joined ("eₗ = ldes − l" for "e_{l} = l_{des} − l").
std::string PlainText(const std::string& label);

/// Runs written back as markup (text escaped, scripts as _{..} / ^{..}).
std::string RunsMarkup(const std::vector<MarkupRun>& runs);

/// `label` with its drawn text (the runs' text) cut to at most `max_bytes` bytes at a character
/// boundary and "…" added, as markup; `label` itself when it is no longer.
std::string ShortenMarkup(const std::string& label, std::size_t max_bytes);

/// How a run sits on its line: its font size as a fraction of the label's, and its baseline
/// shift in ems (down positive, y down). Shared by every canvas and writer, so what is measured
/// is what is drawn.
struct RunPlacement {
  float scale = 1, shift_em = 0;
};
RunPlacement PlacementOf(ScriptKind kind);

/// The runs a Unicode font atlas draws (the window, PNGs): a script run whose every character
/// has a Unicode sub- or superscript (U+2070-U+209F) becomes normal text in those characters;
/// the other script runs stay (drawn smaller, shifted).
std::vector<MarkupRun> AtlasRuns(const std::string& label);

/// A label as one plain string (tooltips, document titles, a cut legend entry): scripts as
/// Unicode sub- and superscripts where every character has one (U+2070-U+209F), else `_x` /
/// `^x` without braces. Text without markup comes back unchanged.
std::string MarkupText(const std::string& label);

}  // namespace formsim::app
