// Roadmaps (shared, grown, joined, out of time) and the space-time search
// over them among moving robots.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/planner.hpp"
#include "earc/util/kdtree.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using earc::test::fiveLinkArm;
using earc::test::line;

using namespace earc;

#include "arc_fixtures.hpp"

using namespace earc::arc_test;

TEST_CASE("Arms with nothing in reach share one roadmap; an arm near an obstacle or the workspace edge has its own") {
  Scenario s;
  s.name = "arms";
  s.workspace = {{-4, -4}, {12, 8}};
  s.robots = {fiveLinkArm("a", {0, 0}, 1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0}),
              fiveLinkArm("b", {0, 4}, -1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0}),
              fiveLinkArm("c", {6, 0}, 0.0, {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0}),
              fiveLinkArm("d", {10.5, 4}, 0.0, {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0})};
  s.obstacles.push_back(Obstacle::makeBox({7, 1.5}, {0.4, 0.4}));  // within c's reach (2.55)
  RobotModels m(s);
  CollisionWorld world(s);
  RoadmapSet roadmaps(world, m.raw, 50, 10, 1);
  CHECK(&roadmaps.forRobot(0) == &roadmaps.forRobot(1));  // facing each other, yet the same valid joint space
  CHECK(&roadmaps.forRobot(2) != &roadmaps.forRobot(0));  // an obstacle within reach
  CHECK(&roadmaps.forRobot(3) != &roadmaps.forRobot(0));  // its reach crosses the workspace edge
  CHECK(&roadmaps.forRobot(3) != &roadmaps.forRobot(2));
}

TEST_CASE("An arm with something in reach gets the free space's roadmap less what it cannot reach; the others keep theirs") {
  Scenario s;
  s.name = "arms";
  s.workspace = {{-4, -4}, {12, 8}};
  s.robots = {fiveLinkArm("a", {0, 0}, 1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0}),
              fiveLinkArm("c", {6, 0}, 0.0, {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0}),
              fiveLinkArm("d", {10.5, 4}, 0.0, {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0})};
  s.obstacles.push_back(Obstacle::makeBox({7, 1.5}, {1.0, 1.0}));  // within c's reach
  RobotModels m(s);
  CollisionWorld world(s);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  // The arm with nothing in reach: the roadmap it has without the others.
  Scenario alone = s;
  alone.robots.resize(1);
  RobotModels m_alone(alone);
  CollisionWorld world_alone(alone);
  RoadmapSet by_itself(world_alone, m_alone.raw, 300, 10, 1);
  Roadmap& free = roadmaps.forRobot(0);
  Roadmap& reference = by_itself.forRobot(0);
  REQUIRE(free.size() == reference.size());
  for (int v = 0; v < free.size(); ++v) {
    CHECK(std::equal(free.config(v), free.config(v) + 5, reference.config(v)));
    CHECK(free.edges(v).size() == reference.edges(v).size());
  }
  CHECK_FALSE(free.droppedAny());
  for (int robot : {1, 2}) {
    CAPTURE(robot);
    Roadmap& rm = roadmaps.forRobot(robot);
    const RobotModel& model = *m.raw[static_cast<std::size_t>(robot)];
    REQUIRE(rm.size() == free.size());
    int dropped = 0;
    for (int v = 0; v < rm.size(); ++v) {
      CHECK(std::equal(rm.config(v), rm.config(v) + 5, free.config(v)));
      // Dropped exactly where the arm's surroundings take the vertex.
      CHECK(rm.dropped(v) == !world.stateValid(model, rm.config(v)));
      if (rm.dropped(v)) {
        ++dropped;
        continue;
      }
      // A vertex left is joined to at least k others left, by edges not
      // marked invalid unchecked.
      int joined = 0;
      for (const Roadmap::Edge& e : rm.edges(v))
        if (!rm.dropped(e.to)) {
          ++joined;
          CHECK_FALSE(rm.knownInvalid(e.id));
        }
      CHECK(joined >= 10);
    }
    CHECK(dropped > 0);
    CHECK(dropped < rm.size() / 2);
  }
}

