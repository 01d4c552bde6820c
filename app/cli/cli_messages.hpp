#pragma once
/// \file The messages several commands print in the same words: errors, the export failure,
/// the time in a progress line and the clearing of a status line.

#include <string>

namespace formsim::app {

/// "formsim: error: MESSAGE" and a newline on stderr.
void PrintCliError(const std::string& message);
/// "formsim: error: export failed (the results were written): ERROR" on stderr (exit code 4 of
/// run and replay).
void PrintExportFailed(const std::string& error);
/// Simulated time in a progress line: "t=1.25 s" (two decimals, no spaces around '=').
std::string ProgressTimeText(double t);
/// "wrote OUT/timeseries.csv and OUT/summary.json": how run and replay start their report line.
std::string WroteRunOutputsText(const std::string& out);
/// Blanks a status line drawn on stderr with '\r' (78 columns) and returns to its start.
void ClearStatusLine();

}  // namespace formsim::app
