/// formsim: command-line entry point (run, list, gui).
#include "app/cli/cli.hpp"

int main(int argc, char** argv) {
  return formsim::app::Main(argc, argv);
}
