// Subcommand registry for the command-line programs: each subcommand lives
// in its own file with its own options struct and registers a setup
// function here; main() builds the CLI11 app from the registry. Adding a
// subcommand never touches another subcommand's file.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace earc::cli {

using SetupFn = std::function<void(CLI::App&)>;

struct SubcommandEntry {
  std::string program;  // "earc-plan", "earc-db", ...
  std::string name;
  SetupFn setup;
};

inline std::vector<SubcommandEntry>& registry() {
  static std::vector<SubcommandEntry> entries;
  return entries;
}

// Use at namespace scope in a subcommand file:
//   static earc::cli::Registrar reg("earc-plan", "validate", setupValidate);
struct Registrar {
  Registrar(std::string program, std::string name, SetupFn fn) {
    registry().push_back({std::move(program), std::move(name), std::move(fn)});
  }
};

// Runs `program`'s app from the registry: InputError is one line on stderr
// and exit 2, another std::exception one line and exit 1; else the exit code
// the callbacks set.
int runProgram(const std::string& program, const std::string& description, int argc, char** argv);

// Subcommand callbacks report their exit status here (default 0).
void setExitCode(int code);

// Where a subcommand's success summary goes: `out`, or with -q nowhere
// (errors are exceptions and still reach stderr through runProgram).
std::ostream& unlessQuiet(bool quiet, std::ostream& out);

// Option checks that, unlike CLI11's NonNegativeNumber and PositiveNumber,
// refuse NaN and infinity, and say so without printing the largest double.
extern const CLI::Validator kFinite;
extern const CLI::Validator kFiniteNonNegative;
extern const CLI::Validator kFinitePositive;
// For unsigned options (seeds, steps): digits only, so "-1" is refused
// instead of wrapping around.
extern const CLI::Validator kWholeNumber;
// Counts (trials, jobs, repeats): the same, and not 0.
extern const CLI::Validator kPositiveWholeNumber;
// A file name: not empty (CLI11 takes `-o ""`, which then failed late with
// "cannot replace it").
extern const CLI::Validator kFileName;
// A whole number from least to most, digits only: CLI11's Range lets "0x10"
// through as 16 and calls "1e3" out of range.
CLI::Validator wholeNumberIn(long least, long most);

}  // namespace earc::cli