TEST_CASE("A robot whose straight motion is free takes it without a roadmap; a wall makes it build one") {
  Scenario s = openScenario(6);
  s.robots = {disc("free", 0.3, {1, 1, 0}, {5, 1, 0}), disc("walled", 0.3, {1, 4.5, 0}, {5, 4.5, 0})};
  // A wall across the second robot's straight line, with room to go round
  // it above and below.
  s.obstacles.push_back(Obstacle::makeBox({3, 4.5}, {0.2, 1.0}));
  RobotModels m(s);
  CollisionWorld world(s);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  const Deadline deadline(10);

  auto free = individualPath(world, roadmaps, *m.raw[0], 0, deadline, 1);
  REQUIRE(free.has_value());
  CHECK(roadmaps.built() == 0);
  CHECK(roadmaps.buildSeconds() == 0);
  // Exactly the straight motion, one step per resolution unit.
  CHECK(free->size() == static_cast<std::size_t>(m.raw[0]->stepsBetween(s.robots[0].start.data(), s.robots[0].goal.data())) + 1);
  for (std::size_t t = 0; t < free->size(); ++t) CHECK(free->at(t)[1] == doctest::Approx(1.0));

  auto walled = individualPath(world, roadmaps, *m.raw[1], 1, deadline, 1);
  REQUIRE(walled.has_value());
  CHECK(roadmaps.built() == 1);
  CHECK(roadmaps.buildSeconds() > 0);
  // Round the wall: somewhere off the straight line, never in the wall.
  bool detours = false;
  for (std::size_t t = 0; t < walled->size(); ++t) {
    detours = detours || std::abs(walled->at(t)[1] - 4.5) > 0.5;
    CHECK(world.stateValid(*m.raw[1], walled->at(t)));
  }
  CHECK(detours);
}

TEST_CASE("A robot in a pocket behind a narrow door grows the roadmap around the pocket, not everywhere") {
  // A 1.6 x 1.6 room in the corner of a 20 x 20 square, its one door 0.8
  // wide opening on a passage that turns up along a wall: no straight
  // motion leads out, and a roadmap of 50 vertices has none that joins
  // the room to the rest.
  // Both ways round: the start in the room (its own part is the small
  // one), and the goal in it (the search from the goal finds the room).
  for (const bool start_inside : {true, false}) {
    CAPTURE(start_inside);
    Scenario s = openScenario(20);
    const std::vector<double> room{0.8, 0.8, 0}, out{15, 15, 0};
    s.robots = {disc("a", 0.3, start_inside ? room : out, start_inside ? out : room)};
    s.obstacles.push_back(Obstacle::makeBox({0.9, 1.7}, {1.8, 0.2}));   // top wall
    s.obstacles.push_back(Obstacle::makeBox({1.7, 0.25}, {0.2, 0.5}));  // right wall, below the door
    s.obstacles.push_back(Obstacle::makeBox({1.7, 1.5}, {0.2, 0.4}));   // and above it: door y in [0.5, 1.3]
    s.obstacles.push_back(Obstacle::makeBox({2.9, 1.3}, {0.2, 2.6}));   // the passage's far wall
    RobotModels m(s);
    CollisionWorld world(s);
    RoadmapSet roadmaps(world, m.raw, 50, 10, 1);
    Roadmap& rm = roadmaps.forRobot(0);
    {
      QueryGraph graph(rm, *m.raw[0]);
      const int a = graph.addVertex(s.robots[0].start.data(), 10), b = graph.addVertex(s.robots[0].goal.data(), 10);
      REQUIRE_FALSE(shortestPath(graph, a, b, Deadline()).has_value());  // the case this is about
    }
    auto path = individualPath(world, roadmaps, *m.raw[0], 0, Deadline(10), 1);
    REQUIRE(path.has_value());
    for (std::size_t t = 0; t < path->size(); ++t) CHECK(world.stateValid(*m.raw[0], path->at(t)));
    // Grown near the room only (doubling would have put most new
    // vertices all over the square), and by no more than doubling would.
    REQUIRE(rm.size() > 50);
    CHECK(rm.size() <= 50 + 3 * 64);
    int far = 0;
    for (int v = 50; v < rm.size(); ++v) far += rm.config(v)[0] > 6.0 || rm.config(v)[1] > 6.0;
    CHECK(far == 0);
  }
}



