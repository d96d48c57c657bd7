// Mobile and arm robot models: time distances, interpolation, bodies,
// limits, signatures and sampling bounds.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "earc/scene/robot_model.hpp"
#include "earc/scene/robot_signature.hpp"
#include "support.hpp"

using earc::test::kPi;

using namespace earc;

namespace {

RobotSpec discSpec(double r) { return RobotSpec::mobileDisc("d", r); }
RobotSpec boxSpec(double length, double width) { return RobotSpec::mobileBox("b", {length, width}); }
RobotSpec armSpec(std::vector<double> links, double r, geo::Vec2 base = {0, 0}, double base_angle = 0.0) {
  return RobotSpec::arm("a", base, base_angle, std::move(links), r);
}

const Resolution kRes{0.05, 0.1, 0.05};

}  // namespace

TEST_CASE("mobile distance is the larger of translation and rotation in steps") {
  auto m = makeRobotModel(discSpec(0.3), kRes);
  const double a[] = {0, 0, 0};
  const double far[] = {0.3, 0.4, 0.1};   // 0.5 / 0.05 = 10 steps, rotation 1 step
  const double turn[] = {0.05, 0, 1.0};   // 1 step of translation, 10 of rotation
  CHECK(m->distance(a, far) == doctest::Approx(10.0));
  CHECK(m->distance(a, turn) == doctest::Approx(10.0));
}

TEST_CASE("mobile rotation distance takes the shortest arc across pi") {
  auto m = makeRobotModel(discSpec(0.3), kRes);
  const double a[] = {0, 0, 3.1};
  const double b[] = {0, 0, -3.1};
  CHECK(m->distance(a, b) == doctest::Approx((2 * kPi - 6.2) / 0.1));
}

TEST_CASE("stepsBetween is zero only for equal configurations, headings modulo 2 pi") {
  auto m = makeRobotModel(discSpec(0.3), kRes);
  const double a[] = {1, 1, 0.5};
  const double same[] = {1, 1, 0.5 + 2 * kPi};
  const double tiny[] = {1 + 1e-12, 1, 0.5};
  CHECK(m->stepsBetween(a, a) == 0);
  CHECK(m->stepsBetween(a, same) == 0);
  CHECK(m->stepsBetween(a, tiny) == 1);
}

TEST_CASE("stepsBetween rounds up fractional steps but forgives rounding noise") {
  auto m = makeRobotModel(armSpec({1, 1}, 0.05), kRes);
  const double a[] = {0, 0};
  const double frac[] = {0.125, 0};           // 2.5 steps
  const double whole[] = {0.15 + 1e-14, 0};   // 3 steps and noise
  CHECK(m->stepsBetween(a, frac) == 3);
  CHECK(m->stepsBetween(a, whole) == 3);
}

TEST_CASE("mobile interpolation turns along the shortest arc and ends exactly at the target") {
  auto m = makeRobotModel(discSpec(0.3), kRes);
  const double a[] = {0, 0, 3.0};
  const double b[] = {2, 4, -3.0};
  double q[3];
  m->interpolate(a, b, 0.5, q);
  CHECK(q[0] == 1.0);
  CHECK(q[1] == 2.0);
  CHECK(q[2] == doctest::Approx(kPi));
  m->interpolate(a, b, 1.0, q);
  CHECK(q[0] == b[0]);
  CHECK(q[1] == b[1]);
  CHECK(q[2] == b[2]);
}

TEST_CASE("interpolation midpoints round like the checker's 0.5 (a + b)") {
  auto m = makeRobotModel(armSpec({1, 1, 1}, 0.05), kRes);
  const double a[] = {0.1, -0.7, 2.3};
  const double b[] = {0.3, 0.2, -1.9};
  double q[3];
  m->interpolate(a, b, 0.5, q);
  for (int i = 0; i < 3; ++i) CHECK(q[i] == 0.5 * (a[i] + b[i]));
}

TEST_CASE("a box footprint's length lies along the heading") {
  auto m = makeRobotModel(boxSpec(0.6, 0.4), kRes);
  const double q[] = {5, 5, kPi / 2};
  std::vector<geo::Body> parts;
  m->bodies(q, parts);
  REQUIRE(parts.size() == 1);
  const geo::Aabb b = geo::bounds(parts[0]);
  CHECK(b.hi.x - b.lo.x == doctest::Approx(0.4));
  CHECK(b.hi.y - b.lo.y == doctest::Approx(0.6));
}

