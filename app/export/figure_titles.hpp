#pragma once
/// \file How much of a figure's title exported figures show (`--titles full|short|none`):
/// the whole title with its panel letter ("(b) Bearing error ..."), the title alone, or none.

#include <string>

namespace formsim::app {

enum class TitleMode { kFull, kShort, kNone };

/// "full|short|none", for help texts and errors.
const char* TitleModeNames();
/// The help text of a `--titles` option.
std::string TitleModeHelp();
/// Parses "full", "short" or "none"; throws std::runtime_error naming `flag` and listing them.
TitleMode ParseTitleMode(const std::string& text, const std::string& flag = "--titles");
/// `title` as `mode` shows it. Short drops a leading panel letter ("(b) ", "Fig. 9: ") and a
/// closing parenthesis of detail ("... (UKF)"); none gives "".
std::string TitleFor(const std::string& title, TitleMode mode);

}  // namespace formsim::app
