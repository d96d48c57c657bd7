// SVG pictures of scenarios and solutions: structure, strips, escaping,
// the facts and key under the picture, decimation and size.
#include <doctest/doctest.h>


#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "earc/gen/generators.hpp"
#include "earc/gen/random.hpp"
#include "earc/render/svg.hpp"
#include "earc/view/viewer.hpp"

using namespace earc;
using namespace earc::render;

#include "svg_fixtures.hpp"

using namespace earc::svg_test;

TEST_CASE("a scenario SVG is well-formed with one group per robot") {
  gen::MobileSettings ms;
  ms.robots = 8;
  ms.obstacles = 5;
  const Scenario s = gen::generateMobile(ms);
  const std::string svg = scenarioSvg(s);
  CHECK(wellFormed(svg));
  CHECK(countOf(svg, "<g class=\"robot\"") == 8);
  CHECK(countOf(svg, "<polygon points") == 2 * 8);  // box robots at start and goal; obstacles are one path
  CHECK(countOf(svg, ">m7</text>") == 2);  // at its start and its goal
}

TEST_CASE("obstacles are filled as one path, so that abutting boxes show no seam between them") {
  // Boxes filled one by one each anti-alias their shared edge: a light
  // hairline runs between the merged cells of a MovingAI map.
  Scenario s;
  s.name = "cells";
  s.workspace = {{0, 0}, {10, 10}};
  s.obstacles = {Obstacle::makeBox({2.15, 5}, {1.3, 2}), Obstacle::makeBox({3.4, 5}, {1.2, 2}),
                 Obstacle::makeCircle({7, 7}, 1), Obstacle::makeBox({7.5, 7.5}, {1, 1}, 0.4)};
  const std::string svg = scenarioSvg(s);
  CHECK(wellFormed(svg));
  CHECK(countOf(svg, "class=\"obstacles\"") == 1);
  const auto at = svg.find("<path class=\"obstacles\"");
  REQUIRE(at != std::string::npos);
  const std::string path = svg.substr(at, svg.find("/>", at) - at);
  CHECK(countOf(path, "M") == 4);  // one outline each
  CHECK(countOf(path, "Z") == 4);
  CHECK(countOf(path, " A") == 2);  // the circle: two half circles
  CHECK(countOf(svg, "<polygon") == 0);
  CHECK(countOf(svg, "<circle") == 0);
  CHECK(scenarioSvg(Scenario{"none", s.workspace, {}, {}, {}}).find("obstacles") == std::string::npos);
}

TEST_CASE("arms are drawn link by link as capsules with joints") {
  gen::ArmSettings as;
  as.robots = 2;
  const Scenario s = gen::generateArms(as);
  const std::string svg = scenarioSvg(s);
  CHECK(wellFormed(svg));
  CHECK(countOf(svg, "<g class=\"robot\"") == 2);
  CHECK(countOf(svg, "<path d=\"M") == 2 * 2 * 5);  // 5 links at start and goal
}

TEST_CASE("a solution SVG draws each robot's path as a polyline and the robots at the chosen step") {
  gen::MobileSettings ms;
  ms.robots = 4;
  const Scenario s = gen::generateMobile(ms);
  SvgOptions o;
  o.steps = {10};
  const std::string svg = solutionSvg(s, straightSolution(s, 40), o);
  CHECK(wellFormed(svg));
  CHECK(countOf(svg, "<polyline class=\"path\"") == 4);
  CHECK(countOf(svg, "t = 10") == 1);
  CHECK(countOf(svg, "<polygon points") == 3 * 4);  // start, goal and step 10
}

TEST_CASE("a strip draws one panel per step, each with every robot") {
  gen::MobileSettings ms;
  ms.robots = 3;
  const Scenario s = gen::generateMobile(ms);
  SvgOptions o;
  o.steps = {0, 5, 20};
  const std::string svg = solutionSvg(s, straightSolution(s, 20), o);
  CHECK(wellFormed(svg));
  CHECK(countOf(svg, "<g class=\"panel\"") == 3);
  CHECK(countOf(svg, "<g class=\"robot\"") == 9);
  CHECK(countOf(svg, "t = 20") == 1);
}