TEST_CASE("arm links point at the base angle plus the cumulative joint angles") {
  const RobotSpec spec = armSpec({1, 2}, 0.1, {1, 2}, kPi / 2);
  const double q[] = {0, -kPi / 2};
  std::vector<geo::Vec2> joints;
  armJointPositions(spec, q, joints);
  REQUIRE(joints.size() == 3);
  CHECK(joints[0] == geo::Vec2{1, 2});
  CHECK(joints[1].x == doctest::Approx(1.0));
  CHECK(joints[1].y == doctest::Approx(3.0));
  CHECK(joints[2].x == doctest::Approx(3.0));
  CHECK(joints[2].y == doctest::Approx(3.0));
}

TEST_CASE("arm bodies are capsules between consecutive joints") {
  const RobotSpec spec = armSpec({1, 2, 0.5}, 0.1, {1, 2}, 0.3);
  auto m = makeRobotModel(spec, kRes);
  const double q[] = {0.4, -1.2, 2.0};
  std::vector<geo::Vec2> joints;
  std::vector<geo::Body> parts;
  armJointPositions(spec, q, joints);
  m->bodies(q, parts);
  REQUIRE(parts.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(parts[i].kind == geo::CoreKind::Segment);
    CHECK(parts[i].p0 == joints[i]);
    CHECK(parts[i].p1 == joints[i + 1]);
    CHECK(parts[i].radius == 0.1);
  }
}

TEST_CASE("boundsWithin holds the bodies at every configuration of its box, and is tight where the box is a point") {
  // Conflict detection prunes whole chunks of instants with these boxes:
  // one that misses a body by a hair would miss a conflict.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  const std::vector<RobotSpec> specs{armSpec({0.5, 0.5, 0.5, 0.5, 0.5}, 0.05, {4, 0}, kPi),
                                     armSpec({1, 2, 0.5}, 0.1, {1, 2}, 0.3), boxSpec(0.6, 0.4), discSpec(0.3)};
  int checked = 0;
  for (const RobotSpec& spec : specs) {
    auto m = makeRobotModel(spec, kRes);
    const auto dim = static_cast<std::size_t>(m->dim());
    std::vector<double> lo(dim), hi(dim), q(dim);
    std::vector<geo::Body> parts;
    for (int box = 0; box < 200; ++box) {
      const double spread = box % 4 == 0 ? 0.0 : 0.6 * unit(rng);  // some boxes are points
      for (std::size_t i = 0; i < dim; ++i) {
        const double c = 3.0 * u(rng);
        lo[i] = c - spread * unit(rng);
        hi[i] = c + spread * unit(rng);
      }
      const geo::Aabb within = m->boundsWithin(lo.data(), hi.data());
      for (int sample = 0; sample < 30; ++sample) {
        // Corners of the box, where a bound is likeliest to be short, and inside it.
        for (std::size_t i = 0; i < dim; ++i) {
          const double s = sample < 8 ? static_cast<double>((sample >> (i % 3)) & 1) : unit(rng);
          q[i] = lo[i] + s * (hi[i] - lo[i]);
        }
        m->bodies(q.data(), parts);
        geo::Aabb tight;
        for (const auto& b : parts) tight.expand(geo::bounds(b));
        REQUIRE(within.contains(tight));
        ++checked;
      }
      if (spread == 0.0 && !m->isMobile()) {  // an arm standing still: its own bounds
        m->bodies(lo.data(), parts);
        geo::Aabb tight;
        for (const auto& b : parts) tight.expand(geo::bounds(b));
        CHECK(within.lo.x == doctest::Approx(tight.lo.x).epsilon(1e-6));
        CHECK(within.hi.y == doctest::Approx(tight.hi.y).epsilon(1e-6));
      }
    }
  }
  CHECK(checked == 4 * 200 * 30);
}

TEST_CASE("a folded arm whose third link crosses its first self-collides") {
  // Link 1 runs (0,0)-(2,0); link 3 comes back down through y = 0 near x = 1.07.
  auto m = makeRobotModel(armSpec({2, 1, 2}, 0.05), kRes);
  const double folded[] = {0, 2.5, 2.0};
  const double open[] = {0, 2.5, 0};
  CHECK(m->selfCollides(folded));
  CHECK_FALSE(m->selfCollides(open));
}

TEST_CASE("adjacent links overlapping at a sharp bend are no self-collision") {
  const RobotSpec spec = armSpec({1, 1, 1}, 0.1);
  auto m = makeRobotModel(spec, kRes);
  const double q[] = {0, 2.9, 0};
  std::vector<geo::Body> parts;
  m->bodies(q, parts);
  REQUIRE(geo::touches(parts[0], parts[1]));  // the pair the contract exempts
  CHECK_FALSE(m->selfCollides(q));
}

