// earc-plan: plan, validate, render and view multi-robot motion plans.
// Subcommands register themselves (see earc/cli/subcommands.hpp).
#include "earc/cli/subcommands.hpp"

int main(int argc, char** argv) {
  return earc::cli::runProgram("earc-plan", "earc-plan: plan, validate, render and view multi-robot motion plans", argc, argv);
}
