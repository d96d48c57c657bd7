// SVG pictures: how robots, names, headings, paths and the scale bar are
// drawn.
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

namespace {

// CIELAB of "#rrggbb" (D65).
std::array<double, 3> labOfHex(const std::string& hex) {
  double c[3];
  for (int k = 0; k < 3; ++k) {
    const double v = std::stoi(hex.substr(1 + 2 * k, 2), nullptr, 16) / 255.0;
    c[k] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  }
  const double xyz[3] = {(0.4124 * c[0] + 0.3576 * c[1] + 0.1805 * c[2]) / 0.95047,
                         0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2],
                         (0.0193 * c[0] + 0.1192 * c[1] + 0.9505 * c[2]) / 1.08883};
  double f[3];
  for (int k = 0; k < 3; ++k) f[k] = xyz[k] > 0.008856 ? std::cbrt(xyz[k]) : 7.787 * xyz[k] + 16.0 / 116.0;
  return {116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])};
}

// Each robot group's colour, in order.
std::vector<std::string> robotFills(const std::string& svg) {
  std::vector<std::string> fills;
  for (auto at = svg.find("<g class=\"robot\""); at != std::string::npos; at = svg.find("<g class=\"robot\"", at + 1)) {
    const auto f = svg.find(" fill=\"", at) + 7;
    fills.push_back(svg.substr(f, 7));
  }
  return fills;
}

}  // namespace

TEST_CASE("any two of 20 robots have colours far apart, and neighbours do beyond") {
  gen::MobileSettings ms;
  ms.robots = 64;
  const auto fills = robotFills(scenarioSvg(gen::generateMobile(ms)));
  REQUIRE(fills.size() == 64);
  auto distance = [](const std::string& a, const std::string& b) {
    const auto p = labOfHex(a), q = labOfHex(b);
    return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
  };
  double closest = 1e9;
  for (std::size_t i = 0; i < 20; ++i)
    for (std::size_t j = i + 1; j < 20; ++j) closest = std::min(closest, distance(fills[i], fills[j]));
  CHECK(closest > 30);  // robots 6 and 14 were both green, 7.5 apart
  for (std::size_t i = 0; i + 1 < fills.size(); ++i) CHECK(distance(fills[i], fills[i + 1]) > 40);
  // The viewer colours robots alike: its list holds the same colours in order.
  for (const auto& a : earc::view::viewerAssets()) {
    if (std::string(a.name) != "viewer.js") continue;
    const auto list = a.text.find("const PALETTE = [");
    REQUIRE(list != std::string::npos);
    std::size_t at = list;
    for (std::size_t i = 0; i < 20; ++i) {
      at = a.text.find("'" + fills[i] + "'", at);
      CHECK(at < a.text.find("];", list));
    }
  }
}

TEST_CASE("names label the robot and, small, its goal, on a white halo, inside the picture") {
  // A long name at the right edge: it once ran off the picture.
  Scenario s = twoDiscs({9.4, 5}, {9.4, 9.4}, {0.6, 0.6}, {5, 5});
  s.robots[0].name = "forklift-m3-east-wing-loading-dock";
  const std::string svg = scenarioSvg(s);
  CHECK(wellFormed(svg));
  const double width = svgAttribute(svg, svg.find("<svg"), "width");
  std::size_t labels = 0;
  for (auto at = svg.find("<text class=\"label\""); at != std::string::npos;
       at = svg.find("<text class=\"label\"", at + 1), ++labels) {
    const auto end = svg.find("</text>", at);
    CHECK(svg.substr(at, end - at).find("stroke=\"#fff\"") != std::string::npos);
    CHECK(svg.substr(at, end - at).find("paint-order=\"stroke\"") != std::string::npos);
    const std::string text = svg.substr(svg.find('>', at) + 1, end - svg.find('>', at) - 1);
    const double font = svg.substr(at, end - at).find("font-size=\"8.5\"") != std::string::npos ? 8.5 : 11.0;
    CHECK(svgAttribute(svg, at, "x") >= 0);
    CHECK(svgAttribute(svg, at, "x") + 0.6 * font * static_cast<double>(text.size()) <= width);
  }
  CHECK(labels == 4);
  CHECK(countOf(svg, ">forklift-m3-east-wing-loading-dock</text>") == 2);
  CHECK(countOf(svg, "font-size=\"8.5\" fill=\"#333\" stroke=\"#fff\" stroke-width=\"2.5\" stroke-linejoin=\"round\" "
                     "paint-order=\"stroke\">m1</text>") == 1);  // m1's goal
}

