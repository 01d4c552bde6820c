#pragma once
/// \file Ctrl-C, SIGTERM and SIGHUP for the headless commands (run, sweep, tune) and the window:
/// the handler only notes the signal; the command stops at its next check (the window at its
/// next frame), writes what it has and exits with 128 + the signal (130, 143, 129). A
/// process-wide flag with no app code in it, so that the CLI and the GUI share it from below.

#include <string>

namespace formsim::sim {

/// Installs the handlers for SIGINT, SIGTERM and SIGHUP and ignores SIGPIPE (a closed pipe is an
/// error to report, not a death).
void InstallStopSignals();
/// The stop signal received so far (0: none).
int StopSignal();
/// "SIGINT (Ctrl-C)", "SIGTERM" or "SIGHUP".
std::string StopSignalName(int sig);

}  // namespace formsim::sim
