// earc-scenario generate --family mobile|arms --robots N [--obstacles [K]]
//   [--seed S] [--shape box|disc] [--radius R] [--workspace W] [--rotated]
//   -o FILE
// A random scenario of the paper's families (earc/gen/generators.hpp); the
// same options give the same file on every platform.
#include <iostream>
#include <memory>
#include <string>

#include "earc/cli/subcommands.hpp"
#include "earc/gen/generators.hpp"
#include "earc/gen/scenario_text.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/format.hpp"
#include "refusals.hpp"

namespace {

// --obstacles given without a count: the family's default.
constexpr int kFamilyDefault = -1;
constexpr const char* kFamilyDefaultText = "default";

struct GenerateOptions {
  std::string family = "mobile";
  int robots = 16;
  int obstacles = 0;
  bool rotated = false;
  std::uint64_t seed = 1;
  std::string shape = "box";
  double radius = 0.3;
  double workspace = 20.0;
  std::string output;
};

earc::Scenario generate(const GenerateOptions& opt) {
  if (opt.family == "arms") {
    earc::gen::ArmSettings s;
    s.robots = opt.robots;
    s.obstacles = opt.obstacles == kFamilyDefault ? earc::gen::defaultArmObstacles(opt.robots) : opt.obstacles;
    s.rotated_obstacles = opt.rotated;
    s.seed = opt.seed;
    return earc::gen::generateArms(s);
  }
  earc::gen::MobileSettings s;
  s.robots = opt.robots;
  s.obstacles = opt.obstacles == kFamilyDefault ? earc::gen::kDefaultMobileObstacles : opt.obstacles;
  s.rotated_obstacles = opt.rotated;
  s.workspace = opt.workspace;
  s.seed = opt.seed;
  s.footprint.shape = opt.shape == "disc" ? earc::MobileShape::Disc : earc::MobileShape::Box;
  s.footprint.radius = opt.radius;
  return earc::gen::generateMobile(s);
}

void runGenerate(const GenerateOptions& opt) {
  earc::requireWritableOutput({"-o", opt.output});
  const earc::Scenario s = earc::scenario_cli::generateOrRefuse("", [&] { return generate(opt); });
  earc::gen::writeScenarioFile(opt.output, s);
  earc::summaryStream({opt.output}) << opt.output << ": " << earc::gen::scenarioSummary(s) << "\n";
}

void setupGenerate(CLI::App& app) {
  auto opt = std::make_shared<GenerateOptions>();
  CLI::App* sub = app.add_subcommand("generate", "Generate a random scenario (mobile robots or facing pairs of arms)");
  sub->add_option("--family", opt->family, "mobile or arms")
      ->check(CLI::IsMember({"mobile", "arms"}))
      ->capture_default_str();
  sub->add_option("--robots,-n", opt->robots, "Number of robots")->check(earc::cli::wholeNumberIn(2, 128))->capture_default_str();
  // The flag alone stands for "default", not for -1 (which a user could
  // type, and which used to be taken as the family's default).
  sub->add_option_function<std::string>(
         "--obstacles",
         [opt](const std::string& k) { opt->obstacles = k == kFamilyDefaultText ? kFamilyDefault : std::stoi(k); },
         "Random box obstacles; the flag alone: 12 (mobile) or one per pair (arms); default none")
      ->expected(0, 1)
      ->default_str(kFamilyDefaultText)
      ->option_text("[K]")
      ->check(CLI::Validator(
          [](std::string& k) -> std::string {
            if (k == kFamilyDefaultText) return {};
            if (!earc::isDigits(k) || k.size() > 4 || std::stoi(k) > 1000) return "'" + k + "' is not a count in [0, 1000]";
            return {};
          },
          "K in [0, 1000]"));
  sub->add_flag("--rotated", opt->rotated, "Turn obstacles by random angles");
  sub->add_option("--seed,-s", opt->seed, "Random seed")->check(earc::cli::kWholeNumber)->capture_default_str();
  CLI::Option* shape = sub->add_option("--shape", opt->shape, "Mobile footprint: box (0.6 x 0.4) or disc")
      ->check(CLI::IsMember({"box", "disc"}))
      ->capture_default_str();
  CLI::Option* radius = sub->add_option("--radius", opt->radius, "Disc radius (--shape disc)")->check(earc::cli::kFinitePositive)->capture_default_str();
  CLI::Option* workspace = sub->add_option("--workspace", opt->workspace, "Side of the square workspace (mobile)")
      ->check(earc::cli::kFinitePositive)
      ->capture_default_str();
  sub->add_option("-o,--output", opt->output, "Scenario file to write")->check(earc::cli::kFileName)->required();
  sub->callback([opt, shape, radius, workspace] {
    if (opt->family == "arms" && (shape->count() || radius->count() || workspace->count()))
      throw CLI::ValidationError("--shape, --radius and --workspace", "apply to --family mobile only");
    earc::scenario_cli::requireDiscForRadius(shape, opt->shape, radius);
    // Turning obstacles that are not there would change nothing, silently.
    if (opt->rotated && opt->obstacles == 0) throw CLI::ValidationError("--rotated", "turns obstacles: give --obstacles");
    runGenerate(*opt);
  });
}

}  // namespace

static earc::cli::Registrar registered_generate("earc-scenario", "generate", setupGenerate);