TEST_CASE("text grows with the panel's width, within bounds that keep it readable") {
  // Fixed sizes made the names of a 4000-pixel picture specks seen whole.
  const Scenario s = oneDisc({2, 2}, {8, 8});
  auto fontOf = [](const std::string& svg, const std::string& tag) {
    return svgAttribute(svg, svg.find(tag), "font-size");
  };
  auto sizes = [&](double width) {
    SvgOptions o;
    o.panel_width_px = width;
    o.steps = {5};
    const std::string svg = solutionSvg(s, straightSolution(s, 10), o);
    auto goal_label = svg.find("<text class=\"label\"");
    while (svg.find(" font-size=", goal_label) > svg.find('>', goal_label))
      goal_label = svg.find("<text class=\"label\"", goal_label + 1);
    // The picture's size is the names' and the key's; the title, the
    // facts and a goal's name have their own.
    return std::array<double, 4>{fontOf(svg, "<svg"), fontOf(svg, "<text x="), fontOf(svg, "<text class=\"facts\""),
                                 svgAttribute(svg, goal_label, "font-size")};
  };
  const auto small = sizes(400), usual = sizes(800), large = sizes(3200), huge = sizes(20000);
  CHECK(usual == std::array<double, 4>{11, 14, 12, 8.5});
  for (std::size_t k = 0; k < usual.size(); ++k) {
    CHECK(large[k] == doctest::Approx(4 * usual[k]));
    CHECK(huge[k] == doctest::Approx(5 * usual[k]));  // at most five times
    CHECK(small[k] < usual[k]);
    CHECK(small[k] >= 8);
  }
}

TEST_CASE("robots too small to see are drawn at a least size, and the key says so") {
  // den520d is 256 cells wide: at 800 pixels its 0.6 x 0.4 boxes were 2
  // pixels long and vanished.
  Scenario s;
  s.name = "large";
  s.workspace = {{0, 0}, {256, 256}};
  RobotSpec box = gen::mobileRobot(0, {});
  box.start = {100, 100, 0};
  box.goal = {150, 150, 0};
  s.robots.push_back(box);
  const std::string svg = scenarioSvg(s);
  // The box keeps its shape, its diagonal (the bounding circle) 9 pixels.
  const auto at = svg.find("<polygon points=\"", svg.find("class=\"robot\""));
  REQUIRE(at != std::string::npos);
  double x[4], y[4];
  REQUIRE(std::sscanf(svg.c_str() + at, "<polygon points=\"%lf,%lf %lf,%lf %lf,%lf %lf,%lf", &x[0], &y[0], &x[1], &y[1],
                      &x[2], &y[2], &x[3], &y[3]) == 8);
  CHECK(std::hypot(x[2] - x[0], y[2] - y[0]) == doctest::Approx(9).epsilon(0.01));
  CHECK(std::hypot(x[1] - x[0], y[1] - y[0]) / std::hypot(x[3] - x[0], y[3] - y[0]) == doctest::Approx(0.6 / 0.4).epsilon(0.01));
  const auto key = svg.find("<g class=\"key\"");
  auto keyTexts = [](const std::string& picture) {
    const auto k = picture.find("<g class=\"key\"");
    return svgTexts(picture, k, picture.find("</g>", k));
  };
  REQUIRE(key != std::string::npos);
  CHECK(keyTexts(svg) == std::vector<std::string>{"start", "goal", "heading", "robots under 9 px drawn 9 px across",
                                                  "50 units"});
  // On a small workspace the same box is drawn true to scale, with no such key.
  s.workspace = {{0, 0}, {20, 20}};
  s.robots[0].start = {10, 10, 0};
  s.robots[0].goal = {12, 12, 0};
  const std::string true_size = scenarioSvg(s);
  CHECK(true_size.find("drawn") == std::string::npos);
  // Arms far apart: their links are drawn 2 pixels thick, not 0.2.
  gen::ArmSettings as;
  as.robots = 2;
  Scenario arms = gen::generateArms(as);
  arms.workspace.hi = arms.workspace.lo + geo::Vec2{400, 400};
  const std::string wide = scenarioSvg(arms);
  CHECK(countOf(wide, "<path d=\"M") == 2 * 2 * 5);
  CHECK(countOf(wide, " A1,1 0 0 0 ") == 2 * 2 * 2 * 5);  // each capsule's two half circles
  CHECK(keyTexts(wide)[keyTexts(wide).size() - 2] == "links under 2 px drawn 2 px wide");
  CHECK(scenarioSvg(gen::generateArms(as)).find("drawn") == std::string::npos);
}

