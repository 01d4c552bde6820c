#pragma once
/// \file Ctrl-C and SIGTERM for the headless commands (run, sweep, tune): the handler only
/// notes the signal; the command stops at its next check, writes what it has and exits with
/// 128 + the signal.

#include <string>

namespace formsim::app {

/// Installs the handlers for SIGINT and SIGTERM and ignores SIGPIPE (a closed pipe is an
/// error to report, not a death).
void InstallStopSignals();
/// The stop signal received so far (0: none).
int StopSignal();
/// "SIGINT (Ctrl-C)" or "SIGTERM".
std::string StopSignalName(int sig);

}  // namespace formsim::app
