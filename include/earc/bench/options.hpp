// Checks of earc-bench's command-line values, made before any work: each
// throws InputError naming the option (and the file, for paths), so that
// bad options end in one line and exit status 2. Single numbers are
// checked as they are parsed, by earc::cli's validators.
#pragma once

#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace earc::bench {

// An executable regular file (e.g. --plan-program).
void requireExecutable(const std::string& path, const std::string& option);

// Refuses (InputError naming `option`) a directory to write files into
// that is an existing file or a new name ending like a file (fig.png).
void requireOutputDirectory(const std::string& path, const std::string& option);

// "a,b,c" as its items; an empty list or item ("2,,4", "a,") is refused.
std::vector<std::string> splitOptionList(const std::string& list, const std::string& option);

// An exception's message without the "PATH: " it may start with, for an
// InputError that names the file itself.
std::string reasonAbout(const std::exception& e, const std::string& path);

// Refuses, before anything is written, an output that is the input file
// (or its SQLite -wal, -shm or -journal file) or the same file as another
// output. outputs: (path, option); empty paths are not outputs.
void requireSeparateOutputs(const std::string& input, const std::string& input_option,
                            const std::vector<std::pair<std::string, std::string>>& outputs);

// Why arguments added to every `earc-plan plan` command (--old-arg,
// --new-arg, --method-arg) cannot be given, or nothing. Does not ask
// earc-plan whether it takes them.
std::optional<std::string> plannerArgsProblem(const std::vector<std::string>& args);
// The same, thrown as InputError naming `option`.
void requirePlannerArgs(const std::vector<std::string>& args, const std::string& option);

// Whether a method reads a database (earc: experiences, lightning: OMPL's).
bool usesDatabase(const std::string& method);

// One plan as earc-bench runs it (run and compare): `earc-plan plan` with
// what earc-bench sets itself (plannerArgsProblem refuses these in
// `extra`), --db for a method that reads one, then `extra`.
struct PlanCommand {
  std::string program, scenario, solution, method;
  double time_limit_s = 0.0;
  std::uint64_t seed = 0;
  std::string db;
  bool learn = false;
  std::vector<std::string> extra;
};
std::vector<std::string> planArgv(const PlanCommand& c);

// The arguments as a shell would take them, each quoted as Python's
// shlex.quote quotes it (plot_results.py labels with shlex.join):
// "--db-k=5 --window 4", "'--x=a b'"; "" for none.
std::string plannerArgsText(const std::vector<std::string>& args);

}  // namespace earc::bench
