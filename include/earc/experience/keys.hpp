// Canonical form of a subproblem, so that one stored experience serves
// every subproblem that is the same up to what E-ARC may change: where it
// happens (mobile robots: a translation), the order in which its robots are
// listed, and (manipulators) which of two arms plays which role.
//
// Mobile robots (translation-invariant; paper: "translating the database
// solutions to the geometric point where the conflict occurred"):
//   offset = centroid of all starts and goals (x, y);
//   canonical order = robots sorted by start relative to the offset (x, then
//   y, compared at kOrderQuantum so rounding noise cannot flip an order);
//   key = per canonical robot (sx-cx, sy-cy, gx-cx, gy-cy): 4 per robot.
//   Headings are not in the key: they add dimensions that separate little
//   (the planner connects and validates every candidate anyway).
//   Canonical paths have x and y minus the offset.
//
// Manipulators (two arms; paper: "only solutions with the same relative
// base transformation are considered ... if it matches negatively, the
// roles of the robots are inverted"):
//   T_ab = inverse(base_a) * base_b = (dx, dy, dtheta) in a's frame,
//   rounded to kBaseClassQuantum into a class string. The canonical
//   orientation is the one whose class string (T_ab or T_ba) is smaller;
//   sign = +1 when the given order is canonical, -1 when the roles swap
//   (order = {1, 0}). When both strings are equal (a symmetric pair, e.g.
//   two arms facing each other) either assignment is valid; the canonical
//   one is then the one with the smaller key, and `symmetric` is set so
//   retrieval can search both.
//   key = per canonical robot, the first kArmKeyJoints joints of start and
//   goal (see keyDimension). Joints are base-relative: no translation.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "earc/experience/experience.hpp"
#include "earc/geometry/shapes.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"

namespace earc::exp {

// What canonicalization needs to know about one robot.
struct RobotTraits {
  RobotKind kind = RobotKind::Mobile;
  int dim = 3;
  std::string signature;  // RobotModel::geometrySignature()
  geo::Vec2 base;         // manipulators
  double base_angle = 0.0;
};
RobotTraits traitsOf(const RobotModel& robot);

// Base transforms closer than this (units and radians) are one class.
inline constexpr double kBaseClassQuantum = 1e-3;
// Mobile starts are ordered after rounding to this (units).
inline constexpr double kOrderQuantum = 1e-6;
// Joints of each arm that enter the key (from the base outwards).
inline constexpr int kArmKeyJoints = 3;

// Key dimension of a class: 4 per mobile robot; 2 x min(dim, kArmKeyJoints)
// per arm.
int keyDimension(RobotKind kind, int robot_count, int robot_dim);

// The key of canonical paths: the definition the stored key must agree with.
std::vector<double> keyOfCanonicalPaths(RobotKind kind, const std::vector<Path>& paths);

// "dx=4.000,dy=0.000,dth=3.142": T rounded to kBaseClassQuantum, dtheta
// wrapped to (-pi, pi], no negative zero.
std::string baseClassString(double dx, double dy, double dtheta);

// Relative transform inverse(base_a) * base_b as (dx, dy, dtheta).
struct RelativeTransform {
  double dx = 0, dy = 0, dtheta = 0;
};
RelativeTransform relativeBaseTransform(const RobotTraits& a, const RobotTraits& b);

// A subproblem's canonical form and the map back.
struct Canonical {
  ExperienceClass cls;
  std::vector<double> key;
  std::vector<int> order;  // order[c] = subproblem index of the robot at canonical position c
  geo::Vec2 offset;        // mobile: subtracted from x and y
  int sign = 1;            // manipulators: -1 when the roles swap
  bool symmetric = false;  // manipulators: both role assignments are the same class

  // Subproblem paths (subproblem order, world frame) -> canonical.
  std::vector<Path> toCanonical(const std::vector<Path>& paths) const;
  // Canonical paths (e.g. retrieved) -> subproblem order and frame.
  std::vector<Path> fromCanonical(const std::vector<Path>& paths) const;
};

// The stored form of a solved subproblem's paths (subproblem order, world
// frame): canonical paths, key and cost; source and bookkeeping at their
// defaults.
Experience canonicalExperience(const Canonical& form, const std::vector<Path>& subproblem_paths);

// True when the robots form a class the store can hold: one or more mobile
// robots, or exactly two manipulators with equal dimensions.
bool hasExperienceClass(std::span<const RobotTraits> robots);

// Throws std::invalid_argument when !hasExperienceClass or when starts and
// goals do not match the robots.
Canonical canonicalize(std::span<const RobotTraits> robots, const std::vector<std::vector<double>>& starts,
                       const std::vector<std::vector<double>>& goals);
Canonical canonicalize(const std::vector<const RobotModel*>& robots, const std::vector<std::vector<double>>& starts,
                       const std::vector<std::vector<double>>& goals);

// Manipulators, symmetric pairs only: the canonical form with the other
// role assignment (same class, other key and order, sign negated).
Canonical swappedRoles(const Canonical& c, const std::vector<std::vector<double>>& starts,
                       const std::vector<std::vector<double>>& goals);

}  // namespace earc::exp
