// The planner's view: what is learned for one subproblem is retrieved for
// the same subproblem elsewhere, listed differently, or with roles swapped.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "earc/experience/retrieval.hpp"
#include "earc/experience/scratch.hpp"
#include "support.hpp"

using earc::test::line;

using namespace earc;
using namespace earc::exp;

namespace {

std::unique_ptr<RobotModel> discModel(double translation = 0.05) {
  RobotSpec s;
  s.radius = 0.3;
  Resolution res;
  res.translation = translation;
  return makeRobotModel(s, res);
}

std::unique_ptr<RobotModel> armModel(double x, double y, double angle) {
  RobotSpec s;
  s.kind = RobotKind::Manipulator;
  s.base_position = {x, y};
  s.base_angle = angle;
  s.links.assign(5, 0.5);
  s.link_radius = 0.05;
  s.joint_limits.assign(5, {-2.6, 2.6});
  return makeRobotModel(s, Resolution{});
}

}  // namespace

TEST_CASE("a mobile solution learned in one place is retrieved translated and reordered elsewhere") {
  ScratchDirectory dir("retrieval");
  ExperienceStore store(dir.file("e.db"));
  auto m = discModel();
  std::vector<const RobotModel*> robots{m.get(), m.get()};
  // 2.83 units in 59 steps of 0.048: within the 0.05 resolution.
  std::vector<Path> solved{line({0, 0, 0}, {2, 2, 0}, 60), line({2, 0, 1}, {0, 2, 1}, 60)};
  REQUIRE(learn(store, robots, solved, 0.1).has_value());
  // The same subproblem 10 units to the right, robots listed the other way.
  auto moved = [](const Path& p) {
    Path q = p;
    for (std::size_t t = 0; t < q.size(); ++t) q.mutableAt(t)[0] += 10;
    return q;
  };
  std::vector<std::vector<double>> starts{{12, 0, 1}, {10, 0, 0}}, goals{{10, 2, 1}, {12, 2, 0}};
  auto found = retrieveCandidates(store, robots, starts, goals, 3);
  REQUIRE(found.size() == 1);
  CHECK(found[0].distance < 1e-9);
  Path want0 = moved(solved[1]), want1 = moved(solved[0]);
  for (std::size_t i = 0; i < want0.raw().size(); ++i) {
    CHECK(found[0].paths[0].raw()[i] == doctest::Approx(want0.raw()[i]));
    CHECK(found[0].paths[1].raw()[i] == doctest::Approx(want1.raw()[i]));
  }
}

TEST_CASE("an arm solution learned with one role order is retrieved for the swapped order") {
  ScratchDirectory dir("retrieval");
  ExperienceStore store(dir.file("e.db"));
  auto a = armModel(0, 0, 0), b = armModel(3, 0, 0);
  std::vector<double> sa{0.1, 0.2, 0.3, 0.4, 0.5}, ga{0.3, 0.2, 0.3, 0.4, 0.5};
  std::vector<double> sb{1.1, 1.2, 1.3, 1.4, 1.5}, gb{1.3, 1.2, 1.3, 1.4, 1.5};
  REQUIRE(learn(store, {a.get(), b.get()}, {line(sa, ga, 5), line(sb, gb, 5)}, 0.1).has_value());
  auto found = retrieveCandidates(store, {b.get(), a.get()}, {sb, sa}, {gb, ga}, 3);
  REQUIRE(found.size() == 1);
  CHECK(found[0].paths[0].raw() == line(sb, gb, 5).raw());  // robot b's path at b's index
  CHECK(found[0].paths[1].raw() == line(sa, ga, 5).raw());
}

