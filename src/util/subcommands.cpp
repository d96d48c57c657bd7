#include "earc/util/subcommands.hpp"

#include <algorithm>
#include <iostream>

#include "earc/io/input_error.hpp"

namespace earc::cli {

namespace {
int g_exit_code = 0;
}

void setExitCode(int code) { g_exit_code = code; }

int runProgram(const std::string& program, const std::string& description, int argc, char** argv) {
  CLI::App app{description, program};
  app.require_subcommand(1);
  auto entries = registry();
  // Registration order follows static initialisation order; sort for a stable --help.
  std::sort(entries.begin(), entries.end(),
            [](const SubcommandEntry& a, const SubcommandEntry& b) { return a.name < b.name; });
  for (const auto& e : entries)
    if (e.program == program) e.setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const InputError& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 1;
  }
  return g_exit_code;
}

}  // namespace earc::cli
