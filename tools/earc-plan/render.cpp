// earc-plan render SCENARIO [SOLUTION] -o out.svg|out.png [--step T]
//   [--strip T1,T2,...]
// Draws a scenario, or a solution on its scenario (earc/render/svg.hpp).
// A .png output goes through rsvg-convert (package librsvg2-bin).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "earc/bench/options.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/render/svg.hpp"
#include "earc/util/format.hpp"
#include "earc/validate/scenario_check.hpp"

namespace {

struct RenderOptions {
  std::string scenario;
  std::string solution;
  std::string output;
  std::vector<std::size_t> steps;  // --step T or --strip T1,T2,...
  std::string steps_option;        // which of the two, for errors
  double width = 800.0;
  bool no_labels = false;
};

// A path for a robot the scenario does not have means the two files do not
// belong together.
void requireKnownRobots(const earc::Scenario& sc, const earc::Solution& sol, const std::string& file) {
  for (std::size_t k = 0; k < sol.robot_names.size(); ++k) {
    bool known = false;
    for (const auto& r : sc.robots) known = known || r.name == sol.robot_names[k];
    if (!known)
      throw earc::InputError(file, "$.paths[" + std::to_string(k) + "].robot",
                             "robot '" + sol.robot_names[k] + "' is not in scenario '" + sc.name + "'");
  }
}

// librsvg makes no PNG of more than kMaxPngSidePx pixels a side, and said
// so in three lines of its own after all the drawing: the panels' width
// is known from the options alone, so it is refused first.
void requirePngWidth(const RenderOptions& opt) {
  const double wide = earc::render::pictureWidthPx(opt.steps.size(), opt.width);
  if (wide <= earc::render::kMaxPngSidePx) return;
  throw earc::InputError(opt.output, "--width",
                         std::to_string(opt.steps.size()) + " panels (" + opt.steps_option + ") of --width " +
                             earc::formatNumber(opt.width) + " make a PNG " + earc::formatNumber(wide) +
                             " pixels wide, more than librsvg's limit of " + earc::formatNumber(earc::render::kMaxPngSidePx) +
                             " pixels a side: use a smaller --width, fewer steps, or an .svg file");
}

// The height follows from the workspace's shape too (a tall map).
void requirePngHeight(const RenderOptions& opt, const std::string& svg) {
  const double tall = earc::render::svgSizePx(svg).height;
  if (tall <= earc::render::kMaxPngSidePx) return;
  throw earc::InputError(opt.output, "--width",
                         "--width " + earc::formatNumber(opt.width) + " makes a PNG " +
                             earc::formatNumber(tall) + " pixels tall for this workspace, more than librsvg's limit of " +
                             earc::formatNumber(earc::render::kMaxPngSidePx) +
                             " pixels a side: use a smaller --width, or an .svg file");
}

void runRender(const RenderOptions& opt) {
  earc::requireDistinctFiles({{"the scenario", opt.scenario}, {"the solution", opt.solution}, {"-o", opt.output}});
  earc::requireWritableOutput({"-o", opt.output});
  const bool png = earc::render::requireImageOutput(opt.output, "-o");
  if (png) requirePngWidth(opt);
  // Drawn even when its geometry is wrong (a start in an obstacle, robots
  // overlapping): a picture helps most when the scenario is broken. But
  // said, in the line plan would refuse it with, so that a picture is not
  // taken for a scenario's clean bill of health. Warnings about the files
  // (unknown keys and the like) once all are read and the options agree
  // with them: bad input gets its one line alone.
  earc::InputWarnings warnings;
  const earc::Scenario sc = earc::scenarioFromJson(earc::readJsonFile(opt.scenario), opt.scenario, &warnings);
  try {
    earc::checkScenarioGeometry(sc, opt.scenario);
  } catch (const earc::InputError& e) {
    warnings.push_back({e.file(), e.where(), e.reason() + " (drawn as it is; plan refuses it)"});
  }
  earc::render::SvgOptions o;
  o.steps = opt.steps;
  o.panel_width_px = opt.width;
  o.labels = !opt.no_labels;
  std::string svg;
  if (opt.solution.empty()) {
    if (!opt.steps.empty()) throw earc::InputError("", opt.steps_option, "a time step needs a SOLUTION file");
    svg = earc::render::scenarioSvg(sc, o);
  } else {
    const earc::Solution sol = earc::loadSolution(opt.solution, &sc, &warnings);
    requireKnownRobots(sc, sol, opt.solution);
    // A solution without paths (one not solved) has no time steps: a
    // picture "at t = 0" would look like a plan that had not started.
    if (!opt.steps.empty() && !sol.hasPaths()) {
      const std::string why = earc::failureReasons(sol.stats);
      const std::string state =
          sol.solved ? "the solution has no paths"
                     : "the solution is not solved" + (why.empty() ? "" : " (" + why + ")") + " and has no paths";
      throw earc::InputError(opt.solution, opt.steps_option,
                             state + ", so there are no time steps to draw: leave out " + opt.steps_option);
    }
    // A step past the makespan would draw every robot at its goal, as if
    // the plan had been that long.
    for (std::size_t t : opt.steps)
      if (t > sol.makespan())
        throw earc::InputError(opt.solution, opt.steps_option,
                               "step " + std::to_string(t) + " is beyond the solution's makespan " +
                                   std::to_string(sol.makespan()) + " (steps 0 to " + std::to_string(sol.makespan()) + ")");
    svg = earc::render::solutionSvg(sc, sol, o);
  }
  if (png) requirePngHeight(opt, svg);
  earc::printInputWarnings(warnings);
  earc::render::writeImage(opt.output, svg);
  earc::summaryStream({opt.output}) << opt.output << "\n";
}

void setupRender(CLI::App& app) {
  auto opt = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand("render", "Draw a scenario or a solution as SVG (or PNG with rsvg-convert)");
  sub->add_option("scenario", opt->scenario, "Scenario file (earc.scenario.v1)")->check(earc::cli::kFileName)->required();
  sub->add_option("solution", opt->solution, "Solution file (earc.solution.v1)")->check(earc::cli::kFileName);
  sub->add_option("-o,--output", opt->output, "Picture to write: .svg, or .png (needs rsvg-convert)")->check(earc::cli::kFileName)->required();
  CLI::Option* step = sub->add_option_function<std::size_t>(
      "--step", [opt](std::size_t t) { opt->steps = {t}; }, "Draw the robots at time step T")->check(earc::cli::kWholeNumber);
  // Split here, not by CLI11, which dropped an empty item ("0,,5") silently.
  CLI::Option* strip = sub->add_option_function<std::string>(
                              "--strip",
                              [opt](const std::string& list) {
                                opt->steps.clear();
                                for (const std::string& item : earc::bench::splitOptionList(list, "--strip")) {
                                  if (!earc::isDigits(item) || item.size() > 18)
                                    throw earc::InputError("", "--strip", "'" + item + "' is not a whole number");
                                  const std::size_t t = std::stoull(item);
                                  // Panels go left to right in the order given, each titled
                                  // with its own step: out of order, a strip reads as robots
                                  // moving back, and a repeated step draws a panel twice.
                                  if (!opt->steps.empty() && t <= opt->steps.back())
                                    throw earc::InputError("", "--strip",
                                                           "step " + item + " after step " +
                                                               std::to_string(opt->steps.back()) +
                                                               ": the steps must increase from left to right");
                                  opt->steps.push_back(t);
                                }
                              },
                              "Draw several time steps side by side, left to right: T1,T2,... (increasing)")
                           ->excludes(step);
  // CLI11's Range lets NaN through (no comparison fails), and it was drawn as width="nan".
  sub->add_option("--width", opt->width, "Width of one panel in pixels")
      ->check(earc::cli::kFinite)
      ->check(CLI::Range(100.0, 20000.0))
      ->capture_default_str();
  sub->add_flag("--no-labels", opt->no_labels, "Leave out the robot names");
  sub->callback([opt, step, strip] {
    if (step->count()) opt->steps_option = "--step";
    if (strip->count()) opt->steps_option = "--strip";
    runRender(*opt);
  });
}

}  // namespace

static earc::cli::Registrar registered_render("earc-plan", "render", setupRender);
