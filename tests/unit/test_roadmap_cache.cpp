// Roadmaps kept between plans (RoadmapCache, earc-plan serve): a roadmap
// made again from a snapshot is the one it was taken from, a kept roadmap
// serves only plans whose building would have made it, and plans from
// kept roadmaps are the plans without them.
#include <doctest/doctest.h>

#include <random>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/planner.hpp"
#include "earc/planning/solver.hpp"
#include "earc/scene/robot_model.hpp"
#include "support.hpp"

using namespace earc;

namespace {

Scenario cacheMobileScenario() {
  gen::MobileSettings m;
  m.robots = 8;
  m.obstacles = 8;
  m.seed = 5;
  return gen::generateMobile(m);
}

// With seed 2 and no obstacles every straight motion is free (no roadmap).
Scenario cacheArmScenario(int obstacles, std::uint64_t seed) {
  gen::ArmSettings a;
  a.robots = 8;
  a.obstacles = obstacles;
  a.seed = seed;
  return gen::generateArms(a);
}

// Plans `s` with `settings` and the cache; the plan must be solved.
PlanResult planKept(const Scenario& s, const PlannerSettings& settings, RoadmapCache* cache) {
  PlanContext context;
  context.roadmap_cache = cache;
  PlanResult r = plan(s, settings, nullptr, context);
  REQUIRE(r.solution.solved);
  return r;
}

std::size_t reusedOf(const PlanResult& r) { return static_cast<std::size_t>(r.stats.roadmaps_reused.value_or(-1)); }

}  // namespace

TEST_CASE("A roadmap made from its snapshot is the roadmap: its vertices, edges, neighbours, and how it grows on") {
  const Scenario s = cacheMobileScenario();
  const RobotModels models(s), other_models(s);
  const CollisionWorld world(s), other_world(s);
  Roadmap original(world, *models.raw[0], 10, 7);
  original.grow(400);
  REQUIRE(original.size() == 400);
  REQUIRE(original.edgeValid(0) == original.edgeValid(0));  // one edge checked before the snapshot
  Roadmap copy(other_world, *other_models.raw[0], original.snapshot());
  auto same = [&] {
    REQUIRE(copy.size() == original.size());
    for (int v = 0; v < original.size(); ++v) {
      CHECK(std::equal(original.config(v), original.config(v) + 3, copy.config(v)));
      REQUIRE(copy.edges(v).size() == original.edges(v).size());
      for (std::size_t i = 0; i < original.edges(v).size(); ++i) {
        CHECK(copy.edges(v)[i].to == original.edges(v)[i].to);
        CHECK(copy.edges(v)[i].id == original.edges(v)[i].id);
        CHECK(copy.edges(v)[i].steps == original.edges(v)[i].steps);
      }
    }
  };
  same();
  CHECK(copy.edgeChecks() == original.edgeChecks());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 20.0);
  for (int i = 0; i < 20; ++i) {
    const double q[3] = {u(rng), u(rng), 0.3};
    CHECK(copy.nearest(q, 6) == original.nearest(q, 6));
  }
  // The random engine came along: both grow the same new vertices.
  const ConfigBox box = original.boxAround({5.0, 5.0, 0.0});
  original.growWithin(box);
  copy.growWithin(box);
  CHECK(original.size() > 400);
  same();
}

TEST_CASE("Plans from roadmaps kept from earlier plans are the plans without them, in work budgets or seconds") {
  for (const Scenario& s : {cacheMobileScenario(), cacheArmScenario(4, 2)}) {
    for (Method method : {Method::Arc, Method::Prioritized}) {
      for (bool work : {true, false}) {
        CAPTURE(s.name);
        CAPTURE(methodName(method));
        CAPTURE(work);
        PlannerSettings settings;
        settings.method = method;
        settings.seed = 4;
        settings.work_budgets = work;
        // Seconds: only where no budget runs out, which the scenarios'
        // plans are far from (a budget's end would follow the clock).
        const PlanResult fresh = planKept(s, settings, nullptr);
        RoadmapCache cache(std::size_t{1} << 28);
        const PlanResult first = planKept(s, settings, &cache);
        const PlanResult second = planKept(s, settings, &cache);
        CHECK(reusedOf(first) == 0);
        CHECK(reusedOf(second) > 0);
        CHECK(cache.hits() == reusedOf(second));
        if (method == Method::Arc) {
          CHECK(reusedOf(second) == static_cast<std::size_t>(second.stats.arc->roadmaps_built));
          CHECK(cache.size() == static_cast<std::size_t>(first.stats.arc->roadmaps_built));
        }
        CHECK(first.solution.paths == fresh.solution.paths);
        CHECK(second.solution.paths == fresh.solution.paths);
      }
    }
  }
}

