// earc-plan view SCENARIO SOLUTION [--trace TRACE] -o plan.html
// Writes one self-contained HTML page that animates the solution on its
// scenario (earc/view/viewer.hpp). With the trace that `earc-plan plan
// --trace` writes, the page also marks each conflict where and when it was
// found and draws each subproblem's region during its window:
//   {"format": "earc.trace.v1", "events": [
//     {"type": "conflict", "id", "robots": [a, b], "t", "place": [x, y], "at_s"},
//     {"type": "subproblem", "id", "conflict", "robots", "window": [t0, t1],
//      "region": [[xmin, ymin], [xmax, ymax]], "expansions", "merged",
//      "solved_by", "entry" (optional), "attempts": [{"solver", "ok", "time_s"}],
//      "length"}]}
#include <iostream>
#include <memory>
#include <string>

#include "earc/cli/subcommands.hpp"
#include "earc/io/json_io.hpp"
#include "earc/view/viewer.hpp"

namespace {

struct ViewOptions {
  std::string scenario;
  std::string solution;
  std::string trace;
  std::string output;
};

void runView(const ViewOptions& opt) {
  earc::requireDistinctFiles({{"the scenario", opt.scenario}, {"the solution", opt.solution}, {"--trace", opt.trace},
                              {"-o", opt.output}});
  earc::requireWritableOutput({"-o", opt.output});
  earc::requireOutputExtension({"-o", opt.output}, {".html", ".htm"});
  // Structure only, as for render: the page is for looking, and the
  // planner already checked the scenario it solved.
  // Warnings about the files (unknown keys and the like) once all are
  // read: bad input gets its one line alone.
  earc::InputWarnings warnings;
  const earc::Scenario sc = earc::scenarioFromJson(earc::readJsonFile(opt.scenario), opt.scenario, &warnings);
  const earc::Solution sol = earc::loadSolution(opt.solution, &sc, &warnings);
  earc::view::checkSolutionMatches(sc, sol, opt.solution);
  const nlohmann::json trace = opt.trace.empty() ? nlohmann::json(nullptr) : earc::view::loadTrace(opt.trace, sc);
  earc::printInputWarnings(warnings);
  earc::writeTextFileAtomic(opt.output, earc::view::viewerHtml(earc::view::viewerData(sc, sol, trace)));
  earc::summaryStream({opt.output}) << opt.output << "\n";
}

void setupView(CLI::App& app) {
  auto opt = std::make_shared<ViewOptions>();
  CLI::App* sub = app.add_subcommand("view", "Write one self-contained HTML page that animates a solution");
  sub->add_option("scenario", opt->scenario, "Scenario file (earc.scenario.v1)")->check(earc::cli::kFileName)->required();
  sub->add_option("solution", opt->solution, "Solution file (earc.solution.v1)")->check(earc::cli::kFileName)->required();
  sub->add_option("--trace", opt->trace, "Trace written by `earc-plan plan --trace` (earc.trace.v1)");
  sub->add_option("-o,--output", opt->output, "HTML page to write (.html or .htm)")->check(earc::cli::kFileName)->required();
  sub->callback([opt] { runView(*opt); });
}

}  // namespace

static earc::cli::Registrar registered_view("earc-plan", "view", setupView);