TEST_CASE("a strip moves each panel right and draws the same path in each") {
  const Scenario s = oneDisc({1, 1}, {9, 9});
  SvgOptions o;
  o.steps = {0, 10};
  o.panel_width_px = 500;
  const std::string svg = solutionSvg(s, straightSolution(s, 10), o);
  CHECK(countOf(svg, "transform=\"translate(0,0)\"") == 1);
  CHECK(countOf(svg, "transform=\"translate(516,0)\"") == 1);  // width + gap
  const auto at = svg.find("points=\"");
  const std::string points = svg.substr(at, svg.find('"', at + 8) - at);
  CHECK(countOf(svg, points) == 2);
}

TEST_CASE("paths are matched to robots by name, not by position") {
  const Scenario s = twoDiscs({1, 1}, {9, 9}, {1, 9}, {9, 1});
  Solution sol = straightSolution(s, 10);
  std::swap(sol.paths[0], sol.paths[1]);
  sol.robot_names = {"m1", "m0"};
  SvgOptions o;
  o.steps = {10};  // every robot at its goal
  const std::string svg = solutionSvg(s, sol, o);
  // m0 ends at (9, 9): top right, so its last polyline point has a small y.
  const auto group = svg.find("data-robot=\"m0\"");
  const auto points = svg.find("points=\"", group) + 8;
  const std::string line = svg.substr(points, svg.find('"', points) - points);
  const double last_y = std::stod(line.substr(line.rfind(',') + 1));
  CHECK(last_y < 200);
}

TEST_CASE("the y axis points up: a robot near the top is drawn near the top of the picture") {
  const std::string svg = scenarioSvg(oneDisc({5, 9}, {5, 1}));
  // The filled start disc follows the outlined goal in the robot's group.
  const auto goal = svg.find("<circle", svg.find("class=\"robot\""));
  const auto start = svg.find("<circle", goal + 1);
  auto cy = [&](std::size_t at) { return std::stod(svg.substr(svg.find("cy=\"", at) + 4)); };
  CHECK(cy(start) < cy(goal));
}

TEST_CASE("robot and scenario names are escaped") {
  Scenario s = oneDisc({2, 2}, {8, 8});
  s.name = "a<b & \"c\"";
  s.robots[0].name = "r<0>";
  const std::string svg = scenarioSvg(s);
  CHECK(wellFormed(svg));
  CHECK(countOf(svg, "r&lt;0&gt;") == 3);  // data attribute and labels at start and goal
}

TEST_CASE("names with characters XML 1.0 forbids are drawn with U+FFFD, so the SVG stays XML") {
  // A name read from JSON may hold any character, escaped in the file (U+0001,
  // even U+0000); XML 1.0 allows none of the C0 controls but tab and line
  // breaks, not even as &#1;: one in an attribute and the picture does not open.
  Scenario s = oneDisc({2, 2}, {8, 8});
  s.name = std::string("scen\x02\xEF\xBF\xBF", 8);
  s.robots[0].name = std::string("ctl\x01x\0", 6);
  const std::string svg = scenarioSvg(s);
  CHECK(wellFormed(svg));
  CHECK(std::all_of(svg.begin(), svg.end(), [](char c) { return static_cast<unsigned char>(c) >= 0x20 || c == '\n'; }));
  CHECK(svg.find("\xEF\xBF\xBF") == std::string::npos);
  CHECK(svg.find("&#") == std::string::npos);
  CHECK(countOf(svg, "ctl\xEF\xBF\xBDx\xEF\xBF\xBD") == 3);  // data attribute and labels at start and goal
  CHECK(countOf(svg, "scen\xEF\xBF\xBD\xEF\xBF\xBD") == 2);   // title and panel heading
}

TEST_CASE("an unsolved solution's picture says that it is not solved, and why, under the title") {
  const Scenario s = oneDisc({2, 2}, {8, 8});
  Solution sol;
  sol.scenario = s.name;
  sol.method = "arc";
  sol.solved = false;
  sol.stats = {{"failure", {"time_limit"}}, {"planning_time_s", 0.02}};
  const std::string svg = solutionSvg(s, sol);
  CHECK(wellFormed(svg));
  CHECK(svg != scenarioSvg(s));
  CHECK(countOf(svg, "<tspan font-weight=\"bold\" fill=\"#c00\">not solved: time_limit</tspan>") == 1);
  const auto texts = svgTexts(svg);
  CHECK(std::find(texts.begin(), texts.end(),
                  "method arc \u00b7 not solved: time_limit \u00b7 no paths: robots at their starts \u00b7 planned in "
                  "0.02 s") != texts.end());
  // The facts lie between the title and the workspace.
  const double facts_y = svgAttribute(svg, svg.find("<text class=\"facts\""), "y");
  CHECK(facts_y > svgAttribute(svg, svg.find("<text", svg.find("class=\"panel\"")), "y"));
  CHECK(facts_y < svgAttribute(svg, svg.find("<rect class=\"workspace\""), "y"));
}

