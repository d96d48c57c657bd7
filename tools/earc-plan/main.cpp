// earc-plan: plan, validate, render and view multi-robot motion plans.
// Subcommands register themselves (see earc/util/subcommands.hpp).
#include "earc/util/subcommands.hpp"

int main(int argc, char** argv) {
  return earc::cli::runProgram("earc-plan", "earc-plan: plan, validate, render and view multi-robot motion plans", argc, argv);
}
