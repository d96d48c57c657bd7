// earc-bench: measure the planner's building blocks and methods.
// Subcommands register themselves (see earc/cli/subcommands.hpp).
#include "earc/cli/subcommands.hpp"

int main(int argc, char** argv) {
  return earc::cli::runProgram("earc-bench", "earc-bench: measure earc's collision checking and planners", argc, argv);
}
