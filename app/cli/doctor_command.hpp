#pragma once
/// \file `formsim doctor`: where the program found its assets, and which optional parts are
/// present (Python module, ffmpeg, NLopt, Cairo, the GL renderer, a display), each missing one
/// with the Debian package that provides it.

#include <string>

namespace formsim::app {

/// "formsim 0.1.0 (git 1a2b3c4, Release)": what `formsim --version` prints.
std::string VersionLine();

/// Prints the report to stdout. Returns 0 when formsim can run (assets and fonts found), 1
/// when something it needs is missing (the report says what).
int DoctorCommand();

}  // namespace formsim::app
