/// formsim: command-line entry point (run, list, gui).
#include "app/cli/cli.hpp"
#include "app/cli/heap_policy.hpp"

int main(int argc, char** argv) {
  formsim::app::ApplyHeapPolicy();
  return formsim::app::Main(argc, argv);
}
