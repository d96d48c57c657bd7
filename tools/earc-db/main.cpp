// earc-db: build, inspect and curate E-ARC experience databases.
// Subcommands register themselves (see earc/cli/subcommands.hpp).
#include "earc/cli/subcommands.hpp"

int main(int argc, char** argv) {
  return earc::cli::runProgram("earc-db", "earc-db: build, inspect and curate E-ARC experience databases", argc, argv);
}