TEST_CASE("a heading is an arrowhead in the body's front, clear of the centre where the path ends") {
  // A line from the centre to the front, at the goal, read as the path's
  // last bend.
  Scenario s = oneDisc({2, 2}, {8, 8});
  s.robots[0].goal[2] = std::numbers::pi / 2;  // facing up
  const std::string svg = solutionSvg(s, straightSolution(s, 10));
  const double scale = (800.0 - 2 * 12) / 10, radius = 0.5 * scale;
  std::vector<std::array<double, 6>> arrows;
  for (auto at = svg.find("<polygon class=\"heading\""); at != std::string::npos;
       at = svg.find("<polygon class=\"heading\"", at + 1)) {
    std::array<double, 6> p{};
    REQUIRE(std::sscanf(svg.c_str() + svg.find("points=\"", at), "points=\"%lf,%lf %lf,%lf %lf,%lf", &p[0], &p[1], &p[2],
                        &p[3], &p[4], &p[5]) == 6);
    arrows.push_back(p);
  }
  REQUIRE(arrows.size() == 2);  // the goal's, then the start's
  const auto ws = svg.find("<rect class=\"workspace\"");
  const double left = svgAttribute(svg, ws, "x"), top = svgAttribute(svg, ws, "y");
  const geo::Vec2 goal{left + 8 * scale, top + 2 * scale};
  const auto& a = arrows[0];
  CHECK(a[0] == doctest::Approx(goal.x));  // the tip at the front edge, straight up
  CHECK(a[1] == doctest::Approx(goal.y - radius));
  for (int k = 0; k < 3; ++k) {
    const double d = std::hypot(a[2 * k] - goal.x, a[2 * k + 1] - goal.y);
    CHECK(d > 0.4 * radius);
    CHECK(d <= radius + 1e-6);
  }
  CHECK(svg.find("<line") > svg.find("<g class=\"key\""));  // no tick from the centre
}