TEST_CASE("a plan picture says what the solution holds, and a step of how many") {
  gen::MobileSettings ms;
  ms.robots = 4;
  const Scenario s = gen::generateMobile(ms);
  Solution sol = straightSolution(s, 40);
  sol.stats = {{"planning_time_s", 1.25}};
  const auto texts = svgTexts(solutionSvg(s, sol));
  CHECK(std::find(texts.begin(), texts.end(),
                  "method test \u00b7 solved \u00b7 makespan 40 steps \u00b7 sum of costs 160 \u00b7 planned in 1.25 s") !=
        texts.end());
  // A compacted plan says what it was before; one whose compaction was
  // undone says why.
  sol.stats["compact"] = {{"makespan_before", 52}, {"sum_of_costs_before", 190}};
  const auto compacted = svgTexts(solutionSvg(s, sol));
  CHECK(std::any_of(compacted.begin(), compacted.end(), [](const std::string& t) {
    return t.find("before --compact: makespan 52, sum of costs 190") != std::string::npos;
  }));
  sol.stats["compact"]["rejected"] = "robots 0 and 1 collide at t = 3";
  const auto undone = svgTexts(solutionSvg(s, sol));
  CHECK(std::any_of(undone.begin(), undone.end(), [](const std::string& t) {
    return t.find("compaction undone: robots 0 and 1 collide at t = 3") != std::string::npos;
  }));
  sol.stats["compact"]["rejected"] = 7;  // a hand-made file's: said as it is, not thrown on
  const auto odd = svgTexts(solutionSvg(s, sol));
  CHECK(std::any_of(odd.begin(), odd.end(), [](const std::string& t) {
    return t.find("compaction undone: 7") != std::string::npos;
  }));
  sol.stats.erase("compact");
  SvgOptions o;
  o.steps = {10, 40};
  const auto timed = svgTexts(solutionSvg(s, sol, o));
  CHECK(std::count(timed.begin(), timed.end(), s.name + " \u00b7 t = 10 of 40") == 1);
  CHECK(std::count(timed.begin(), timed.end(), s.name + " \u00b7 t = 40 of 40") == 1);
  CHECK(scenarioSvg(s).find("class=\"facts\"") == std::string::npos);  // a scenario has no plan to describe
}

TEST_CASE("the key names every mark and lies below the drawing, whatever the robots near the edges") {
  // Two discs whose starts and goals each touch one edge of the workspace.
  const Scenario s = twoDiscs({0.5, 5}, {9.5, 5}, {5, 9.5}, {5, 0.5});
  for (double width : {800.0, 150.0}) {
    SvgOptions o;
    o.panel_width_px = width;
    o.steps = {3};
    const std::string svg = solutionSvg(s, straightSolution(s, 10), o);
    CHECK(wellFormed(svg));
    const auto ws = svg.find("<rect class=\"workspace\"");
    const double bottom = svgAttribute(svg, ws, "y") + svgAttribute(svg, ws, "height");
    const auto key = svg.find("<g class=\"key\"");
    REQUIRE(key != std::string::npos);
    const auto key_end = svg.find("</g>", key);
    const auto texts = svgTexts(svg, key, key_end);
    CHECK(texts == std::vector<std::string>{"robot at t", "start", "goal", "path travelled", "path to go", "heading",
                                            "2 units"});
    const double height = svgAttribute(svg, svg.find("<svg"), "height");
    for (auto at = svg.find(" y=\"", key); at < key_end; at = svg.find(" y=\"", at + 1)) {
      const double y = std::stod(svg.substr(at + 4));
      CHECK(y > bottom);
      CHECK(y < height);
    }
    // Each key text begins inside the picture.
    const double total = svgAttribute(svg, svg.find("<svg"), "width");
    for (auto at = svg.find("<text", key); at < key_end; at = svg.find("<text", at + 1))
      CHECK(svgAttribute(svg, at, "x") < total);
  }
  // Arms: the path is the tip's; joints instead of a heading.
  gen::ArmSettings as;
  as.robots = 2;
  const Scenario arms = gen::generateArms(as);
  const std::string svg = solutionSvg(arms, straightSolution(arms, 5));
  const auto key = svg.find("<g class=\"key\"");
  CHECK(svgTexts(svg, key, svg.find("</g>", key)) ==
        std::vector<std::string>{"start", "goal", "path of the tip", "base and joints", "1 unit"});
}

