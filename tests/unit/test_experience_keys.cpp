// Canonical keys: what makes one stored experience serve many subproblems.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "earc/experience/keys.hpp"
#include "earc/experience/sampling.hpp"
#include "support.hpp"

using earc::test::discTraits;
using earc::test::line;

using namespace earc;
using namespace earc::exp;

namespace {

RobotTraits arm(double x, double y, double angle) {
  RobotSpec s;
  s.kind = RobotKind::Manipulator;
  s.base_position = {x, y};
  s.base_angle = angle;
  s.links.assign(5, 0.5);
  s.link_radius = 0.05;
  s.joint_limits.assign(5, {-2.6, 2.6});
  return traitsOf(*makeRobotModel(s, Resolution{}));
}

void checkNear(const std::vector<double>& a, const std::vector<double>& b, double tol = 1e-9) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) CHECK(std::abs(a[i] - b[i]) < tol);
}

}  // namespace

TEST_CASE("a mobile subproblem gives the same key and class whatever order its robots are listed in") {
  std::vector<RobotTraits> robots{discTraits(0.3), discTraits(0.3), discTraits(0.3)};
  std::vector<std::vector<double>> s{{1, 2, 0}, {3, 1, 1}, {2, 4, 2}}, g{{3, 3, 0}, {1, 2.5, 0}, {2, 0, 1}};
  Canonical a = canonicalize(robots, s, g);
  // Listed as robots 2, 0, 1.
  Canonical b = canonicalize(robots, {s[2], s[0], s[1]}, {g[2], g[0], g[1]});
  CHECK(a.cls == b.cls);
  checkNear(a.key, b.key);
  CHECK(a.key.size() == 12);
  // Canonical position c holds the same physical robot in both listings.
  std::vector<int> b_to_a{2, 0, 1};
  for (int c = 0; c < 3; ++c) CHECK(b_to_a[static_cast<std::size_t>(b.order[static_cast<std::size_t>(c)])] == a.order[static_cast<std::size_t>(c)]);
}

TEST_CASE("a mobile key is invariant under translation of the whole subproblem") {
  std::vector<RobotTraits> robots{discTraits(0.3), discTraits(0.3)};
  std::vector<std::vector<double>> s{{1, 2, 0}, {3, 1, 1}}, g{{3, 3, 0}, {1, 2.5, 0}};
  Canonical a = canonicalize(robots, s, g);
  for (auto* v : {&s, &g})
    for (auto& q : *v) {
      q[0] += 123.456;
      q[1] -= 78.9;
    }
  Canonical b = canonicalize(robots, s, g);
  CHECK(a.cls == b.cls);
  checkNear(a.key, b.key);
  CHECK(b.offset.x == doctest::Approx(a.offset.x + 123.456));
  CHECK(b.offset.y == doctest::Approx(a.offset.y - 78.9));
}

TEST_CASE("a mobile key is the starts and goals relative to their centroid, headings left out") {
  std::vector<RobotTraits> robots{discTraits(0.3), discTraits(0.3)};
  Canonical c = canonicalize(robots, {{0, 0, 1}, {2, 0, 2}}, {{2, 2, 3}, {0, 2, -1}});
  CHECK(c.offset.x == doctest::Approx(1.0));
  CHECK(c.offset.y == doctest::Approx(1.0));
  checkNear(c.key, {-1, -1, 1, 1, 1, -1, -1, 1}, 1e-12);
  CHECK(c.order == std::vector<int>{0, 1});
}

TEST_CASE("mobile paths survive the trip to canonical form and back") {
  std::vector<RobotTraits> robots{discTraits(0.3), discTraits(0.3)};
  std::vector<std::vector<double>> s{{5, 5, 0}, {4, 6, 1}}, g{{6, 6, 0}, {6, 4, 1}};
  Canonical c = canonicalize(robots, s, g);
  std::vector<Path> paths{line(s[0], g[0], 5), line(s[1], g[1], 5)};
  auto canonical = c.toCanonical(paths);
  checkNear(keyOfCanonicalPaths(RobotKind::Mobile, canonical), c.key);
  auto back = c.fromCanonical(canonical);
  for (std::size_t r = 0; r < 2; ++r) checkNear(back[r].raw(), paths[r].raw());
}

TEST_CASE("discs of different radius never share a class") {
  std::vector<std::vector<double>> s{{0, 0, 0}, {1, 0, 0}}, g{{1, 1, 0}, {0, 1, 0}};
  Canonical small = canonicalize(std::vector<RobotTraits>{discTraits(0.3), discTraits(0.3)}, s, g);
  Canonical large = canonicalize(std::vector<RobotTraits>{discTraits(0.5), discTraits(0.5)}, s, g);
  CHECK(small.cls != large.cls);
  CHECK(small.key == large.key);
}

TEST_CASE("mobile subproblems of different robot counts are different classes") {
  auto two = canonicalize(std::vector<RobotTraits>{discTraits(0.3), discTraits(0.3)}, {{0, 0, 0}, {1, 0, 0}}, {{1, 1, 0}, {0, 1, 0}});
  auto three = canonicalize(std::vector<RobotTraits>{discTraits(0.3), discTraits(0.3), discTraits(0.3)},
                            {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{1, 1, 0}, {0, 1, 0}, {2, 2, 0}});
  CHECK(two.cls != three.cls);
  CHECK(two.cls.robot_count == 2);
  CHECK(three.key.size() == 12);
}