TEST_CASE("A kept roadmap serves only plans whose building would have made it") {
  PlannerSettings settings;
  settings.work_budgets = true;
  settings.seed = 4;
  RoadmapCache cache(std::size_t{1} << 28);
  const Scenario s = cacheMobileScenario();
  const PlanResult first = planKept(s, settings, &cache);
  const auto built = static_cast<std::size_t>(first.stats.arc->roadmaps_built);
  REQUIRE(built > 0);
  // Other starts and goals: the same roadmap.
  Scenario moved = s;
  std::swap(moved.robots[0].start, moved.robots[0].goal);
  std::swap(moved.robots[1].start, moved.robots[1].goal);
  CHECK(reusedOf(planKept(moved, settings, &cache)) == built);
  // Another seed, an obstacle a billionth away, robots a millionth
  // larger: built anew.
  PlannerSettings reseeded = settings;
  reseeded.seed = 5;
  CHECK(reusedOf(planKept(s, reseeded, &cache)) == 0);
  Scenario nudged = s;
  REQUIRE_FALSE(nudged.obstacles.empty());
  nudged.obstacles[0].center.x += 1e-9;
  CHECK(reusedOf(planKept(nudged, settings, &cache)) == 0);

  // Arms with nothing in reach share a roadmap wherever their bases are;
  // an arm with an obstacle in reach has one for its base.
  const Scenario arms = cacheArmScenario(0, 3);
  const PlanResult arms_first = planKept(arms, settings, &cache);
  Scenario shifted = arms;
  for (RobotSpec& r : shifted.robots) r.base_position.x += 0.25;
  const PlanResult arms_shifted = planKept(shifted, settings, &cache);
  CHECK(reusedOf(arms_shifted) == static_cast<std::size_t>(arms_shifted.stats.arc->roadmaps_built));
  CHECK(reusedOf(arms_shifted) > 0);
}

TEST_CASE("A roadmap cut short by the plan's deadline is not kept; a kept one counts the work of building it") {
  const Scenario s = cacheMobileScenario();
  const RobotModels models(s);
  const CollisionWorld world(s);
  RoadmapCache cache(std::size_t{1} << 28);
  RoadmapSet late(world, models.raw, 300, 10, 1, Deadline(-1.0));
  late.useCache(cache, s);
  CHECK(late.forRobot(0).size() < 300);
  CHECK(cache.size() == 0);
  RoadmapSet in_time(world, models.raw, 300, 10, 1);
  in_time.useCache(cache, s);
  const std::uint64_t before_build = t_work_done;
  CHECK(in_time.forRobot(0).size() == 300);
  const std::uint64_t building = t_work_done - before_build;
  CHECK(building > 0);
  CHECK(in_time.reused() == 0);
  CHECK(cache.size() == 1);
  // Work budgets end where they would have: taking it counts as much.
  RoadmapSet again(world, models.raw, 300, 10, 1);
  again.useCache(cache, s);
  const std::uint64_t before_reuse = t_work_done;
  CHECK(again.forRobot(0).size() == 300);
  CHECK(t_work_done - before_reuse == building);
  CHECK(again.reused() == 1);
}

TEST_CASE("The roadmap cache drops the least recently used roadmaps once past its capacity") {
  const Scenario s = cacheMobileScenario();
  const RobotModels models(s);
  const CollisionWorld world(s);
  Roadmap rm(world, *models.raw[0], 10, 7);
  rm.grow(200);
  RoadmapCache probe(std::size_t{1} << 28);
  probe.put("a", rm.snapshot(), 0);
  const std::size_t one = probe.bytes();
  REQUIRE(one > 200 * 3 * sizeof(double));
  // Room for two (keys of one letter).
  RoadmapCache cache(2 * one + 1);
  cache.put("a", rm.snapshot(), 1);
  cache.put("b", rm.snapshot(), 2);
  REQUIRE(cache.find("a"));  // a is now the most recently used
  cache.put("c", rm.snapshot(), 3);
  CHECK(cache.size() == 2);
  CHECK(cache.bytes() == 2 * one);
  CHECK_FALSE(cache.find("b"));
  REQUIRE(cache.find("a"));
  CHECK(cache.find("a")->work == 1);
  CHECK(cache.find("c")->work == 3);
  // The same key again replaces its entry.
  cache.put("c", rm.snapshot(), 4);
  CHECK(cache.size() == 2);
  CHECK(cache.find("c")->work == 4);
  // One larger than the whole capacity is not kept, and drops nothing.
  RoadmapCache small(one - 1);
  small.put("a", rm.snapshot(), 0);
  CHECK(small.size() == 0);
  CHECK(small.bytes() == 0);
}

TEST_CASE("A roadmap taken from the cache is the one building would have made, whatever the other robots") {
  // Arms c and d have an obstacle or the workspace's edge in reach: their
  // roadmaps are copies of the free space's, whose seed is the roadmap of
  // the arms with nothing in reach where there are any (a), else the
  // first such arm's. d is the third robot both times, with another seed.
  auto cacheArm = [](const std::string& name, geo::Vec2 base) {
    return test::fiveLinkArm(name, base, 0.0, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0});
  };
  Scenario with_free;
  with_free.name = "arms";
  with_free.workspace = {{-4, -4}, {12, 8}};
  with_free.obstacles.push_back(Obstacle::makeBox({7, 1.5}, {1.0, 1.0}));
  with_free.robots = {cacheArm("c", {6, 0}), cacheArm("a", {0, 0}), cacheArm("d", {10.5, 4})};
  Scenario without = with_free;
  without.robots[1] = cacheArm("e", {7.5, 4.5});  // the obstacle in reach too
  RoadmapCache cache(std::size_t{1} << 28);
  for (const Scenario* s : {&with_free, &without}) {
    const RobotModels models(*s);
    const CollisionWorld world(*s);
    RoadmapSet kept(world, models.raw, 300, 10, 1), fresh(world, models.raw, 300, 10, 1);
    kept.useCache(cache, *s);
    for (int r = 0; r < 3; ++r) {
      CAPTURE(r);
      const Roadmap &a = kept.forRobot(r), &b = fresh.forRobot(r);
      REQUIRE(a.size() == b.size());
      for (int v = 0; v < a.size(); ++v) {
        CHECK(std::equal(a.config(v), a.config(v) + 5, b.config(v)));
        CHECK(a.dropped(v) == b.dropped(v));
        CHECK(a.edges(v).size() == b.edges(v).size());
      }
    }
    CHECK(kept.reused() == 0);  // nothing of the first scenario fits the second
  }
}
