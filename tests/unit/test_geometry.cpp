// Signed distances, bounds and workspace excess of the contract's bodies,
// against values computed by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "earc/geometry/shapes.hpp"

using earc::geo::Aabb;
using earc::geo::Body;
using earc::geo::Vec2;
using earc::geo::signedDistance;

namespace {
const double kSqrt2 = std::sqrt(2.0);
const double kQuarterTurn = std::atan(1.0);  // pi / 4
constexpr double kEps = 1e-12;
}  // namespace

TEST_CASE("point-point signed distance is the centre gap minus both radii") {
  CHECK(signedDistance(Body::disc({0, 0}, 1.0), Body::disc({3, 0}, 0.5)) == doctest::Approx(1.5).epsilon(kEps));
  CHECK(signedDistance(Body::disc({0, 0}, 1.0), Body::disc({1.5, 0}, 1.0)) == doctest::Approx(-0.5).epsilon(kEps));
}

TEST_CASE("point-segment distance is perpendicular inside the segment and to the end beyond it") {
  CHECK(signedDistance(Body::disc({1, 2}, 0.5), Body::capsule({0, 0}, {2, 0}, 0.25)) ==
        doctest::Approx(1.25).epsilon(kEps));
  CHECK(signedDistance(Body::disc({5, 4}, 0.0), Body::capsule({0, 0}, {2, 0}, 0.0)) ==
        doctest::Approx(5.0).epsilon(kEps));
}

TEST_CASE("point-rect distance is to the nearest side, corner, or minus the depth inside") {
  const Body box = Body::box({0, 0}, {1, 1}, 0.0);
  CHECK(signedDistance(Body::disc({3, 0}, 0.5), box) == doctest::Approx(1.5).epsilon(kEps));
  CHECK(signedDistance(Body::disc({2, 2}, 0.0), box) == doctest::Approx(kSqrt2).epsilon(kEps));
  CHECK(signedDistance(Body::disc({0.5, 0}, 0.0), box) == doctest::Approx(-0.5).epsilon(kEps));
}

TEST_CASE("point-rect distance uses the rectangle's rotation") {
  // A unit-half square turned 45 degrees has a vertex at (sqrt 2, 0).
  const Body diamond = Body::box({0, 0}, {1, 1}, kQuarterTurn);
  CHECK(signedDistance(Body::disc({2, 0}, 0.0), diamond) == doctest::Approx(2.0 - kSqrt2).epsilon(kEps));
}

TEST_CASE("crossing segments have minus the smaller SAT overlap as signed distance") {
  // Normal of the first: (0,1), the second spans [-0.5, 2] -> overlap 0.5;
  // normal of the second: (-1,0), the first spans [-1, 1] -> overlap 1.
  const Body a = Body::capsule({-1, 0}, {1, 0}, 0.1);
  const Body b = Body::capsule({0, -0.5}, {0, 2}, 0.1);
  CHECK(signedDistance(a, b) == doctest::Approx(-0.7).epsilon(kEps));
}

TEST_CASE("parallel segments are the line gap apart") {
  const Body a = Body::capsule({0, 0}, {2, 0}, 0.3);
  const Body b = Body::capsule({1, 1}, {3, 1}, 0.3);
  CHECK(signedDistance(a, b) == doctest::Approx(0.4).epsilon(kEps));
}

TEST_CASE("overlapping collinear segments have core distance zero, as in the checker") {
  const Body a = Body::capsule({0, 0}, {2, 0}, 0.0);
  const Body b = Body::capsule({1, 0}, {3, 0}, 0.0);
  CHECK(signedDistance(a, b) == 0.0);
}

TEST_CASE("segments apart are the distance between their nearest ends") {
  const Body a = Body::capsule({0, 0}, {1, 0}, 0.0);
  const Body b = Body::capsule({2, 1}, {3, 5}, 0.0);
  CHECK(signedDistance(a, b) == doctest::Approx(kSqrt2).epsilon(kEps));
}

TEST_CASE("a segment through a rectangle is as deep as its SAT overlap") {
  // The segment y = 0.5 crosses the unit-half square; the y axis overlap
  // min(1.5, 0.5) = 0.5 is the smallest.
  const Body box = Body::box({0, 0}, {1, 1}, 0.0);
  CHECK(signedDistance(Body::capsule({-3, 0.5}, {3, 0.5}, 0.0), box) == doctest::Approx(-0.5).epsilon(kEps));
}

TEST_CASE("a segment beside a rectangle is at the corner distance") {
  const Body box = Body::box({0, 0}, {1, 1}, 0.0);
  CHECK(signedDistance(Body::capsule({2, 3}, {5, 3}, 0.0), box) == doctest::Approx(std::sqrt(5.0)).epsilon(kEps));
  CHECK(signedDistance(Body::capsule({-3, 3}, {3, 3}, 0.5), box) == doctest::Approx(1.5).epsilon(kEps));
}

TEST_CASE("a rotated rectangle's vertex sets its distance to an axis-aligned one") {
  // The diamond's left vertex sits at x = 2.5 - sqrt 2 = 1.0858, 0.0858 from the square.
  const Body square = Body::box({0, 0}, {1, 1}, 0.0);
  const Body diamond = Body::box({2.5, 0}, {1, 1}, kQuarterTurn);
  CHECK(signedDistance(square, diamond) == doctest::Approx(1.5 - kSqrt2).epsilon(kEps));
}

