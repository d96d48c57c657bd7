// The database builder stores what it promises: valid solutions of small
// conflicting subproblems, for every class of the layout.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "earc/experience/rows.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/gen/generators.hpp"
#include "earc/methods/builder.hpp"
#include "earc/validate/validator.hpp"

using namespace earc;
using namespace earc::exp;

namespace {

std::vector<Experience> allRows(ExperienceStore& store) {
  Statement s = store.connection().prepare(selectExperiencesSql(store.schemaVersion()) + " ORDER BY id");
  std::vector<Experience> out;
  while (s.step()) out.push_back(readExperience(s));
  return out;
}

// The stored paths as a solution of the canonical subproblem they solve.
ValidationReport validateStored(const Experience& e, std::vector<RobotSpec> robots, geo::Aabb workspace) {
  Scenario sc;
  sc.name = "stored";
  sc.workspace = workspace;
  Solution sol;
  sol.scenario = sc.name;
  sol.solved = true;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const Path& p = e.paths[r];
    robots[r].name = std::to_string(r) + "-robot";
    robots[r].start.assign(p.at(0), p.at(0) + p.dim());
    robots[r].goal.assign(p.back(), p.back() + p.dim());
    sol.paths.push_back(p);
  }
  sc.robots = robots;
  return validateSolution(sc, sol);
}

// A stored mobile experience, every robot `robot`, checked as a solution in
// a workspace `margin` around its paths.
void checkStoredMobileValid(const Experience& e, const RobotSpec& robot, double margin) {
  geo::Aabb box;
  for (const Path& p : e.paths)
    for (std::size_t t = 0; t < p.size(); ++t) box.expand({{p.at(t)[0], p.at(t)[1]}, {p.at(t)[0], p.at(t)[1]}});
  auto report = validateStored(e, std::vector<RobotSpec>(e.paths.size(), robot), box.inflated(margin));
  CHECK_MESSAGE(report.valid, (report.violations.empty() ? "" : report.violations.front().detail));
}

RobotSpec builderDisc(double radius) {
  RobotSpec disc;
  disc.kind = RobotKind::Mobile;
  disc.shape = MobileShape::Disc;
  disc.radius = radius;
  return disc;
}

std::vector<RobotSpec> generatedArms() {
  gen::ArmSettings a;
  a.robots = 4;
  return gen::generateArms(a).robots;
}

}  // namespace

TEST_CASE("the generated arm layout yields the facing and neighbouring classes, not far diagonals") {
  auto pairs = armPairClasses(generatedArms(), Resolution{});
  CHECK(pairs.size() == 2);
}

TEST_CASE("built mobile experiences are valid solutions of conflicting subproblems") {
  // The default mix of 2, 3 and 4 robots, and 4 robots alone: four robots
  // as close together as two (spread_per_robot 0) found a conflicting
  // query in 12 of these 30 problems.
  struct Case {
    const char* name;
    std::vector<double> mix;
    int count;
    unsigned seed;
    int max_no_query;
  };
  for (const Case& c : {Case{"default mix", {0.5, 0.3, 0.2}, 12, 4, 1}, Case{"four robots", {0, 0, 1}, 30, 5, 3}}) {
    SUBCASE(c.name) {
      ScratchDirectory dir("builder");
      ExperienceStore store(dir.file("m.db"));
      BuildSettings s;
      s.count = c.count;
      s.seed = c.seed;
      s.mobile_mix = c.mix;
      BuildReport r = buildDatabase(store, s);
      CHECK(r.problems == c.count);
      CHECK(r.no_query <= c.max_no_query);
      CHECK(r.inserted == r.solved - r.duplicates);
      CHECK(r.inserted >= c.count - c.max_no_query - 1);
      RobotSpec robot;
      robot.shape = MobileShape::Box;
      robot.box_size = gen::MobileFootprint{}.box_size;
      for (const Experience& e : allRows(store)) {
        CAPTURE(e.id);
        if (c.mix.front() == 0) CHECK(e.paths.size() == 4);
        checkStoredMobileValid(e, robot, 1.0);
        CHECK(e.source == Source::Build);
        CHECK(e.solve_time_s > 0);
        // A conflict: the straight motion was not already valid, so the
        // paths are not straight lines of equal length... at least one
        // bends or waits.
        CHECK(e.paths.front().size() > 2);
      }
    }
  }
}

TEST_CASE("drawn mobile queries: some robots rest, the others pass by the conflict point") {
  // ARC's subproblems have robots that wait while others pass, and robots
  // that pass beside the conflict point rather than through it: the
  // database is drawn alike (QuerySampling).
  const QuerySampling s;
  std::mt19937_64 rng(7);
  int robots = 0, resting = 0, beside = 0;
  for (int i = 0; i < 2000; ++i) {
    const Query q = sampleMobileQuery(2, rng, s);
    REQUIRE(q.starts.size() == 2);
    for (std::size_t r = 0; r < 2; ++r) {
      ++robots;
      const auto& a = q.starts[r];
      const auto& b = q.goals[r];
      if (a == b) {
        ++resting;
        CHECK(std::hypot(a[0], a[1]) <= s.rest_radius + 1e-12);
        continue;
      }
      const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
      CHECK(len <= 2 * s.max_travel + 1e-12);
      CHECK(len >= 2 * s.min_travel - 1e-12);
      CHECK(std::abs(geo::wrapAngle(b[2] - a[2])) <= s.max_heading_change + 1e-12);
      // The straight motion passes within pass_offset of the conflict point.
      const double along = std::clamp(-(a[0] * dx + a[1] * dy) / (len * len), 0.0, 1.0);
      const double miss = std::hypot(a[0] + along * dx, a[1] + along * dy);
      CHECK(miss <= s.pass_offset + 1e-9);
      beside += miss > 0.25;
    }
  }
  CHECK(resting > robots / 10);
  CHECK(resting < robots / 5);
  CHECK(beside > robots / 5);
}