TEST_CASE("at a step, the path travelled is solid and the path to go dashed and faded, meeting at the robot") {
  // Both were one line alike, so a panel did not show how far a robot had come.
  const Scenario s = oneDisc({1, 1}, {9, 1});
  SvgOptions o;
  o.steps = {0, 4, 10};
  const std::string svg = solutionSvg(s, straightSolution(s, 10), o);
  auto lines = [&](std::size_t panel, const std::string& cls) {
    std::vector<std::string> found;
    const auto from = svg.find("<g class=\"panel\"", panel), to = svg.find("</g>\n</g>", from);
    for (auto at = svg.find("<polyline class=\"" + cls + "\"", from); at < to;
         at = svg.find("<polyline class=\"" + cls + "\"", at + 1))
      found.push_back(svg.substr(at, svg.find("/>", at) - at));
    return found;
  };
  const auto p0 = svg.find("<g class=\"panel\""), p4 = svg.find("<g class=\"panel\"", p0 + 1),
             p10 = svg.find("<g class=\"panel\"", p4 + 1);
  auto points = [](const std::string& line) {
    const auto at = line.find("points=\"") + 8;
    return line.substr(at, line.find('"', at) - at);
  };
  // At 0 all is to go, at 10 all travelled.
  CHECK(lines(p0, "path").empty());
  REQUIRE(lines(p0, "path-ahead").size() == 1);
  REQUIRE(lines(p10, "path").size() == 1);
  CHECK(lines(p10, "path-ahead").empty());
  CHECK(points(lines(p0, "path-ahead")[0]) == points(lines(p10, "path")[0]));
  // At 4 the two meet where the robot is, 4/10 of the way from x = 1 to 9.
  REQUIRE(lines(p4, "path").size() == 1);
  REQUIRE(lines(p4, "path-ahead").size() == 1);
  const std::string done = points(lines(p4, "path")[0]), to_go = points(lines(p4, "path-ahead")[0]);
  const std::string meet = done.substr(done.rfind(' ') + 1);
  CHECK(to_go.substr(0, to_go.find(' ')) == meet);
  const double scale = (800.0 - 2 * 12) / 10;
  CHECK(std::stod(meet) == doctest::Approx(12 + (1 + 0.4 * 8) * scale));
  const auto circle = svg.find("<circle", svg.find("<circle", svg.find("<circle", p4) + 1) + 1);  // goal, start, now
  CHECK(svgAttribute(svg, circle, "cx") == doctest::Approx(std::stod(meet)));
  const std::string ahead = lines(p4, "path-ahead")[0];
  CHECK(ahead.find("stroke-dasharray=") != std::string::npos);
  CHECK(ahead.find("opacity=\"0.5\"") != std::string::npos);
  CHECK(lines(p4, "path")[0].find("stroke-dasharray=") == std::string::npos);
  CHECK(lines(p4, "path")[0].find("opacity") == std::string::npos);
  // Without a step the whole path is one solid line, as the key says.
  const std::string whole = solutionSvg(s, straightSolution(s, 10));
  CHECK(countOf(whole, "<polyline class=\"path\"") == 1);
  CHECK(countOf(whole, "path-ahead") == 0);
}

TEST_CASE("the key ends with a scale bar of a round length, at most a quarter of the workspace wide") {
  // Without one, a picture did not say how large anything was.
  auto bar = [](const Scenario& s, double width) {
    SvgOptions o;
    o.panel_width_px = width;
    const std::string svg = scenarioSvg(s, o);
    const auto key = svg.find("<g class=\"key\"");
    REQUIRE(key != std::string::npos);
    const auto at = svg.find("<path class=\"scale-bar\"", key);
    REQUIRE(at < svg.find("</g>", key));
    double x0 = 0, y0 = 0, x1 = 0;
    REQUIRE(std::sscanf(svg.c_str() + svg.find(" M", at + 20), " M%lf,%lf H%lf", &x0, &y0, &x1) == 3);
    const double scale = (width - 2 * 12) / (s.workspace.hi.x - s.workspace.lo.x);
    return std::make_pair(svgTexts(svg, key, svg.find("</g>", key)).back(), (x1 - x0) / scale);
  };
  auto barIs = [&](const Scenario& sc, double width, const std::string& text, double length) {
    const auto [shown, drawn] = bar(sc, width);
    CHECK(shown == text);
    CHECK(drawn == doctest::Approx(length).epsilon(1e-4));  // pixels have two decimals
  };
  Scenario s = oneDisc({2, 2}, {8, 8});  // 10 wide
  barIs(s, 800, "2 units", 2.0);
  barIs(s, 300, "2 units", 2.0);  // a length in the world, whatever the picture's width
  s.workspace = {{0, 0}, {256, 257}};  // den520d
  barIs(s, 800, "50 units", 50.0);
  s.workspace = {{-1, 0}, {3, 4}};
  s.robots.clear();  // an empty scenario has a scale too
  barIs(s, 800, "1 unit", 1.0);
  s.workspace = {{0, 0}, {1.5, 1}};
  barIs(s, 800, "0.2 units", 0.2);
}