TEST_CASE("the candidates after the k nearest come without those k") {
  ScratchDirectory dir("retrieval");
  ExperienceStore store(dir.file("e.db"));
  auto a = armModel(0, 0, 0), b = armModel(3, 0, 0);
  std::vector<double> sb{1.1, 1.2, 1.3, 1.4, 1.5}, gb{1.3, 1.2, 1.3, 1.4, 1.5};
  for (double d : {0.0, 0.2, 0.4, 0.6}) {
    std::vector<double> sa{0.1 + d, 0.2, 0.3, 0.4, 0.5}, ga{0.3 + d, 0.2, 0.3, 0.4, 0.5};
    REQUIRE(learn(store, {a.get(), b.get()}, {line(sa, ga, 5), line(sb, gb, 5)}, 0.1).has_value());
  }
  const std::vector<double> sa{0.1, 0.2, 0.3, 0.4, 0.5}, ga{0.3, 0.2, 0.3, 0.4, 0.5};
  auto all = retrieveCandidates(store, {a.get(), b.get()}, {sa, sb}, {ga, gb}, 4);
  REQUIRE(all.size() == 4);
  auto next = retrieveCandidates(store, {a.get(), b.get()}, {sa, sb}, {ga, gb}, 4, 1);
  REQUIRE(next.size() == 3);
  for (std::size_t i = 0; i < next.size(); ++i) {
    CHECK(next[i].id == all[i + 1].id);
    CHECK(next[i].paths[0].raw() == all[i + 1].paths[0].raw());
  }
  CHECK(retrieveCandidates(store, {a.get(), b.get()}, {sa, sb}, {ga, gb}, 2, 4).empty());
}

TEST_CASE("a symmetric arm pair searches both role assignments") {
  ScratchDirectory dir("retrieval");
  ExperienceStore store(dir.file("e.db"));
  const double pi = std::numbers::pi;
  auto lower = armModel(3, 3, pi / 2), upper = armModel(3, 7, -pi / 2);
  std::vector<double> s1{0.1, 0.2, 0.3, 0.4, 0.5}, g1{0.2, 0.2, 0.3, 0.4, 0.5};
  std::vector<double> s2{-0.5, 0.4, 0.3, 0.2, 0.1}, g2{-0.4, 0.4, 0.3, 0.2, 0.1};
  REQUIRE(learn(store, {lower.get(), upper.get()}, {line(s1, g1, 4), line(s2, g2, 4)}, 0.1, Source::Planner, -1)
              .has_value());
  // The mirror-role query: the lower arm does what the upper arm did. Only
  // the other role assignment matches it exactly.
  auto found = retrieveCandidates(store, {lower.get(), upper.get()}, {s2, s1}, {g2, g1}, 1);
  REQUIRE(found.size() == 1);
  CHECK(found[0].distance < 1e-12);
  CHECK(found[0].paths[0].raw() == line(s2, g2, 4).raw());
}

TEST_CASE("robots that form no class retrieve nothing and learn nothing") {
  ScratchDirectory dir("retrieval");
  ExperienceStore store(dir.file("e.db"));
  auto a = armModel(0, 0, 0);
  auto m = discModel();
  std::vector<double> q{0, 0, 0, 0, 0};
  CHECK(retrieveCandidates(store, {a.get()}, {q}, {q}, 5).empty());
  CHECK_FALSE(learn(store, {a.get(), m.get()}, {line(q, q, 2), line({0, 0, 0}, {1, 0, 0}, 2)}, 0.1).has_value());
}

TEST_CASE("an entry stored under a coarser resolution comes back in steps the robots can take") {
  ScratchDirectory dir("retrieval");
  ExperienceStore store(dir.file("e.db"));
  auto coarse = discModel(0.2), fine = discModel(0.05);
  // 0.2 per step: fine robots need 4 steps for each.
  std::vector<Path> solved{line({0, 0, 0}, {1, 0, 0}, 6), line({1, 1, 0}, {0, 1, 0}, 6)};
  REQUIRE(learn(store, {coarse.get(), coarse.get()}, solved, 0.1).has_value());
  std::vector<const RobotModel*> robots{fine.get(), fine.get()};
  auto found = retrieveCandidates(store, robots, {{0, 0, 0}, {1, 1, 0}}, {{1, 0, 0}, {0, 1, 0}}, 1);
  REQUIRE(found.size() == 1);
  const auto& p = found[0].paths;
  CHECK(p[0].size() == 21);
  CHECK(p[0].size() == p[1].size());
  for (std::size_t r = 0; r < 2; ++r)
    for (std::size_t t = 0; t + 1 < p[r].size(); ++t) CHECK(fine->stepsBetween(p[r].at(t), p[r].at(t + 1)) <= 1);
  CHECK(p[0].back()[0] == doctest::Approx(1.0));
  // Paths that already fit are handed back unchanged.
  CHECK(fitResolution(robots, p)[0].raw() == p[0].raw());
}