TEST_CASE("A space-time search among crossing robots returns paths clear of them at every instant") {
  // A turning box robot on a roadmap, three box robots sweeping straight
  // across its square, turning as they go. The search meets the same edge
  // at many start times and in both directions (what it keeps of a motion
  // between tries must be that motion's, at the right instants); every
  // path it returns is checked here instant by instant.
  Scenario s = fourBoxes();
  RobotModels m(s);
  CollisionWorld world(s);
  const RobotModel& model = *m.raw[0];
  Roadmap rm(world, model, 10, 5);
  rm.grow(400);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> pos(0.5, 5.5), ang(-3.0, 3.0);
  const std::size_t horizon = 400;
  SearchTally tally;
  for (int trial = 0; trial < 150; ++trial) {
    std::vector<Path> sweeps;
    for (int i = 0; i < 3; ++i) {
      // From one side of the square to the other, 0.04 a step, turning.
      const double y0 = pos(rng), y1 = pos(rng), th0 = ang(rng), th1 = ang(rng);
      const bool across = trial % 2 == 0;
      Path p(3);
      const int steps = 60 + 40 * (trial % 3);
      for (int t = 0; t <= steps; ++t) {
        const double f = static_cast<double>(t) / steps, a = 0.3 + 5.4 * f, b = y0 + (y1 - y0) * f;
        const double q[3] = {across ? a : b, across ? b : a, th0 + (th1 - th0) * f};
        p.push(q);
      }
      sweeps.push_back(std::move(p));
    }
    std::vector<MovingObstacle> obstacles;
    for (int i = 0; i < 3; ++i) obstacles.push_back({m.raw[static_cast<std::size_t>(i) + 1], &sweeps[static_cast<std::size_t>(i)], 0, i + 1});
    const std::vector<double> start{pos(rng), pos(rng), ang(rng)}, goal{pos(rng), pos(rng), ang(rng)};
    if (!world.stateValid(model, start.data()) || !world.stateValid(model, goal.data())) continue;
    searchAmongMoving(rm, model, start.data(), goal.data(), obstacles, horizon, tally);
  }
  CHECK(tally.found > 100);
  CHECK(tally.none < 30);  // most crossings leave a way through
  CHECK(tally.delayed > 10);  // the crossings got in the way, and the search went around or waited
}