TEST_CASE("decimation drops points on straight runs and waits, and keeps corners") {
  std::vector<geo::Vec2> line, corner;
  for (int k = 0; k <= 1000; ++k) line.push_back({0.01 * k, 0.02 * k});
  line.push_back(line.back());  // a wait
  CHECK(decimatePolyline(line, 0.01).size() == 2);
  for (int k = 0; k <= 100; ++k) corner.push_back({0.1 * k, 0.0});
  for (int k = 1; k <= 100; ++k) corner.push_back({10.0, 0.1 * k});
  const auto kept = decimatePolyline(corner, 0.01);
  REQUIRE(kept.size() == 3);
  CHECK(kept[1] == geo::Vec2{10.0, 0.0});
}

TEST_CASE("no point dropped by decimation lies farther than the tolerance from the kept polyline") {
  gen::Random rng(12);
  std::vector<geo::Vec2> walk{{0, 0}};
  double heading = 0;
  for (int k = 0; k < 3000; ++k) {
    heading += rng.uniform(-0.3, 0.3);
    walk.push_back(walk.back() + geo::Vec2{std::cos(heading), std::sin(heading)});
  }
  const double tol = 0.5;
  const auto kept = decimatePolyline(walk, tol);
  CHECK(kept.size() < walk.size() / 2);
  double worst = 0;
  for (const auto& p : walk) {
    double best = 1e300;
    for (std::size_t k = 0; k + 1 < kept.size(); ++k) {
      const geo::Vec2 d = kept[k + 1] - kept[k];
      const double t = std::clamp(geo::dot(p - kept[k], d) / std::max(geo::dot(d, d), 1e-300), 0.0, 1.0);
      best = std::min(best, geo::norm(p - (kept[k] + d * t)));
    }
    worst = std::max(worst, best);
  }
  CHECK(worst <= tol + 1e-9);
}

TEST_CASE("an SVG of 128 robots over 5000 steps stays small") {
  gen::MobileSettings ms;
  ms.robots = 128;
  ms.obstacles = 12;
  const Scenario s = gen::generateMobile(ms);
  // Each path: straight to the workspace centre line, then to the goal.
  Solution sol;
  sol.scenario = s.name;
  sol.solved = true;
  for (const auto& r : s.robots) {
    Path p(3);
    const double mid[3] = {10.0, r.start[1], 0.0};
    for (int t = 0; t < 2500; ++t) {
      const double f = t / 2500.0;
      const double q[3] = {r.start[0] + f * (mid[0] - r.start[0]), r.start[1], r.start[2]};
      p.push(q);
    }
    for (int t = 0; t <= 2500; ++t) {
      const double f = t / 2500.0;
      const double q[3] = {mid[0] + f * (r.goal[0] - mid[0]), mid[1] + f * (r.goal[1] - mid[1]), r.goal[2]};
      p.push(q);
    }
    sol.paths.push_back(std::move(p));
  }
  SvgOptions o;
  o.steps = {2500};
  const std::string svg = solutionSvg(s, sol, o);
  CHECK(wellFormed(svg));
  CHECK(svg.size() < 200'000);
}

TEST_CASE("writing a .png without rsvg-convert on PATH names the package to install") {
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  setenv("PATH", "/nonexistent-earc-test", 1);
  std::string message;
  try {
    writeImage(std::string(EARC_BINARY_DIR) + "/render-test.png", "<svg/>");
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  setenv("PATH", saved.c_str(), 1);
  CHECK(message.find("librsvg2-bin") != std::string::npos);
}