TEST_CASE("an arm's name is beside its base, away from its links, and its goal's past the goal's tip") {
  // The name sat just above the base, where links pointing up ran through it.
  for (const double angle : {std::numbers::pi / 2, 0.0}) {  // links up, links right
    Scenario s;
    s.name = "arm";
    s.workspace = {{0, 0}, {10, 10}};
    RobotSpec arm = RobotSpec::arm("a0", {5, 5}, angle, {0.5, 0.5, 0.5, 0.5, 0.5}, 0.05);
    arm.start = {0, 0, 0, 0, 0};
    arm.goal = {0.1, 0, 0, 0, 0};
    s.robots.push_back(arm);
    const std::string svg = scenarioSvg(s);
    const double scale = (800.0 - 2 * 12) / 10, left = 12;
    const double top = svgAttribute(svg, svg.find("<rect class=\"workspace\""), "y");
    const geo::Vec2 base{left + 5 * scale, top + 5 * scale};
    const auto name = svg.find("<text class=\"label\"");
    REQUIRE(name != std::string::npos);
    const double x = svgAttribute(svg, name, "x"), y = svgAttribute(svg, name, "y");
    const double w = 0.6 * 11 * 2, h = 0.75 * 11;  // "a0": its box from the baseline up
    const double clear = 0.05 * scale;              // a link's radius
    if (angle > 0) {
      CHECK(y - h > base.y + clear);  // below the base, the links going up
      CHECK(x < base.x);
      CHECK(x + w > base.x);
    } else {
      CHECK(x + w < base.x - clear);  // left of the base, the links going right
      CHECK(y > base.y);
      CHECK(y - h < base.y);
    }
    // The goal's name: past the tip, 2.5 out along the goal's links.
    const auto goal = svg.find("<text class=\"label\"", name + 1);
    REQUIRE(goal != std::string::npos);
    const double gx = svgAttribute(svg, goal, "x"), gy = svgAttribute(svg, goal, "y");
    const geo::Vec2 tip = base + geo::Vec2{std::cos(angle + 0.1), -std::sin(angle + 0.1)} * (2.5 * scale);
    if (angle > 0)
      CHECK(gy < tip.y);
    else
      CHECK(gx > tip.x);
  }
}

TEST_CASE("names are drawn over every robot, after all the robots of their panel") {
  // In each robot's group, a later robot's body covered an earlier name.
  const Scenario s = twoDiscs({5, 5}, {9, 9}, {5, 5.4}, {1, 1});
  SvgOptions o;
  o.steps = {0, 10};
  const std::string svg = solutionSvg(s, straightSolution(s, 10), o);
  for (auto panel = svg.find("<g class=\"panel\""); panel != std::string::npos;
       panel = svg.find("<g class=\"panel\"", panel + 1)) {
    const auto next = svg.find("<g class=\"panel\"", panel + 1);
    const auto labels = svg.find("<g class=\"labels\"", panel);
    REQUIRE(labels < next);
    const auto last_robot = svg.rfind("<g class=\"robot\"", std::min(next, svg.size()));
    CHECK(svg.find("<text class=\"label\"", panel) > labels);
    CHECK(svg.find("</g>", last_robot) < labels);
    CHECK(countOf(svg.substr(labels, std::min(next, svg.size()) - labels), "<text class=\"label\"") == 4);
  }
  o.labels = false;
  CHECK(solutionSvg(s, straightSolution(s, 10), o).find("class=\"label") == std::string::npos);
}
