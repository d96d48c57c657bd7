// The scenario model: the in-memory form of an earc.scenario.v1 document.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "earc/geometry/shapes.hpp"

namespace earc {

// Largest change of one robot's configuration between consecutive steps.
struct Resolution {
  double translation = 0.05;
  double rotation = 0.05;
  double joint = 0.05;
};

struct Obstacle {
  enum class Type { Box, Circle };
  Type type = Type::Box;
  geo::Vec2 center;
  geo::Vec2 size;      // box: full side lengths
  double angle = 0.0;  // box
  double radius = 0.0; // circle
  geo::Body body() const;

  // Shorthands for code that builds scenes (tests, generators, benchmarks).
  static Obstacle makeBox(geo::Vec2 center, geo::Vec2 size, double angle = 0.0) {
    Obstacle o;
    o.center = center;
    o.size = size;
    o.angle = angle;
    return o;
  }
  static Obstacle makeCircle(geo::Vec2 center, double radius) {
    Obstacle o;
    o.type = Type::Circle;
    o.center = center;
    o.radius = radius;
    return o;
  }
};

enum class RobotKind { Mobile, Manipulator };
enum class MobileShape { Disc, Box };

struct RobotSpec {
  std::string name;
  RobotKind kind = RobotKind::Mobile;
  // Mobile robots: configuration [x, y, theta].
  MobileShape shape = MobileShape::Disc;
  double radius = 0.0;      // disc
  geo::Vec2 box_size;       // box: full length along the heading, full width
  // Manipulators: configuration q, one joint angle per link.
  geo::Vec2 base_position;
  double base_angle = 0.0;
  std::vector<double> links;
  double link_radius = 0.0;
  std::vector<std::pair<double, double>> joint_limits;  // one per link
  std::vector<double> start;
  std::vector<double> goal;

  int dim() const { return kind == RobotKind::Mobile ? 3 : static_cast<int>(links.size()); }

  // Shorthands for code that builds scenes; start and goal are left empty
  // and joint limits default ([-pi, pi] each).
  static RobotSpec mobileDisc(std::string name, double radius) {
    RobotSpec s;
    s.name = std::move(name);
    s.radius = radius;
    return s;
  }
  static RobotSpec mobileBox(std::string name, geo::Vec2 size) {
    RobotSpec s;
    s.name = std::move(name);
    s.shape = MobileShape::Box;
    s.box_size = size;
    return s;
  }
  static RobotSpec arm(std::string name, geo::Vec2 base, double base_angle, std::vector<double> links,
                       double link_radius) {
    RobotSpec s;
    s.name = std::move(name);
    s.kind = RobotKind::Manipulator;
    s.base_position = base;
    s.base_angle = base_angle;
    s.links = std::move(links);
    s.link_radius = link_radius;
    return s;
  }
};

struct Scenario {
  std::string name;
  geo::Aabb workspace;
  Resolution resolution;
  std::vector<Obstacle> obstacles;
  std::vector<RobotSpec> robots;
};

}  // namespace earc
