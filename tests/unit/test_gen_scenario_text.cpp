// Generated scenario files: the contract's JSON, one obstacle or robot per line.
#include <doctest/doctest.h>

#include <algorithm>

#include "earc/gen/generators.hpp"
#include "earc/gen/scenario_text.hpp"
#include "earc/io/json_io.hpp"

using namespace earc;

TEST_CASE("scenario text parses back to the same document") {
  gen::MobileSettings ms;
  ms.robots = 5;
  ms.obstacles = 3;
  const Scenario s = gen::generateMobile(ms);
  CHECK(parseJsonText(gen::scenarioText(s), "t.json") == scenarioToJson(s));
}

TEST_CASE("scenario text puts each obstacle and each robot on its own line") {
  gen::ArmSettings as;
  as.robots = 4;
  as.obstacles = 2;
  const Scenario s = gen::generateArms(as);
  const std::string text = gen::scenarioText(s);
  // {, format, name, "obstacles": [, 2 obstacles, ], resolution,
  // "robots": [, 4 robots, ], workspace, }
  CHECK(std::count(text.begin(), text.end(), '\n') == 16);
  CHECK(text.find("\n    {\"base\":") != std::string::npos);
}
