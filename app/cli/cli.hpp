#pragma once
/// \file The formsim command line: `formsim run`, `formsim list`, `formsim gui`, `formsim sweep`,
/// `formsim sweep collect`, `formsim tune`.

namespace formsim::app {

/// Parses the command line and runs the chosen command. Returns the process exit code.
int Main(int argc, char** argv);

}  // namespace formsim::app