TEST_CASE("built arm experiences are valid solutions for their base transform class") {
  ScratchDirectory dir("builder");
  ExperienceStore store(dir.file("a.db"));
  BuildSettings s;
  s.kind = RobotKind::Manipulator;
  s.count = 8;
  BuildReport r = buildDatabase(store, s);
  CHECK(r.inserted_per_class.size() == 2);
  const auto arms = generatedArms();
  const auto pairs = armPairClasses(arms, Resolution{});
  gen::ArmSettings a;
  a.robots = 4;
  const geo::Aabb workspace = gen::generateArms(a).workspace;
  int checked = 0;
  for (const Experience& e : allRows(store)) {
    for (auto [i, j] : pairs) {
      std::vector<RobotSpec> pair{arms[static_cast<std::size_t>(i)], arms[static_cast<std::size_t>(j)]};
      auto models = makeRobotModels(Scenario{"", workspace, {}, {}, pair});
      RelativeTransform t = relativeBaseTransform(traitsOf(*models[0]), traitsOf(*models[1]));
      if (baseClassString(t.dx, t.dy, t.dtheta) != e.cls.base_class) continue;
      auto report = validateStored(e, pair, workspace);
      CHECK_MESSAGE(report.valid, (report.violations.empty() ? "" : report.violations.front().detail));
      ++checked;
    }
  }
  CHECK(checked == r.inserted);
}

TEST_CASE("the builder finds conflicting queries for robots larger than the default footprint") {
  // Start and goal distances made for the 0.6 x 0.4 box put 0.8-radius
  // discs on top of each other: 77 entries of 5,000 problems.
  ScratchDirectory dir("builder-large");
  ExperienceStore store(dir.file("large.db"));
  BuildSettings s;
  s.count = 40;
  s.seed = 2;
  const RobotSpec disc = builderDisc(0.8);
  s.mobile_robots = {disc};
  const BuildReport r = buildDatabase(store, s);
  CHECK(r.problems == 40);
  CHECK(r.no_query <= 12);
  CHECK(r.inserted >= 20);
  for (const Experience& e : allRows(store)) {
    CAPTURE(e.id);
    checkStoredMobileValid(e, disc, 2.0);
  }
}

TEST_CASE("a fleet of two footprints gets mixed groups, in proportion to its robots") {
  // A user's warehouse of several footprints: its conflicts are between
  // robots of different footprints, and so must its database's problems be.
  ScratchDirectory dir("builder-mixed");
  ExperienceStore store(dir.file("mixed.db"));
  BuildSettings s;
  s.count = 80;
  s.seed = 3;
  const RobotSpec disc = builderDisc(0.3);
  RobotSpec box;
  box.kind = RobotKind::Mobile;
  box.shape = MobileShape::Box;
  box.box_size = {0.8, 0.5};
  s.mobile_robots = {disc, box};
  s.mobile_shares = {3, 1};  // three discs to each box
  const BuildReport r = buildDatabase(store, s);
  REQUIRE(r.inserted >= 60);
  const std::string disc_sig = makeRobotModel(disc, s.resolution)->geometrySignature();
  const std::string box_sig = makeRobotModel(box, s.resolution)->geometrySignature();
  int mixed = 0;
  std::size_t discs = 0, boxes = 0;
  for (const Experience& e : allRows(store)) {
    CAPTURE(e.cls.signature);
    // Each canonical robot's footprint, from the class signature.
    std::vector<RobotSpec> robots;
    std::stringstream parts(e.cls.signature);
    for (std::string part; std::getline(parts, part, '|');) {
      REQUIRE((part == disc_sig || part == box_sig));
      robots.push_back(part == disc_sig ? disc : box);
    }
    REQUIRE(robots.size() == e.paths.size());
    const auto n_disc = static_cast<std::size_t>(std::count_if(
        robots.begin(), robots.end(), [](const RobotSpec& x) { return x.shape == MobileShape::Disc; }));
    discs += n_disc;
    boxes += robots.size() - n_disc;
    mixed += n_disc > 0 && n_disc < robots.size();
    geo::Aabb bounds;
    for (const Path& p : e.paths)
      for (std::size_t t = 0; t < p.size(); ++t) bounds.expand({{p.at(t)[0], p.at(t)[1]}, {p.at(t)[0], p.at(t)[1]}});
    const auto report = validateStored(e, robots, bounds.inflated(2.0));
    CHECK_MESSAGE(report.valid, (report.violations.empty() ? "" : report.violations.front().detail));
  }
  // Robots drawn 3:1: of 80 problems most have a disc and a box together.
  CHECK(mixed >= r.inserted / 3);
  CHECK(discs > 2 * boxes);
}