TEST_CASE("joint limits default to -pi..pi with the contract's 1e-6 slack") {
  auto m = makeRobotModel(armSpec({1, 1}, 0.05), kRes);
  const double inside[] = {kPi + 5e-7, -kPi};
  const double outside[] = {0, -kPi - 2e-6};
  CHECK(m->withinLimits(inside));
  CHECK_FALSE(m->withinLimits(outside));
}

TEST_CASE("an arm with one limit pair per link missing is refused") {
  RobotSpec spec = armSpec({1, 1}, 0.05);
  spec.joint_limits = {{-1, 1}};
  CHECK_THROWS_AS(makeRobotModel(spec, kRes), std::invalid_argument);
}

TEST_CASE("geometry signatures name the shape with six significant digits") {
  CHECK(makeRobotModel(discSpec(0.3), kRes)->geometrySignature() == "mobile:disc:r=0.3");
  CHECK(makeRobotModel(boxSpec(0.6, 0.4), kRes)->geometrySignature() == "mobile:box:0.6x0.4");
  RobotSpec arm = armSpec({0.5, 0.5}, 0.05);
  arm.joint_limits = {{-3.14159265, 3.14159265}, {-2.6, 2.6}};
  CHECK(makeRobotModel(arm, kRes)->geometrySignature() ==
        "arm:links=0.5,0.5:r=0.05:limits=-3.14159/3.14159,-2.6/2.6");
}

TEST_CASE("a geometry signature reads back to its robot, and no other text does") {
  RobotSpec arm = armSpec({0.5, 0.25, 1e-7}, 0.05, {3, 4}, 1.0);
  arm.joint_limits = {{-3.14159265, 3.14159265}, {-2.6, 2.6}, {0, 0}};
  for (const RobotSpec& spec : {discSpec(0.3), boxSpec(0.6, 0.4), boxSpec(0, 0.4), arm}) {
    const std::string signature = makeRobotModel(spec, kRes)->geometrySignature();
    CAPTURE(signature);
    const auto read = robotFromSignature(signature);
    REQUIRE(read.has_value());
    CHECK(read->kind == spec.kind);
    CHECK(read->dim() == spec.dim());
    CHECK(makeRobotModel(*read, kRes)->geometrySignature() == signature);
  }
  // "0x0.4" is a box of length 0, not a hexadecimal number.
  CHECK(robotFromSignature("mobile:box:0x0.4")->box_size.y == 0.4);
  for (const char* bad : {"", "spaceship", "mobile:disc:-1", "mobile:disc:r=-1", "mobile:disc:r=0.30",
                          "mobile:disc:r=nan", "mobile:disc:r=inf", "mobile:disc:r=0.3 ", "mobile:disc:r=0.3|",
                          "mobile:box:0.6x", "mobile:box:0.6", "arm:links=:r=0.05:limits=",
                          "arm:links=1,1:r=0.05:limits=-1/1", "arm:links=1:r=0.05:limits=1/-1",
                          "arm:links=1:r=0.05", "arm:links=-1:r=0.05:limits=-1/1"}) {
    CAPTURE(bad);
    CHECK_FALSE(robotFromSignature(bad).has_value());
  }
}

TEST_CASE("arms placed at different bases share a geometry signature") {
  auto a = makeRobotModel(armSpec({1, 1}, 0.05, {0, 0}, 0.0), kRes);
  auto b = makeRobotModel(armSpec({1, 1}, 0.05, {7, 3}, 1.2), kRes);
  auto c = makeRobotModel(armSpec({1, 1.5}, 0.05, {0, 0}, 0.0), kRes);
  CHECK(a->geometrySignature() == b->geometrySignature());
  CHECK(a->geometrySignature() != c->geometrySignature());
}

TEST_CASE("mobile sampling bounds inset the workspace by the footprint's inner radius") {
  const geo::Aabb ws{{0, 0}, {20, 10}};
  std::vector<double> lo, hi;
  makeRobotModel(boxSpec(0.6, 0.4), kRes)->samplingBounds(ws, lo, hi);
  REQUIRE(lo.size() == 3);
  CHECK(lo[0] == doctest::Approx(0.2));
  CHECK(hi[1] == doctest::Approx(9.8));
  CHECK(lo[2] == doctest::Approx(-kPi));
  CHECK(hi[2] == doctest::Approx(kPi));
}

