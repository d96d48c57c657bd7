// Planar geometry: exact signed distances between convex bodies.
//
// Every body in earc (obstacle, mobile footprint, manipulator link) is a
// convex "core" (a point, a segment or an oriented rectangle) swept by a
// radius: a disc is a point plus r, a capsule a segment plus r, a box a
// rectangle plus 0. This is the contract's geometry (shared/spec/formats.md),
// and two bodies touch when they overlap by more than kContactTolerance.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace earc::geo {

// Contract tolerance: overlap, endpoints, resolution and workspace slack.
inline constexpr double kContactTolerance = 1e-6;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  Vec2 operator*(double s) const { return {x * s, y * s}; }
  bool operator==(const Vec2&) const = default;
};

inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// std::hypot's value, with axis-aligned vectors (a grid robot's steps and
// waits) exactly |x| or |y| without the library call, as C defines hypot.
inline double norm(Vec2 a) {
  if (a.y == 0.0) return std::abs(a.x);
  if (a.x == 0.0) return std::abs(a.y);
  return std::hypot(a.x, a.y);
}
inline Vec2 perp(Vec2 a) { return {-a.y, a.x}; }

// Axis-aligned box; empty when lo > hi.
struct Aabb {
  Vec2 lo{1e300, 1e300};
  Vec2 hi{-1e300, -1e300};
  bool overlaps(const Aabb& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y;
  }
  void expand(const Aabb& o) {
    lo = {std::min(lo.x, o.lo.x), std::min(lo.y, o.lo.y)};
    hi = {std::max(hi.x, o.hi.x), std::max(hi.y, o.hi.y)};
  }
  Aabb inflated(double m) const { return {{lo.x - m, lo.y - m}, {hi.x + m, hi.y + m}}; }
  bool contains(const Aabb& o) const { return lo.x <= o.lo.x && lo.y <= o.lo.y && o.hi.x <= hi.x && o.hi.y <= hi.y; }
};

enum class CoreKind { Point, Segment, Rect };

// A convex body. Point: p0 is the centre. Segment: p0 and p1 are the ends.
// Rect: p0 is the centre, axis the unit vector of its first side, half the
// half side lengths (along axis, across). radius sweeps the core.
struct Body {
  CoreKind kind = CoreKind::Point;
  Vec2 p0;
  Vec2 p1;
  Vec2 axis{1.0, 0.0};
  Vec2 half;
  double radius = 0.0;

  static Body disc(Vec2 c, double r) { return {CoreKind::Point, c, c, {1, 0}, {}, r}; }
  static Body capsule(Vec2 a, Vec2 b, double r) { return {CoreKind::Segment, a, b, {1, 0}, {}, r}; }
  static Body box(Vec2 c, Vec2 half_size, double angle) {
    return {CoreKind::Rect, c, c, {std::cos(angle), std::sin(angle)}, half_size, 0.0};
  }
};

// Signed distance between two bodies: the Euclidean gap when they are
// apart, minus the penetration depth (exact, by separating axes) when they
// overlap. Symmetric in its arguments.
double signedDistance(const Body& a, const Body& b);

// The contract's contact rule: overlap by more than kContactTolerance.
// The same as signedDistance(a, b) < -kContactTolerance, faster for
// rectangles that are clearly apart.
bool touches(const Body& a, const Body& b);

// Tight axis-aligned bounds of a body.
Aabb bounds(const Body& b);

// How far a body sticks out of an axis-aligned box (<= 0 when inside).
double excessOutside(const Body& b, const Aabb& box);
// How far an axis-aligned box sticks out of another.
double excessOutside(const Aabb& inner, const Aabb& box);

// Angle arithmetic: headings are compared and interpolated on the circle.
inline double wrapAngle(double a) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  double r = std::fmod(a + std::numbers::pi, two_pi);
  if (r < 0) r += two_pi;
  return r - std::numbers::pi;  // [-pi, pi)
}
inline double angleDiff(double from, double to) { return wrapAngle(to - from); }

}  // namespace earc::geo
