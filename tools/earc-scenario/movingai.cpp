// earc-scenario movingai MAP --robots N [--seed S] [--shape box|disc]
//   [--radius R] -o FILE
// A scenario on a MovingAI benchmark map (earc/gen/movingai.hpp): blocked
// cells merged into box obstacles, random starts and goals. MAP is a .map
// file, or the name of a map compiled in (datasets/movingai: den520d,
// random-32-32-10, random-32-32-20) when no such file exists.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/movingai.hpp"
#include "earc/gen/scenario_text.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/subcommands.hpp"
#include "refusals.hpp"

namespace {

struct MovingAiOptions {
  std::string map;
  int robots = 8;
  std::uint64_t seed = 1;
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
  earc::requireWritableOutput({"-o", opt.output});
  earc::gen::MovingAiSettings s;
  s.robots = opt.robots;
  s.seed = opt.seed;
  s.footprint.shape = opt.shape == "disc" ? earc::MobileShape::Disc : earc::MobileShape::Box;
  s.footprint.radius = opt.radius;
  const earc::gen::GridMap map = loadMap(opt.map);
  const earc::Scenario sc = earc::scenario_cli::generateOrRefuse(opt.map, [&] { return earc::gen::generateMovingAi(map, s); });
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
  sub->add_option("--seed,-s", opt->seed, "Random seed")->check(earc::cli::kWholeNumber)->capture_default_str();
  CLI::Option* shape = sub->add_option("--shape", opt->shape, "Footprint: box (0.6 x 0.4) or disc")
      ->check(CLI::IsMember({"box", "disc"}))
      ->capture_default_str();
  CLI::Option* radius = sub->add_option("--radius", opt->radius, "Disc radius (--shape disc)")->check(earc::cli::kFinitePositive)->capture_default_str();
  sub->add_option("-o,--output", opt->output, "Scenario file to write")->check(earc::cli::kFileName)->required();
  sub->callback([opt, shape, radius] {
    earc::scenario_cli::requireDiscForRadius(shape, opt->shape, radius);
    runMovingAi(*opt);
  });
}

}  // namespace

static earc::cli::Registrar registered_movingai("earc-scenario", "movingai", setupMovingAi);