TEST_CASE("overlapping rotated rectangles have minus the smallest SAT overlap") {
  // Along x: 1 + sqrt 2 - 2; along the diamond's axes: sqrt 2 + 1 - sqrt 2 = 1.
  const Body square = Body::box({0, 0}, {1, 1}, 0.0);
  const Body diamond = Body::box({2, 0}, {1, 1}, kQuarterTurn);
  CHECK(signedDistance(square, diamond) == doctest::Approx(1.0 - kSqrt2).epsilon(kEps));
}

TEST_CASE("signed distance does not depend on the argument order") {
  const Body bodies[] = {Body::disc({0.3, 0.2}, 0.4), Body::capsule({-1, 0.5}, {1.2, -0.3}, 0.1),
                         Body::box({0.5, -0.2}, {0.6, 0.3}, 0.7)};
  for (const Body& a : bodies)
    for (const Body& b : bodies) CHECK(signedDistance(a, b) == doctest::Approx(signedDistance(b, a)).epsilon(1e-14));
}

TEST_CASE("flush contact is not a collision") {
  CHECK_FALSE(touches(Body::box({0, 0}, {1, 1}, 0.0), Body::box({2, 0}, {1, 1}, 0.0)));
  CHECK_FALSE(touches(Body::disc({0, 0}, 0.5), Body::disc({1, 0}, 0.5)));
}

TEST_CASE("an overlap of 5e-7 is within the contact tolerance") {
  CHECK_FALSE(touches(Body::box({0, 0}, {1, 1}, 0.0), Body::box({2 - 5e-7, 0}, {1, 1}, 0.0)));
  CHECK_FALSE(touches(Body::disc({0, 0}, 0.5), Body::disc({1 - 5e-7, 0}, 0.5)));
}

TEST_CASE("an overlap of 2e-6 is a collision") {
  CHECK(touches(Body::box({0, 0}, {1, 1}, 0.0), Body::box({2 - 2e-6, 0}, {1, 1}, 0.0)));
  CHECK(touches(Body::disc({0, 0}, 0.5), Body::disc({1 - 2e-6, 0}, 0.5)));
}

TEST_CASE("touches says what the signed distance says for rectangles, near, apart, with and without radii") {
  // touches skips the exact distance when a separating axis keeps two
  // rectangles further apart than their radii.
  auto rounded = [](Body b, double r) {
    b.radius = r;
    return b;
  };
  // Diagonal neighbours: apart on both axes by 0.1, corners sqrt(0.02) apart.
  const Body a = Body::box({0, 0}, {1, 1}, 0.0);
  const Body b = Body::box({2.1, 2.1}, {1, 1}, 0.0);
  CHECK_FALSE(touches(a, b));
  CHECK_FALSE(touches(rounded(a, 0.05), rounded(b, 0.02)));  // radii 0.07 < corner gap 0.141
  CHECK(touches(rounded(a, 0.1), rounded(b, 0.05)));          // radii 0.15 > corner gap, though > axis gap 0.1
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-2.0, 2.0), half(0.05, 1.0), angle(-3.2, 3.2), radius(0.0, 0.3);
  int touching = 0;
  for (int i = 0; i < 20000; ++i) {
    const Body x = rounded(Body::box({pos(rng), pos(rng)}, {half(rng), half(rng)}, angle(rng)), i % 2 ? radius(rng) : 0.0);
    const Body y = rounded(Body::box({pos(rng), pos(rng)}, {half(rng), half(rng)}, angle(rng)), i % 3 ? radius(rng) : 0.0);
    const bool expected = signedDistance(x, y) < -earc::geo::kContactTolerance;
    touching += expected;
    REQUIRE(touches(x, y) == expected);
    REQUIRE(touches(y, x) == (signedDistance(y, x) < -earc::geo::kContactTolerance));
  }
  CHECK(touching > 2000);  // both answers were exercised
  CHECK(touching < 18000);
}

TEST_CASE("bounds of a rotated box are its projected half extents around the centre") {
  const Aabb b = bounds(Body::box({3, 4}, {1, 0.5}, kQuarterTurn));
  const double e = 1.5 / kSqrt2;
  CHECK(b.lo.x == doctest::Approx(3 - e));
  CHECK(b.hi.x == doctest::Approx(3 + e));
  CHECK(b.lo.y == doctest::Approx(4 - e));
  CHECK(b.hi.y == doctest::Approx(4 + e));
}

TEST_CASE("bounds of a capsule are its ends' box grown by the radius") {
  const Aabb b = bounds(Body::capsule({1, 5}, {3, 2}, 0.5));
  CHECK(b.lo == Vec2{0.5, 1.5});
  CHECK(b.hi == Vec2{3.5, 5.5});
}

TEST_CASE("excess outside is how far the body's box sticks out, negative inside") {
  const Aabb ws{{0, 0}, {10, 10}};
  CHECK(excessOutside(Body::disc({0.5, 5}, 1.0), ws) == doctest::Approx(0.5));
  CHECK(excessOutside(Body::disc({9.8, 5}, 1.0), ws) == doctest::Approx(0.8));
  CHECK(excessOutside(Body::disc({5, 5}, 1.0), ws) == doctest::Approx(-4.0));
}

TEST_CASE("wrapAngle maps from -pi inclusive to pi exclusive and angleDiff takes the shortest arc") {
  const double pi = std::numbers::pi;
  CHECK(earc::geo::wrapAngle(pi) == doctest::Approx(-pi));
  CHECK(earc::geo::wrapAngle(3 * pi + 0.5) == doctest::Approx(-pi + 0.5));
  CHECK(earc::geo::angleDiff(3.1, -3.1) == doctest::Approx(2 * pi - 6.2));
}
