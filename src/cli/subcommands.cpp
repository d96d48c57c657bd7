#include "earc/cli/subcommands.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>

#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"
#include "earc/util/memory_reserve.hpp"
#include "earc/util/version.hpp"

namespace earc::cli {

namespace {
int g_exit_code = 0;
}

std::ostream& unlessQuiet(bool quiet, std::ostream& out) {
  static std::ostream nowhere(nullptr);  // no buffer: writes go nowhere
  return quiet ? nowhere : out;
}

void setExitCode(int code) { g_exit_code = code; }

namespace {
enum class Sign { Any, NonNegative, Positive };

CLI::Validator finiteNumber(Sign sign) {
  return CLI::Validator(
      [sign](std::string& text) -> std::string {
        double v = 0;
        std::size_t used = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size() || !std::isfinite(v))
          return "'" + text + "' is not a finite number";
        if (sign == Sign::NonNegative && v < 0) return text + " is negative";
        if (sign == Sign::Positive && v <= 0) return text + " is not positive";
        return {};
      },
      sign == Sign::Any ? "NUMBER" : sign == Sign::NonNegative ? "NUMBER >= 0" : "NUMBER > 0");
}
}  // namespace

const CLI::Validator kFinite = finiteNumber(Sign::Any);
const CLI::Validator kFiniteNonNegative = finiteNumber(Sign::NonNegative);
const CLI::Validator kFinitePositive = finiteNumber(Sign::Positive);

namespace {
// CLI11 converts "-1" into an unsigned option by wrapping it to 2^64-1, so a
// seed of -1 silently became 18446744073709551615. Only digits pass.
CLI::Validator wholeNumber(bool positive) {
  const std::string least = positive ? "1" : "0";
  return CLI::Validator(
      [positive, least](std::string& text) -> std::string {
        if (!isDigits(text) || (positive && text.find_first_not_of('0') == std::string::npos))
          return "'" + text + "' is not a whole number >= " + least;
        // CLI11 saturates a value beyond 2^64 - 1 silently.
        try {
          (void)std::stoull(text);
        } catch (const std::out_of_range&) {
          return "'" + text + "' is more than 18446744073709551615";
        }
        return {};
      },
      "N >= " + least);
}
}  // namespace

const CLI::Validator kWholeNumber = wholeNumber(false);
const CLI::Validator kPositiveWholeNumber = wholeNumber(true);

const CLI::Validator kFileName(
    [](std::string& text) -> std::string { return text.empty() ? "an empty file name" : ""; }, "FILE");

CLI::Validator wholeNumberIn(long least, long most) {
  const std::string range = std::to_string(least) + ".." + std::to_string(most);
  return CLI::Validator(
      [least, most, range](std::string& text) -> std::string {
        // More digits than any long holds is out of range, not an error.
        const bool digits = isDigits(text);
        if (!digits || text.size() > 18 || std::stol(text) < least || std::stol(text) > most)
          return "'" + text + "' is not a whole number in " + range;
        return {};
      },
      "N in " + range);
}

namespace {
// An error quotes what it was given (robot names, file names, words):
// control characters in them would split the one line or drive the
// terminal, so each becomes '?'.
std::string printable(std::string_view message) { return printableText(message, 16384); }
}  // namespace

// Builds the app for `program` from the registry, runs it, and maps
// exceptions to exit codes: earc::InputError -> one line on stderr, exit 2;
// any other std::exception -> one line, exit 1. Subcommand callbacks set
// the exit code through the returned reference.
int runProgram(const std::string& program, const std::string& description, int argc, char** argv) {
  armMemoryReserve();
  CLI::App app{description, program};
  app.require_subcommand(1);
  const std::string version_line = program + " " + std::string(version());
  app.set_version_flag("--version", version_line, "Print the build's version and exit");
  auto entries = registry();
  // Registration order follows static initialisation order; sort for a stable --help.
  std::sort(entries.begin(), entries.end(),
            [](const SubcommandEntry& a, const SubcommandEntry& b) { return a.name < b.name; });
  for (const auto& e : entries)
    if (e.program == program) e.setup(app);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    // After a subcommand too (`earc-plan plan --version`), before its required
    // arguments are asked for.
    sub->set_version_flag("--version", version_line, "Print the build's version and exit");
    // CLI11 lets one occurrence of a repeatable option take every argument
    // up to the next option: `compare --new-arg=--db-k=5 s.json` gave the
    // scenario to the planner and compared generated ones. Where positional
    // arguments may follow, each occurrence takes one (repeat the option).
    const bool positionals = !sub->get_options([](const CLI::Option* o) { return o->get_positional(); }).empty();
    if (positionals)
      for (CLI::Option* o : sub->get_options([](const CLI::Option* o) { return o->nonpositional(); }))
        o->allow_extra_args(false);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help (and the like) "fail" with success: CLI11 prints what was asked.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    // Otherwise one line and the bad-input status, like every other input error.
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    std::string help = program;  // and the subcommand, when one was named
    for (const CLI::App* sub : app.get_subcommands()) help += " " + sub->get_name();
    // No command recognised: CLI11 says only that one is required; name
    // the word it could not place instead.
    if (app.get_subcommands().empty() && argc > 1) {
      const std::string word = argv[1];
      std::string names;
      for (const auto& entry : entries)
        if (entry.program == program) names += (names.empty() ? "" : ", ") + entry.name;
      what = (word.rfind('-', 0) == 0 ? "unknown option " : "unknown command ") + word + " (commands: " + names + ")";
    }
    std::cerr << program << ": error: " << printable(what) << " (see " << help << " --help)\n";
    return kExitBadInput;
  } catch (const InputError& e) {
    std::cerr << program << ": error: " << printable(e.what()) << "\n";
    return kExitBadInput;
  } catch (const std::bad_alloc& e) {
    std::cerr << program << ": error: " << printable(outOfMemoryMessage(e)) << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << printable(e.what()) << "\n";
    return 1;
  }
  return g_exit_code;
}

}  // namespace earc::cli
