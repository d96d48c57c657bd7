#include "earc/bench/options.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string_view>

#include "earc/bench/suites.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/format.hpp"

namespace fs = std::filesystem;

namespace earc::bench {

void requireExecutable(const std::string& path, const std::string& option) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, option, "no such file");
  if (!fs::is_regular_file(path, ec) || ::access(path.c_str(), X_OK) != 0)
    throw InputError(path, option, "not an executable program");
}

// A name ending like a file is refused: plot -o fig.png would make a
// directory fig.png holding the figures.
void requireOutputDirectory(const std::string& path, const std::string& option) {
  std::error_code ec;
  if (fs::exists(path, ec)) {
    if (!fs::is_directory(path, ec)) throw InputError(path, option, "exists and is not a directory");
    return;
  }
  const std::string ext = lowerExtension(path);
  for (const char* file_ext : {".png", ".svg", ".pdf", ".csv", ".log"})
    if (ext == file_ext)
      throw InputError(path, option, "names the directory the files go into, not a " + ext + " file; give a directory name");
}

std::vector<std::string> splitOptionList(const std::string& list, const std::string& option) {
  if (list.empty()) throw InputError("", option, "empty list");
  std::vector<std::string> items = splitList(list);
  // splitList drops empty items: one is missing for each of them.
  if (items.size() != static_cast<std::size_t>(std::count(list.begin(), list.end(), ',')) + 1)
    throw InputError("", option, "empty item in '" + list + "'");
  return items;
}

std::string reasonAbout(const std::exception& e, const std::string& path) {
  std::string why = e.what();
  if (why.rfind(path + ": ", 0) == 0) why.erase(0, path.size() + 2);
  return why;
}

void requireSeparateOutputs(const std::string& input, const std::string& input_option,
                            const std::vector<std::pair<std::string, std::string>>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto& [path, option] = outputs[i];
    if (path.empty()) continue;
    if (sameFile(path, input))
      throw InputError(path, option, "is the " + input_option + " file; writing it would destroy that");
    // Beside the real file, through any link, as well as beside the name.
    for (const char* suffix : kDatabaseCompanions)
      if (sameFile(path, input + suffix) || sameFile(path, exp::databaseFile(input) + suffix))
        throw InputError(path, option,
                         "is the " + input_option + " file's " + suffix + " file; writing it would destroy that");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].first.empty() && sameFile(path, outputs[j].first))
        throw InputError(path, option, "is the same file as " + outputs[j].second + " " + outputs[j].first);
  }
}

namespace {

// An argument as a message quotes it: on one line, cut short.
std::string quotedArg(const std::string& arg) { return "'" + printableText(arg, 80) + "'"; }

// What earc-bench gives `earc-plan plan` itself (compare's and run's plan
// commands), by option name: a second one would be refused, or would
// stand in for the benchmark's own.
bool setByBench(const std::string& arg) {
  if (arg.rfind("--", 0) == 0) {
    const std::string name = arg.substr(0, arg.find('='));
    for (const char* own : {"--output", "--method", "--time-limit", "--seed", "--db", "--no-learn", "--quiet"})
      if (name == own) return true;
    return false;
  }
  // -o FILE, -oFILE, -q (and -q clustered with others: -qv).
  return arg.size() >= 2 && arg[0] == '-' && (arg[1] == 'o' || arg[1] == 'q');
}

// An option that makes earc-plan print something and exit without planning.
bool stopsThePlan(const std::string& arg) {
  const std::string name = arg.substr(0, arg.find('='));
  return name == "--help" || name == "--version" || (arg.size() >= 2 && arg[0] == '-' && arg[1] == 'h');
}

}  // namespace

// Refused: an argument that sets what earc-bench gives earc-plan itself
// (the scenario, -o, --method, --time-limit, --seed, --db, --no-learn, -q)
// or stops every plan (--help, --version, --); an empty one; one with a
// control character or not UTF-8 (results files record it, tables show it
// on one line). Whether earc-plan takes the rest is for earc-plan to say:
// compare and run stop at the first plan it refuses (refusedItsCommand).
std::optional<std::string> plannerArgsProblem(const std::vector<std::string>& args) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.empty()) return std::string("an empty argument");
    if (printableText(a, a.size()) != a)
      return quotedArg(a) + " has a control character or a byte that is not UTF-8 text";
    if (a == "--") return "'--' ends earc-plan's options: what follows it would be taken for a scenario";
    if (stopsThePlan(a)) return quotedArg(a) + " would stop every plan before it planned";
    if (setByBench(a))
      return quotedArg(a) + " sets what earc-bench gives earc-plan itself (the scenario, -o, --method, --time-limit, "
                            "--seed, --db, --no-learn, -q)";
    // A word that is no option: an option's value when it follows one
    // written without '=' (--window 4), else a second scenario.
    const bool option = a.size() > 1 && a[0] == '-';
    const bool after_option = i > 0 && args[i - 1].size() > 1 && args[i - 1][0] == '-' &&
                              args[i - 1].find('=') == std::string::npos;
    if (!option && !after_option)
      return quotedArg(a) + " is not an option (nor the value of one): the scenario is earc-bench's to give";
  }
  return std::nullopt;
}

void requirePlannerArgs(const std::vector<std::string>& args, const std::string& option) {
  if (const auto why = plannerArgsProblem(args)) throw InputError("", option, *why);
}

bool usesDatabase(const std::string& method) { return method == "earc" || method == "lightning"; }

std::vector<std::string> planArgv(const PlanCommand& c) {
  std::vector<std::string> a = {c.program,  "plan",   c.scenario,    "-o",   c.solution, "--method", c.method,
                                "--time-limit", exactNumber(c.time_limit_s), "--seed", std::to_string(c.seed), "-q"};
  if (usesDatabase(c.method)) {
    a.insert(a.end(), {"--db", c.db});
    if (!c.learn) a.push_back("--no-learn");
  }
  a.insert(a.end(), c.extra.begin(), c.extra.end());
  return a;
}

std::string plannerArgsText(const std::vector<std::string>& args) {
  std::string out;
  for (const std::string& a : args) {
    if (!out.empty()) out += ' ';
    const bool safe = !a.empty() && std::all_of(a.begin(), a.end(), [](unsigned char c) {
      return std::isalnum(c) || std::string_view("@%+=:,./-_").find(static_cast<char>(c)) != std::string_view::npos;
    });
    if (safe) {
      out += a;
      continue;
    }
    // shlex.quote: in single quotes, each ' as '"'"'.
    out += '\'';
    for (char c : a) out += c == '\'' ? std::string("'\"'\"'") : std::string(1, c);
    out += '\'';
  }
  return out;
}

}  // namespace earc::bench
