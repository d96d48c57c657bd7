// earc-scenario movingai MAP --robots N [--seed S | --scen FILE]
//   [--shape box|disc] [--radius R] -o FILE
// A scenario on a MovingAI benchmark map (earc/gen/movingai.hpp): blocked
// cells merged into box obstacles, random starts and goals, or with --scen
// the first N agents of a benchmark scenario file (movingai_scen.hpp).
// MAP (FILE) is a .map (.scen) file, or the name of one compiled in
// (datasets/movingai) when no such file exists.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "earc/cli/subcommands.hpp"
#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/movingai.hpp"
#include "earc/gen/scenario_text.hpp"
#include "earc/io/json_io.hpp"
#include "refusals.hpp"

namespace {

struct MovingAiOptions {
  std::string map;
  int robots = 8;
  std::uint64_t seed = 1;
  std::string scen;
  std::string shape = "box";
  double radius = 0.3;
  std::string output;
};

// The compiled-in maps' names: "den520d, random-32-32-10, ...".
std::string embeddedMapNames() {
  std::string names;
  for (const auto& m : earc::gen::embeddedMovingAiMaps()) names += (names.empty() ? "" : ", ") + std::string(m.name);
  return names;
}

// The compiled-in scenario files' names.
std::string embeddedScenNames() {
  std::string names;
  for (const auto& m : earc::gen::embeddedMovingAiScens()) names += (names.empty() ? "" : ", ") + std::string(m.name);
  return names;
}

earc::gen::MovingAiScen loadScen(const std::string& scen) {
  if (!std::filesystem::exists(scen)) {
    if (auto embedded = earc::gen::embeddedMovingAiScen(scen)) return *embedded;
    throw earc::InputError(scen, "", "no such file, nor a compiled-in scenario file (" + embeddedScenNames() + ")");
  }
  return earc::gen::readMovingAiScen(scen);
}

earc::gen::GridMap loadMap(const std::string& map) {
  if (!std::filesystem::exists(map)) {
    if (auto embedded = earc::gen::embeddedMovingAiMap(map)) return *embedded;
    // Neither: say both, or a mistyped map name reads as a missing file.
    throw earc::InputError(map, "", "no such file, nor a compiled-in map (" + embeddedMapNames() + ")");
  }
  return earc::gen::readMovingAiMap(map);
}

void runMovingAi(const MovingAiOptions& opt) {
  // (A compiled-in map's name is no file.)
  if (std::filesystem::exists(opt.map)) earc::requireDistinctFiles({{"the map", opt.map}, {"-o", opt.output}});
  if (std::filesystem::exists(opt.scen)) earc::requireDistinctFiles({{"--scen", opt.scen}, {"-o", opt.output}});
  earc::requireWritableOutput({"-o", opt.output});
  earc::gen::MovingAiSettings s;
  s.robots = opt.robots;
  s.seed = opt.seed;
  s.footprint.shape = opt.shape == "disc" ? earc::MobileShape::Disc : earc::MobileShape::Box;
  s.footprint.radius = opt.radius;
  const earc::gen::GridMap map = loadMap(opt.map);
  earc::Scenario sc;
  if (!opt.scen.empty()) {
    const earc::gen::MovingAiScen scen = loadScen(opt.scen);
    earc::gen::ScenSettings ss;
    ss.robots = opt.robots;
    ss.footprint = s.footprint;
    sc = earc::scenario_cli::generateOrRefuse(opt.scen, [&] { return earc::gen::scenarioFromScen(map, scen, ss); });
  } else {
    sc = earc::scenario_cli::generateOrRefuse(opt.map, [&] { return earc::gen::generateMovingAi(map, s); });
  }
  earc::gen::writeScenarioFile(opt.output, sc);
  earc::summaryStream({opt.output}) << opt.output << ": " << earc::gen::scenarioSummary(sc) << "\n";
}

void setupMovingAi(CLI::App& app) {
  auto opt = std::make_shared<MovingAiOptions>();
  CLI::App* sub = app.add_subcommand("movingai", "Make a scenario from a MovingAI .map file");
  sub->add_option("map", opt->map, "MovingAI .map file, or the name of a compiled-in map (" + embeddedMapNames() + ")")
      ->check(earc::cli::kFileName)
      ->required();
  sub->add_option("--robots,-n", opt->robots, "Number of robots")->check(earc::cli::wholeNumberIn(1, 1024))->capture_default_str();
  CLI::Option* seed = sub->add_option("--seed,-s", opt->seed, "Random seed")->check(earc::cli::kWholeNumber)->capture_default_str();
  CLI::Option* scen = sub->add_option("--scen", opt->scen,
                                      "The first --robots agents of this MovingAI .scen file (or compiled-in one: " +
                                          embeddedScenNames() + ") instead of random robots; default footprint a disc of radius 0.3")
                          ->check(earc::cli::kFileName);
  CLI::Option* shape = sub->add_option("--shape", opt->shape, "Footprint: box (0.6 x 0.4) or disc (default with --scen)")
      ->check(CLI::IsMember({"box", "disc"}))
      ->capture_default_str();
  CLI::Option* radius = sub->add_option("--radius", opt->radius, "Disc radius (--shape disc)")->check(earc::cli::kFinitePositive)->capture_default_str();
  sub->add_option("-o,--output", opt->output, "Scenario file to write")->check(earc::cli::kFileName)->required();
  sub->callback([opt, shape, radius, seed, scen] {
    // A scenario file places the robots: nothing is drawn, and its
    // README's robots are discs.
    if (scen->count() && seed->count())
      throw CLI::ValidationError("--seed", "applies to random robots, not to --scen (the file places them)");
    if (scen->count() && !shape->count()) opt->shape = "disc";
    earc::scenario_cli::requireDiscForRadius(shape, opt->shape, radius);
    runMovingAi(*opt);
  });
}

}  // namespace

static earc::cli::Registrar registered_movingai("earc-scenario", "movingai", setupMovingAi);
