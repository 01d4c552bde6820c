#include "app/cli/cli_messages.hpp"

#include <cstdio>

#include "sim/core/number_format.hpp"

namespace formsim::app {

void PrintCliError(const std::string& message) {
  std::fputs(("formsim: error: " + message + "\n").c_str(), stderr);
}

void PrintExportFailed(const std::string& error) {
  PrintCliError("export failed (the results were written): " + error);
}

std::string ProgressTimeText(double t) {
  return sim::Sprintf("t=%.2f s", t);
}

std::string WroteRunOutputsText(const std::string& out) {
  return "wrote " + out + "/timeseries.csv and " + out + "/summary.json";
}

void ClearStatusLine() {
  std::fputs(("\r" + std::string(78, ' ') + "\r").c_str(), stderr);
}

}  // namespace formsim::app