TEST_CASE("a solved subproblem beyond what the store holds is not learned, and learning goes on") {
  ScratchDirectory dir("retrieval");
  ExperienceStore store(dir.file("e.db"));
  // Units so coarse (1000 per step) that a 3e6-unit swap is a short plan;
  // its robots end 1.5e6 from its centre, beyond kMaxStoredPosition.
  auto m = discModel(1000);
  std::vector<const RobotModel*> robots{m.get(), m.get()};
  std::vector<Path> wide{line({0, 0, 0}, {3e6, 0, 0}, 3001), line({3e6, 1, 0}, {0, 1, 0}, 3001)};
  CHECK_FALSE(learn(store, robots, wide, 0.1).has_value());
  const std::vector<Path> near{line({0, 0, 0}, {2, 2, 0}, 6), line({2, 0, 1}, {0, 2, 1}, 6)};
  CHECK(learnAll(store, {{robots, wide, 0.1}, {robots, near, 0.1}}) == 1);
  CHECK(store.size() == 1);
}

TEST_CASE("a stored path the robots cannot follow is refused before it is split") {
  auto m = discModel(0.05);
  std::vector<const RobotModel*> robots{m.get(), m.get()};
  // One state 1e4 units out: 2.8e5 steps of 0.05 there and as many back.
  std::vector<Path> far{line({{0, 0, 0}, {1e4, 1e4, 0}, {1, 0, 0}}), line({{1, 1, 0}, {1, 1, 0}, {0, 1, 0}})};
  CHECK_THROWS_WITH_AS(fitResolution(robots, far), doctest::Contains("more than 100000"), NoStepCountError);
  // Too far for an int count of steps at all.
  far[0].mutableAt(1)[0] = 1e300;
  CHECK_THROWS_AS(fitResolution(robots, far), NoStepCountError);
  // The longest it splits: the first state, then one stored step into
  // kMaxFittedStates - 2 and one of a step (0.25 per step: exact sums).
  auto quarter = discModel(0.25);
  const double reach = 0.25 * static_cast<double>(kMaxFittedStates - 2);
  std::vector<Path> longest{line({{0, 0, 0}, {reach, 0, 0}, {reach, 0.25, 0}}),
                            line({{1, 1, 0}, {1, 1, 0}, {1.25, 1, 0}})};
  CHECK(fitResolution({quarter.get(), quarter.get()}, longest)[0].size() == kMaxFittedStates);
}

TEST_CASE("several solved subproblems are learned in one call") {
  ScratchDirectory dir("retrieval");
  ExperienceStore store(dir.file("e.db"));
  auto m = discModel();
  std::vector<const RobotModel*> robots{m.get(), m.get()};
  std::vector<Solved> solved{{robots, {line({0, 0, 0}, {2, 2, 0}, 6), line({2, 0, 1}, {0, 2, 1}, 6)}, 0.1},
                             {robots, {line({0, 0, 0}, {2, 2, 0}, 6), line({2, 0, 1}, {0, 2, 1}, 6)}, 0.1},
                             {robots, {line({5, 0, 0}, {5, 3, 0}, 7), line({6, 3, 0}, {6, 0, 0}, 7)}, 0.2}};
  CHECK(learnAll(store, solved) == 2);  // the second is a duplicate of the first
  CHECK(store.size() == 2);
}