TEST_CASE("mobile sampling bounds collapse to the centre line when the robot cannot fit") {
  const geo::Aabb ws{{0, 0}, {20, 0.5}};
  std::vector<double> lo, hi;
  makeRobotModel(discSpec(0.3), kRes)->samplingBounds(ws, lo, hi);
  CHECK(lo[1] == doctest::Approx(0.25));
  CHECK(hi[1] == doctest::Approx(0.25));
}

TEST_CASE("arm sampling bounds are its joint limits") {
  RobotSpec spec = armSpec({1, 1}, 0.05);
  spec.joint_limits = {{-1, 2}, {-0.5, 0.25}};
  std::vector<double> lo, hi;
  makeRobotModel(spec, kRes)->samplingBounds({{0, 0}, {1, 1}}, lo, hi);
  CHECK(lo == std::vector<double>{-1, -0.5});
  CHECK(hi == std::vector<double>{2, 0.25});
}

namespace {

// Farthest distance from c to any point of a body (bodies are convex, so a
// vertex of the core plus the radius).
double farthestFrom(const geo::Body& b, geo::Vec2 c) {
  switch (b.kind) {
    case geo::CoreKind::Point: return geo::norm(b.p0 - c) + b.radius;
    case geo::CoreKind::Segment: return std::max(geo::norm(b.p0 - c), geo::norm(b.p1 - c)) + b.radius;
    case geo::CoreKind::Rect: {
      const geo::Vec2 u = b.axis * b.half.x, v = geo::perp(b.axis) * b.half.y;
      double far = 0.0;
      for (geo::Vec2 k : {b.p0 + u + v, b.p0 + u - v, b.p0 - u + v, b.p0 - u - v})
        far = std::max(far, geo::norm(k - c));
      return far + b.radius;
    }
  }
  return 0.0;
}

}  // namespace

TEST_CASE("every body part stays inside the bounding disc") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  const std::unique_ptr<RobotModel> models[] = {makeRobotModel(discSpec(0.3), kRes),
                                                makeRobotModel(boxSpec(0.6, 0.4), kRes),
                                                makeRobotModel(armSpec({1, 0.5, 0.7}, 0.08, {3, 4}, 0.2), kRes)};
  std::vector<geo::Body> parts;
  for (const auto& m : models) {
    for (int trial = 0; trial < 100; ++trial) {
      std::vector<double> q(static_cast<std::size_t>(m->dim()));
      for (double& v : q) v = u(rng);
      m->bodies(q.data(), parts);
      for (const geo::Body& p : parts) CHECK(farthestFrom(p, m->boundingCenter(q.data())) <= m->boundingRadius() + 1e-12);
    }
  }
}

TEST_CASE("settleAtGoal ends a path where the robot arrived, waits on a 2 pi turn or rounding noise included") {
  auto m = makeRobotModel(discSpec(0.3), kRes);
  constexpr double kTwoPi = 6.283185307179586;
  Path p(3);
  for (const std::array<double, 3>& q : std::vector<std::array<double, 3>>{
           {0.0, 0.0, 0.5}, {0.05, 0.0, 0.5}, {0.1, 0.0, 0.5 + kTwoPi}, {0.1, 0.0, 0.5 + kTwoPi}, {0.1 + 1e-13, 0.0, 0.5}, {0.1, 0.0, 0.5}})
    p.push(q.data());
  settleAtGoal(*m, p);
  p.dropTrailingWaits();
  REQUIRE(p.size() == 3);
  CHECK(p.at(2)[0] == 0.1);
  CHECK(p.at(2)[2] == 0.5);
  CHECK(p.at(1)[0] == 0.05);
  // A last step that moves is kept: the robot arrives with it.
  Path moving(3);
  for (const std::array<double, 3>& q :
       std::vector<std::array<double, 3>>{{0.0, 0.0, 0.0}, {0.05, 0.0, 0.0}, {0.05, 0.0, 0.0}, {0.1, 0.0, 0.0}})
    moving.push(q.data());
  settleAtGoal(*m, moving);
  moving.dropTrailingWaits();
  CHECK(moving.size() == 4);
  // Arms: joint noise far below a step settles; a real move does not.
  auto arm = makeRobotModel(armSpec({1, 1}, 0.05), kRes);
  Path a(2);
  for (const std::array<double, 2>& q :
       std::vector<std::array<double, 2>>{{0.0, 0.0}, {0.3, 0.2}, {0.3 + 1e-12, 0.2}, {0.3, 0.2}})
    a.push(q.data());
  settleAtGoal(*arm, a);
  a.dropTrailingWaits();
  CHECK(a.size() == 2);
}