TEST_CASE("arm pairs are classed by their relative base transform in canonical orientation") {
  // b sits 3 units along a's x axis, both facing the same way: T_ab =
  // (3, 0, 0), T_ba = (-3, 0, 0); "dx=-3..." sorts first, so b leads.
  std::vector<RobotTraits> ab{arm(0, 0, 0), arm(3, 0, 0)};
  std::vector<std::vector<double>> s{{0.1, 0.2, 0.3, 0.4, 0.5}, {-0.1, -0.2, -0.3, -0.4, -0.5}};
  std::vector<std::vector<double>> g{{0.2, 0.2, 0.3, 0.4, 0.5}, {-0.2, -0.2, -0.3, -0.4, -0.5}};
  Canonical c = canonicalize(ab, s, g);
  CHECK(c.cls.base_class == "dx=-3.000,dy=0.000,dth=0.000");
  CHECK(c.sign == -1);
  CHECK(c.order == std::vector<int>{1, 0});
  CHECK_FALSE(c.symmetric);
  CHECK(c.key.size() == static_cast<std::size_t>(keyDimension(RobotKind::Manipulator, 2, 5)));
  // Listed the other way round the order is already canonical.
  Canonical d = canonicalize(std::vector<RobotTraits>{ab[1], ab[0]}, {s[1], s[0]}, {g[1], g[0]});
  CHECK(d.sign == 1);
  CHECK(d.cls == c.cls);
  CHECK(d.key == c.key);
}

TEST_CASE("retrieval swaps robot roles for a negative base-transform match") {
  std::vector<RobotTraits> ab{arm(0, 0, 0), arm(3, 0, 0)};
  std::vector<std::vector<double>> s{{0.1, 0.2, 0.3, 0.4, 0.5}, {1.1, 1.2, 1.3, 1.4, 1.5}};
  std::vector<std::vector<double>> g{{0.3, 0.2, 0.3, 0.4, 0.5}, {1.3, 1.2, 1.3, 1.4, 1.5}};
  // Stored from a subproblem listing (b, a): sign +1, canonical = (b, a).
  Canonical stored = canonicalize(std::vector<RobotTraits>{ab[1], ab[0]}, {s[1], s[0]}, {g[1], g[0]});
  REQUIRE(stored.sign == 1);
  std::vector<Path> canonical = stored.toCanonical({line(s[1], g[1], 4), line(s[0], g[0], 4)});
  // Retrieved for a subproblem listing (a, b): sign -1 puts canonical robot
  // 0 (b) at subproblem index 1 and canonical robot 1 (a) at index 0.
  Canonical query = canonicalize(ab, s, g);
  REQUIRE(query.sign == -1);
  auto mapped = query.fromCanonical(canonical);
  CHECK(mapped[0].raw() == line(s[0], g[0], 4).raw());
  CHECK(mapped[1].raw() == line(s[1], g[1], 4).raw());
}

TEST_CASE("two arms facing each other are a symmetric class with an order-independent key") {
  const double pi = std::numbers::pi;
  std::vector<RobotTraits> pair{arm(3, 3, pi / 2), arm(3, 7, -pi / 2)};
  std::vector<std::vector<double>> s{{0.1, 0.2, 0.3, 0.4, 0.5}, {0.5, 0.4, 0.3, 0.2, 0.1}};
  std::vector<std::vector<double>> g{{0.2, 0.2, 0.3, 0.4, 0.5}, {0.6, 0.4, 0.3, 0.2, 0.1}};
  Canonical a = canonicalize(pair, s, g);
  Canonical b = canonicalize(std::vector<RobotTraits>{pair[1], pair[0]}, {s[1], s[0]}, {g[1], g[0]});
  CHECK(a.symmetric);
  CHECK(a.cls.base_class == "dx=4.000,dy=0.000,dth=3.142");
  CHECK(a.cls == b.cls);
  CHECK(a.key == b.key);
  CHECK(a.sign == -b.sign);
  Canonical other = swappedRoles(a, s, g);
  CHECK(other.cls == a.cls);
  CHECK(other.sign == -a.sign);
  CHECK(other.key != a.key);
}

TEST_CASE("base transform classes ignore rounding noise and treat -pi and pi as one angle") {
  const double pi = std::numbers::pi;
  CHECK(baseClassString(4.0000000001, -1e-12, pi) == baseClassString(3.9999999999, 1e-12, -pi));
  CHECK(baseClassString(0, -0.0, 0) == "dx=0.000,dy=0.000,dth=0.000");
  CHECK(baseClassString(1, 0, 0) != baseClassString(1.01, 0, 0));
}

TEST_CASE("the stored key of a canonical experience agrees with its paths' endpoints") {
  std::mt19937_64 rng(5);
  std::vector<RobotTraits> robots{discTraits(0.3), discTraits(0.3), discTraits(0.3), discTraits(0.3)};
  for (int i = 0; i < 20; ++i) {
    Experience e = straightLineExperience(robots, sampleMobileQuery(4, rng), 7);
    CHECK_FALSE(findProblem(e).has_value());
  }
}

TEST_CASE("robots that form no experience class are refused") {
  CHECK_FALSE(hasExperienceClass(std::vector<RobotTraits>{arm(0, 0, 0)}));
  CHECK_FALSE(hasExperienceClass(std::vector<RobotTraits>{arm(0, 0, 0), discTraits(0.3)}));
  CHECK(hasExperienceClass(std::vector<RobotTraits>{discTraits(0.3)}));
  CHECK_THROWS_AS(canonicalize(std::vector<RobotTraits>{arm(0, 0, 0), arm(1, 0, 0), arm(2, 0, 0)},
                               {{0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}},
                               {{0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}}),
                  std::invalid_argument);
}
