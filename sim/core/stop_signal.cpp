#include "sim/core/stop_signal.hpp"

#include <atomic>
#include <csignal>

namespace formsim::sim {
namespace {

std::atomic<int> g_signal{0};
extern "C" void OnStopSignal(int sig) {
  g_signal = sig;
}

}  // namespace

void InstallStopSignals() {
  struct sigaction sa = {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGHUP, &sa, nullptr);  // the terminal closed: written like Ctrl-C (exit 129)
  std::signal(SIGPIPE, SIG_IGN);
}

int StopSignal() {
  return g_signal.load();
}

std::string StopSignalName(int sig) {
  if (sig == SIGINT) return "SIGINT (Ctrl-C)";
  return sig == SIGHUP ? "SIGHUP" : "SIGTERM";
}

}  // namespace formsim::sim
