// Helpers shared by the SVG tests (test_render_svg*.cpp): counting and
// parsing the picture, and small scenarios with straight solutions.
#pragma once

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


namespace earc::svg_test {

inline std::size_t countOf(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size())) ++n;
  return n;
}

// Well-formed for our purposes: every tag closes in order, attribute values
// are quoted, and text holds no bare '<' or '&'.
inline bool wellFormed(const std::string& xml) {
  std::vector<std::string> open;
  std::size_t i = 0;
  while (i < xml.size()) {
    if (xml[i] == '&') {
      const auto semi = xml.find(';', i);
      if (semi == std::string::npos || semi - i > 6) return false;
      i = semi + 1;
      continue;
    }
    if (xml[i] != '<') {
      ++i;
      continue;
    }
    const auto end = xml.find('>', i);
    if (end == std::string::npos) return false;
    std::string tag = xml.substr(i + 1, end - i - 1);
    i = end + 1;
    if (countOf(tag, "\"") % 2 != 0 || tag.find('<') != std::string::npos) return false;
    if (tag.starts_with("?") || tag.starts_with("!")) continue;
    if (tag.starts_with("/")) {
      if (open.empty() || open.back() != tag.substr(1)) return false;
      open.pop_back();
    } else if (!tag.ends_with("/")) {
      open.push_back(tag.substr(0, tag.find(' ')));
    }
  }
  return open.empty();
}

inline Solution straightSolution(const Scenario& s, std::size_t steps) {
  Solution sol;
  sol.scenario = s.name;
  sol.method = "test";
  sol.solved = true;
  for (const auto& r : s.robots) {
    Path p(r.dim());
    std::vector<double> q(r.start.size());
    for (std::size_t t = 0; t <= steps; ++t) {
      const double f = static_cast<double>(t) / static_cast<double>(steps);
      for (std::size_t k = 0; k < q.size(); ++k) q[k] = r.start[k] + f * (r.goal[k] - r.start[k]);
      p.push(q.data());
    }
    sol.paths.push_back(std::move(p));
  }
  return sol;
}

inline Scenario oneDisc(geo::Vec2 start, geo::Vec2 goal) {
  Scenario s;
  s.name = "one";
  s.workspace = {{0, 0}, {10, 10}};
  RobotSpec r = gen::mobileRobot(0, {MobileShape::Disc, {}, 0.5});
  r.start = {start.x, start.y, 0};
  r.goal = {goal.x, goal.y, 0};
  s.robots.push_back(r);
  return s;
}

// oneDisc's m0 and a second disc, m1.
inline Scenario twoDiscs(geo::Vec2 start0, geo::Vec2 goal0, geo::Vec2 start1, geo::Vec2 goal1) {
  Scenario s = oneDisc(start0, goal0);
  RobotSpec second = s.robots[0];
  second.name = "m1";
  second.start = {start1.x, start1.y, 0};
  second.goal = {goal1.x, goal1.y, 0};
  s.robots.push_back(second);
  return s;
}

// The numeric value of attribute `name` in the tag that starts at `at`.
inline double svgAttribute(const std::string& svg, std::size_t at, const std::string& name) {
  const auto end = svg.find('>', at);
  const auto a = svg.find(" " + name + "=\"", at);
  REQUIRE(a < end);
  return std::stod(svg.substr(a + name.size() + 3));
}

// The text of every <text> element (tspans flattened) inside the element
// that starts at `from` and ends at `to`.
inline std::vector<std::string> svgTexts(const std::string& svg, std::size_t from = 0, std::size_t to = std::string::npos) {
  std::vector<std::string> texts;
  for (auto at = svg.find("<text", from); at < to; at = svg.find("<text", at + 1)) {
    const auto open_end = svg.find('>', at) + 1;
    std::string inner = svg.substr(open_end, svg.find("</text>", open_end) - open_end), flat;
    bool in_tag = false;
    for (char c : inner) {
      if (c == '<') in_tag = true;
      if (!in_tag) flat += c;
      if (c == '>') in_tag = false;
    }
    texts.push_back(flat);
  }
  return texts;
}

}  // namespace earc::svg_test
