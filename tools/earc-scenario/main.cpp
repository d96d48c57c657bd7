// earc-scenario: generate and convert multi-robot planning scenarios.
// Subcommands register themselves (see earc/cli/subcommands.hpp).
#include "earc/cli/subcommands.hpp"

int main(int argc, char** argv) {
  return earc::cli::runProgram("earc-scenario", "earc-scenario: generate and convert multi-robot planning scenarios", argc, argv);
}