TEST_CASE("The space-time search keeps an arm clear of neighbouring arms that sweep their links past it") {
  // Arms' bounding discs, centred on their fixed bases, always meet their
  // neighbours', so the search's broad phase bounds the arms' bodies over
  // chunks of instants and over the part of each roadmap edge in a chunk
  // (edges here take many steps). Every path it returns is checked here
  // instant by instant against the neighbours' exact bodies.
  Scenario s = openScenario(9);
  s.robots.push_back(fiveLinkArm("mid", {4.5, 4.5}, 0.0, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  s.robots.push_back(fiveLinkArm("left", {2.0, 4.5}, 0.0, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  s.robots.push_back(fiveLinkArm("right", {7.0, 4.5}, 3.14159, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  RobotModels m(s);
  CollisionWorld world(s);
  const RobotModel& model = *m.raw[0];
  Roadmap rm(world, model, 10, 5);
  rm.grow(600);
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> joint(-2.0, 2.0);
  using Config = std::array<double, 5>;
  auto config = [&]() {
    Config q;
    for (double& v : q) v = joint(rng);
    return q;
  };
  const std::size_t horizon = 600;
  SearchTally tally;
  for (int trial = 0; trial < 60; ++trial) {
    // Each neighbour starts and ends stretched away from the middle arm
    // and reaches over to it through two random configurations on the
    // way, 0.15 rad a step at most per joint (fast enough that a chunk's
    // bounds taken from one of its instants miss collisions here).
    std::vector<Path> sweeps;
    const Config away{3.0, 0, 0, 0, 0};
    for (std::size_t r = 1; r <= 2; ++r) {
      Path p(5);
      Config q = away;
      for (int leg = 0; leg < 3; ++leg) {
        const Config to = leg == 2 ? away : config();
        double span = 0.0;
        for (std::size_t j = 0; j < 5; ++j) span = std::max(span, std::abs(to[j] - q[j]));
        const int steps = std::max(1, static_cast<int>(std::ceil(span / 0.15)));
        for (int t = 0; t < steps; ++t) {
          Config at;
          for (std::size_t j = 0; j < 5; ++j) at[j] = q[j] + (to[j] - q[j]) * t / steps;
          p.push(at.data());
        }
        q = to;
      }
      p.push(q.data());
      sweeps.push_back(std::move(p));
    }
    const std::vector<MovingObstacle> obstacles{{m.raw[1], &sweeps[0], 0, 1}, {m.raw[2], &sweeps[1], 0, 2}};
    const Config start = config(), goal = config();
    if (!world.stateValid(model, start.data()) || !world.stateValid(model, goal.data())) continue;
    CAPTURE(trial);
    searchAmongMoving(rm, model, start.data(), goal.data(), obstacles, horizon, tally);
  }
  CHECK(tally.found > 40);
  CHECK(tally.delayed > 8);  // the neighbours got in the way
}

TEST_CASE("The space-time search arrives as early with the roadmap-distance heuristic as with the straight line, and gives up exactly when the horizon is too short") {
  // A disc among walls that the straight line runs through, and a box
  // robot sweeping across. Both heuristics never overestimate, so A*
  // finds the earliest arrival with either; one step less of horizon
  // leaves none (the search stops once its least f passes the horizon).
  Scenario s = openScenario(8);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {7, 7, 0}), RobotSpec::mobileBox("b", {0.6, 0.4})};
  s.robots[1].start = s.robots[1].goal = {0, 0, 0};
  s.obstacles.push_back(Obstacle::makeBox({2.7, 3.0}, {0.3, 6.0}));  // open at the top
  s.obstacles.push_back(Obstacle::makeBox({5.3, 5.0}, {0.3, 6.0}));  // open at the bottom
  SearchWorld w(s, 500);
  const RobotModels& m = w.m;
  const CollisionWorld& world = w.world;
  const RobotModel& model = w.model();
  Roadmap& rm = w.rm;
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> pos(0.4, 7.6);
  int compared = 0, detours = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double y0 = pos(rng), y1 = pos(rng);
    const Path sweep = line({0.4, y0, 0.0}, {7.6, y1, 3.0}, 151);  // left to right, turning
    const std::vector<MovingObstacle> obstacles{{m.raw[1], &sweep, 0, 1}};
    const std::vector<double> start{pos(rng), pos(rng), 0}, goal{pos(rng), pos(rng), 0};
    if (!world.stateValid(model, start.data()) || !world.stateValid(model, goal.data())) continue;
    QueryGraph graph(rm, model);
    const int sv = graph.addVertex(start.data(), 10), gv = graph.addVertex(goal.data(), 10);
    auto line = spaceTimeSearch(graph, sv, gv, obstacles, 600, 0, Deadline(), 2000000, false);
    auto roads = spaceTimeSearch(graph, sv, gv, obstacles, 600, 0, Deadline(), 2000000, true);
    REQUIRE(line.has_value() == roads.has_value());
    if (!line) continue;
    ++compared;
    CAPTURE(trial);
    CHECK(roads->size() == line->size());
    const std::size_t arrival = line->size() - 1;
    if (static_cast<double>(arrival) > 1.5 * model.distance(start.data(), goal.data()) + 2) ++detours;
    for (const bool by_roads : {false, true}) {
      CHECK(spaceTimeSearch(graph, sv, gv, obstacles, arrival, 0, Deadline(), 2000000, by_roads).has_value());
      CHECK_FALSE(spaceTimeSearch(graph, sv, gv, obstacles, arrival - 1, 0, Deadline(), 2000000, by_roads).has_value());
    }
  }
  CHECK(compared > 30);
  CHECK(detours > 5);  // the walls made many ways longer than the straight line
}

TEST_CASE("The searches over a roadmap count their work, so that a budget of work ends them as one of seconds would") {
  // A disc in an open square on a large roadmap. Its edges are checked by
  // a first search and cached, so that what the searches count after it
  // is their own queue work. The space-time search's distances to the
  // goal visit the whole roadmap (6,000 vertices), however near the goal.
  Scenario s = openScenario(8);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {2, 1, 0}), disc("b", 0.3, {6, 6, 0}, {6, 6, 0})};
  SearchWorld w(s, 6000);
  const RobotModels& m = w.m;
  const RobotModel& model = w.model();
  QueryGraph graph(w.rm, model);
  const double start[3] = {1, 1, 0}, goal[3] = {2.5, 1.5, 0};
  const int sv = graph.addVertex(start, 10), gv = graph.addVertex(goal, 10);
  REQUIRE(spaceTimeSearch(graph, sv, gv, {}, 200, 0, Deadline(), 1000000, true).has_value());  // checks the edges

  auto workOf = [&](auto&& search) {
    const std::uint64_t before = t_work_done;
    search();
    return t_work_done - before;
  };
  std::optional<std::vector<int>> vertices;
  const std::uint64_t shortest = workOf([&] { vertices = shortestPath(graph, sv, gv, Deadline()); });
  REQUIRE(vertices.has_value());
  CHECK(shortest >= kWorkPerGraphPop * vertices->size());
  const std::uint64_t by_line = workOf([&] { REQUIRE(spaceTimeSearch(graph, sv, gv, {}, 200, 0, Deadline(), 1000000, false)); });
  const std::uint64_t by_roads = workOf([&] { REQUIRE(spaceTimeSearch(graph, sv, gv, {}, 200, 0, Deadline(), 1000000, true)); });
  CHECK(by_roads >= by_line + kWorkPerGraphPop * 5000);

  // A budget of work halfway between the two: enough for the search by
  // the straight line, not for the one that first measures the roadmap.
  const double halfway = static_cast<double>(by_line + by_roads) / 2 / kWorkPerBudgetSecond;
  const Deadline budget = Deadline().withWorkBudgets(true);
  CHECK(spaceTimeSearch(graph, sv, gv, {}, 200, 0, budget.capped(halfway), 1000000, false).has_value());
  CHECK_FALSE(spaceTimeSearch(graph, sv, gv, {}, 200, 0, budget.capped(halfway), 1000000, true).has_value());
  CHECK(spaceTimeSearch(graph, sv, gv, {}, 200, 0, budget.capped(2 * halfway), 1000000, true).has_value());

  // A budget that ends in the search's own loop ends it at the expansion
  // that spends it (a few units each here), not expansions later. A
  // second disc parked on the goal for 100 steps makes the search expand
  // many states before the robot may arrive.
  Path parked(3);
  for (int t = 0; t <= 100; ++t) parked.push(goal);
  const double away[3] = {6, 6, 0};
  parked.push(away);
  const std::vector<MovingObstacle> obstacles{{m.raw[1], &parked, 0, 1}};
  const std::uint64_t waiting = workOf([&] { REQUIRE(spaceTimeSearch(graph, sv, gv, obstacles, 200, 150, Deadline(), 1000000, false)); });
  REQUIRE(waiting > 20000);
  const std::uint64_t units = waiting / 2;
  const std::uint64_t stopped = workOf([&] {
    CHECK_FALSE(spaceTimeSearch(graph, sv, gv, obstacles, 200, 150,
                                budget.capped(static_cast<double>(units) / kWorkPerBudgetSecond), 1000000, false)
                    .has_value());
  });
  CHECK(stopped >= units);
  CHECK(stopped <= units + 16);  // 2 over here; 67 when the loop read its budget every 256 expansions
}

TEST_CASE("Once nothing near it moves, a space-time search that finds no way stops searching later steps") {
  // A ring of resting discs walls the goal in. The roadmap knows nothing
  // of them (they are robots), so only the space-time search can find
  // that there is no way; once the world stands still, being at a vertex
  // later is no better than being there sooner, and a longer horizon
  // should cost next to nothing more.
  Scenario s = openScenario(8);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {5, 5, 0})};
  const std::vector<double> goal{5, 5, 0};
  std::vector<Path> ring;
  for (int j = 0; j < 8; ++j) {
    const double angle = j * test::kPi / 4;
    const std::vector<double> q{5 + 0.65 * std::cos(angle), 5 + 0.65 * std::sin(angle), 0};
    s.robots.push_back(disc("r" + std::to_string(j), 0.3, q, q));
    ring.push_back(line({q}));
  }
  SearchWorld w(s, 1500);
  const RobotModels& m = w.m;
  QueryGraph graph(w.rm, w.model());
  const double start[3] = {1, 1, 0};
  const int sv = graph.addVertex(start, 10), gv = graph.addVertex(goal.data(), 10);
  std::vector<MovingObstacle> obstacles;
  for (int j = 0; j < 8; ++j) obstacles.push_back({m.raw[static_cast<std::size_t>(j + 1)], &ring[static_cast<std::size_t>(j)], 0, j + 1});
  REQUIRE(spaceTimeSearch(graph, sv, gv, {}, 1000, 0, Deadline(), 10000000).has_value());
  auto workOf = [&](std::size_t horizon) {
    const std::uint64_t before = t_work_done;
    SearchEnd end = SearchEnd::Found;
    CHECK_FALSE(spaceTimeSearch(graph, sv, gv, obstacles, horizon, 0, Deadline(), 10000000, false, &end));
    CHECK(end == SearchEnd::NoWay);
    return t_work_done - before;
  };
  workOf(300);  // checks the edges it reaches, so that what is counted next is the searches' own work
  const std::uint64_t short_horizon = workOf(300), long_horizon = workOf(1200);
  CAPTURE(short_horizon);
  CAPTURE(long_horizon);
  CHECK(long_horizon < short_horizon * 5 / 4);  // searching every vertex at every step: 8 times
}

