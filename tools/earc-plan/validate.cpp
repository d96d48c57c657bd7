// earc-plan validate SCENARIO SOLUTION [--json]: checks a solution against
// the contract's rules (shared/spec/formats.md). Exit status 0 valid,
// 1 invalid, 2 bad input (a file that is not a valid scenario or solution).
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "earc/cli/subcommands.hpp"
#include "earc/io/json_io.hpp"
#include "earc/scene/pass_through.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/validate/validator.hpp"

namespace {

// Violations printed in the text report; --json lists ValidatorSettings' default.
constexpr std::size_t kPrintedViolations = 10;

struct ValidateOptions {
  std::string scenario;
  std::string solution;
  bool json = false;
};

nlohmann::json reportToJson(const earc::Scenario& sc, const earc::ValidationReport& rep) {
  nlohmann::json violations = nlohmann::json::array();
  for (const auto& v : rep.violations) {
    nlohmann::json robots = nlohmann::json::array();
    for (int r : v.robots) robots.push_back(sc.robots[static_cast<std::size_t>(r)].name);
    violations.push_back({{"type", earc::violationTypeName(v.type)},
                          {"t", v.t < 0 ? nlohmann::json(nullptr) : nlohmann::json(v.t)},
                          {"robots", std::move(robots)},
                          {"detail", v.detail}});
  }
  return {{"valid", rep.valid},
          {"violation_count", rep.violation_count},
          {"violations", std::move(violations)},
          {"robots", sc.robots.size()},
          {"makespan", rep.makespan},
          {"sum_of_costs", rep.sum_of_costs},
          {"total_distance", rep.total_distance}};
}

void printText(const earc::Scenario& sc, const earc::ValidationReport& rep, std::ostream& out) {
  char summary[160];
  std::snprintf(summary, sizeof summary, "robots %zu, makespan %zu, sum_of_costs %zu, total_distance %.6g",
                sc.robots.size(), rep.makespan, rep.sum_of_costs, rep.total_distance);
  if (rep.valid) {
    out << "VALID: " << summary << "\n";
    return;
  }
  out << "INVALID: " << rep.violation_count << " violation(s); " << summary << "\n";
  const std::size_t shown = std::min(kPrintedViolations, rep.violations.size());
  for (std::size_t i = 0; i < shown; ++i) {
    const earc::Violation& v = rep.violations[i];
    char t[32] = "-";
    if (v.t >= 0) std::snprintf(t, sizeof t, "t=%g", v.t);
    char head[64];
    std::snprintf(head, sizeof head, "  %-9s %-15s ", t, earc::violationTypeName(v.type));
    out << head << v.detail << "\n";
  }
  if (rep.violation_count > shown) out << "  ... " << rep.violation_count - shown << " more\n";
}

// Validates and prints the report; returns the exit status (0 valid,
// 1 invalid). Bad input throws earc::InputError (exit status 2).
int runValidate(const ValidateOptions& opt, std::ostream& out) {
  try {
    // Warnings about either file (unknown keys and the like): said only
    // when both are read, on stderr or in --json's "warnings".
    earc::InputWarnings read_warnings;
    const earc::Scenario sc = earc::loadScenario(opt.scenario, &read_warnings);
    const earc::Solution sol = earc::loadSolution(opt.solution, &sc, &read_warnings);
    const earc::ValidationReport rep = earc::validateSolution(sc, sol);
    // Valid or not, the verdict holds only at the checked instants.
    if (opt.json) {
      nlohmann::json warnings = nlohmann::json::array();
      for (const earc::InputWarning& w : read_warnings) warnings.push_back(w.text());
      // Named by its file, as the readers' warnings are (FILE: PATH: REASON).
      if (const std::string warning = earc::passThroughWarning(sc); !warning.empty())
        warnings.push_back(earc::inputMessage(opt.scenario, "", warning));
      nlohmann::json report = reportToJson(sc, rep);
      report["warnings"] = std::move(warnings);
      out << earc::dumpCompact(report) << "\n";
    } else {
      earc::printInputWarnings(read_warnings);
      if (const std::string line = earc::passThroughWarningLine(sc, opt.scenario, "earc-plan"); !line.empty())
        std::cerr << line << "\n";
      printText(sc, rep, out);
    }
    return rep.valid ? 0 : 1;
  } catch (const earc::InputError& e) {
    // The one-line message goes to stderr (runProgram); --json readers
    // still get a verdict on stdout.
    if (opt.json)
      out << earc::dumpCompact({{"valid", false}, {"malformed", true}, {"error", e.what()}}) << "\n";
    throw;
  }
}

void setupValidate(CLI::App& app) {
  auto opt = std::make_shared<ValidateOptions>();
  CLI::App* sub = app.add_subcommand(
      "validate", "Check a solution against its scenario (exit 0 valid, 1 invalid, 2 bad input)");
  sub->add_option("scenario", opt->scenario, "Scenario file (earc.scenario.v1)")->check(earc::cli::kFileName)->required();
  sub->add_option("solution", opt->solution, "Solution file (earc.solution.v1)")->check(earc::cli::kFileName)->required();
  sub->add_flag("--json", opt->json, "Print one JSON object instead of text");
  sub->callback([opt] { earc::cli::setExitCode(runValidate(*opt, std::cout)); });
}

}  // namespace

static earc::cli::Registrar registered_validate("earc-plan", "validate", setupValidate);