TEST_CASE("A roadmap whose deadline has passed grows no further and checks no edge") {
  Scenario s = openScenario(6);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {5, 5, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  const double start[3] = {1, 1, 0}, goal[3] = {2, 1, 0};
  // In time: the query's start and goal, joined directly, make a path.
  Roadmap rm(world, *m.raw[0], 10, 3, Deadline(1e6));
  QueryGraph in_time(rm, *m.raw[0]);
  const int s0 = in_time.addVertex(start, 10), g0 = in_time.addVertex(goal, 10);
  CHECK(shortestPath(in_time, s0, g0, Deadline()).has_value());
  // Late: no vertex, and the same edge reads as invalid without being
  // marked so (it was never checked), and the search gives up even with
  // time of its own left.
  Roadmap late(world, *m.raw[0], 10, 3, Deadline(-1.0));
  late.grow(300);
  CHECK(late.size() == 0);
  QueryGraph graph(late, *m.raw[0]);
  const int s1 = graph.addVertex(start, 10), g1 = graph.addVertex(goal, 10);
  int key = 0;
  graph.forEachEdge(s1, [&](int to, int, int k) {
    if (to == g1) key = k;
  });
  REQUIRE(key < 0);  // a query edge
  CHECK_FALSE(graph.edgeValid(key));
  CHECK_FALSE(graph.knownInvalid(key));
  CHECK_FALSE(shortestPath(graph, s1, g1, Deadline()).has_value());
}

TEST_CASE("A roadmap joins each vertex to its nearest once: one edge per pair, listed at both ends") {
  Scenario s = openScenario(6);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {5, 5, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  Roadmap rm(world, *m.raw[0], 10, 3);
  // A vertex is joined to each of its 10 nearest other vertices as they
  // were when it was added.
  auto joinedToNearest = [&](int from) {
    for (int v = from; v < rm.size(); v += 7) {
      std::set<int> adjacent;
      for (const Roadmap::Edge& e : rm.edges(v)) adjacent.insert(e.to);
      for (int u : rm.nearest(rm.config(v), 11))
        if (u != v) CHECK(adjacent.count(u));
    }
  };
  rm.grow(300);
  joinedToNearest(0);
  rm.grow(100);  // vertices added later join the older ones too
  joinedToNearest(300);
  REQUIRE(rm.size() == 400);
  std::map<int, std::vector<std::pair<int, int>>> ends_of;  // edge id -> (from, to) as listed
  for (int v = 0; v < rm.size(); ++v) {
    std::set<int> seen;
    for (const Roadmap::Edge& e : rm.edges(v)) {
      CHECK(e.to != v);
      CHECK(seen.insert(e.to).second);  // no pair twice
      ends_of[e.id].emplace_back(v, e.to);
    }
  }
  for (const auto& [id, ends] : ends_of) {
    CAPTURE(id);
    REQUIRE(ends.size() == 2);
    CHECK(ends[0].first == ends[1].second);
    CHECK(ends[0].second == ends[1].first);
  }
}

TEST_CASE("A point index answers into the caller's buffers what it returns afresh") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3, 3);
  PointIndex index(3);
  for (int i = 0; i < 200; ++i) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    index.add(p);
  }
  // One pair of buffers for every query, the k going up and down, so a
  // longer earlier answer must not leak into a shorter later one.
  std::vector<std::size_t> idx;
  std::vector<double> d2;
  for (std::size_t k : {15u, 3u, 0u, 500u, 1u, 11u}) {
    CAPTURE(k);
    const double q[3] = {u(rng), u(rng), u(rng)};
    index.nearest(q, k, idx, d2);
    CHECK(idx == index.nearest(q, k));
    CHECK(idx.size() == std::min<std::size_t>(k, 200));
  }
}
