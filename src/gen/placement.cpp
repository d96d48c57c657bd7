#include "earc/gen/placement.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <queue>

#include "earc/gen/generators.hpp"

namespace earc::gen {

namespace {

// Rejection budget per robot: start candidates, and goal candidates per
// accepted start. A start in a small pocket of free space finds no goal in
// its component quickly, so the budget moves on to another start.
constexpr int kStartAttempts = 2000;
constexpr int kGoalAttempts = 200;

void sampleConfiguration(const std::vector<double>& lo, const std::vector<double>& hi, Random& rng,
                         std::vector<double>& q) {
  q.resize(lo.size());
  for (std::size_t k = 0; k < lo.size(); ++k) q[k] = roundCoordinate(rng.uniform(lo[k], hi[k]));
}

// True when q keeps kClearance from the configurations of every robot
// before `robot` (the same field, start or goal).
bool clearOfEarlier(const std::vector<std::shared_ptr<const RobotModel>>& models, std::size_t robot,
                    const std::vector<std::vector<double>>& placed, const std::vector<double>& q) {
  for (std::size_t j = 0; j < robot; ++j)
    if (robotDistance(*models[robot], q.data(), *models[j], placed[j].data()) <= kClearance) return false;
  return true;
}

}  // namespace

// Adding 0.0 turns -0 into 0, which the JSON would print as "-0.0".
double roundCoordinate(double v) { return std::round(v * 1e4) / 1e4 + 0.0; }

// The free space of a disc robot, cut into 4-connected components on a
// coarse grid. A cell is free when a disc of radius + cell/2 at its centre
// is free, so a disc can move between the centres of adjacent free cells:
// two points with the same component are connected for the disc (the test
// is conservative; it never joins two separated regions).
FreeSpaceGrid::FreeSpaceGrid(const geo::Aabb& workspace, double cell, double radius, DiscFree free)
    : workspace_(workspace), cell_(cell), radius_(radius), free_(std::move(free)) {
  cols_ = static_cast<int>(std::floor((workspace.hi.x - workspace.lo.x) / cell));
  rows_ = static_cast<int>(std::floor((workspace.hi.y - workspace.lo.y) / cell));
  const auto count = static_cast<std::size_t>(std::max(cols_, 0)) * static_cast<std::size_t>(std::max(rows_, 0));
  constexpr int kUnlabelled = -2;
  label_.assign(count, kUnlabelled);
  auto centre = [&](int c, int r) {
    return geo::Vec2{workspace_.lo.x + (c + 0.5) * cell_, workspace_.lo.y + (r + 0.5) * cell_};
  };
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c)
      if (!free_(centre(c, r), radius_ + 0.5 * cell_)) label_[static_cast<std::size_t>(r * cols_ + c)] = -1;
  std::queue<int> frontier;
  for (std::size_t seed = 0; seed < count; ++seed) {
    if (label_[seed] != kUnlabelled) continue;
    label_[seed] = components_;
    frontier.push(static_cast<int>(seed));
    while (!frontier.empty()) {
      const int k = frontier.front();
      frontier.pop();
      const int c = k % cols_, r = k / cols_;
      const int next[4][2] = {{c - 1, r}, {c + 1, r}, {c, r - 1}, {c, r + 1}};
      for (const auto& n : next) {
        if (n[0] < 0 || n[0] >= cols_ || n[1] < 0 || n[1] >= rows_) continue;
        int& l = label_[static_cast<std::size_t>(n[1] * cols_ + n[0])];
        if (l != kUnlabelled) continue;
        l = components_;
        frontier.push(n[1] * cols_ + n[0]);
      }
    }
    ++components_;
  }
}

int FreeSpaceGrid::componentOf(geo::Vec2 p) const {
  const double fc = std::floor((p.x - workspace_.lo.x) / cell_), fr = std::floor((p.y - workspace_.lo.y) / cell_);
  if (!(fc >= 0 && fc < cols_ && fr >= 0 && fr < rows_)) return -1;  // also NaN; before any cast to int
  const int c = static_cast<int>(fc), r = static_cast<int>(fr);
  const int l = label_[static_cast<std::size_t>(r * cols_ + c)];
  if (l < 0) return -1;
  // Every point of the segment from p to the cell centre lies within
  // |p - centre| of p: a disc that large at p covers the straight move.
  const geo::Vec2 centre{workspace_.lo.x + (c + 0.5) * cell_, workspace_.lo.y + (r + 0.5) * cell_};
  return free_(p, radius_ + geo::norm(p - centre)) ? l : -1;
}

bool clearOfWorld(const CollisionWorld& world, const RobotModel& robot, const double* q) {
  if (!robot.withinLimits(q) || robot.selfCollides(q)) return false;
  std::vector<geo::Body> bodies;
  robot.bodies(q, bodies);
  for (geo::Body b : bodies) {
    b.radius += kClearance;
    if (!world.bodyFree(b)) return false;
  }
  return true;
}

// Draws every robot's start and goal from its sampling bounds, in robot
// order, by rejection: clear of the world, kClearance from every earlier
// robot's start (goal), and start and goal in the same region (region may
// be empty: one region). Fills s.robots[i].start and .goal. Returns false
// when a robot found no place within the attempt budget; the caller then
// tries another obstacle layout.
bool placeStartsAndGoals(Scenario& s, const CollisionWorld& world, Random& rng, const RegionOf& region) {
  for (auto& r : s.robots) {  // models may look at the configuration sizes
    r.start.assign(static_cast<std::size_t>(r.dim()), 0.0);
    r.goal = r.start;
  }
  const auto models = makeRobotModels(s);
  std::vector<std::vector<double>> starts(s.robots.size()), goals(s.robots.size());
  std::vector<double> lo, hi, start, goal;
  auto regionOf = [&](const RobotModel& m, const std::vector<double>& q) { return region ? region(m, q.data()) : 0; };
  for (std::size_t i = 0; i < s.robots.size(); ++i) {
    const RobotModel& model = *models[i];
    model.samplingBounds(s.workspace, lo, hi);
    bool placed = false;
    for (int a = 0; a < kStartAttempts && !placed; ++a) {
      sampleConfiguration(lo, hi, rng, start);
      if (!clearOfWorld(world, model, start.data()) || !clearOfEarlier(models, i, starts, start)) continue;
      const int home = regionOf(model, start);
      if (home < 0) continue;
      for (int b = 0; b < kGoalAttempts && !placed; ++b) {
        sampleConfiguration(lo, hi, rng, goal);
        placed = clearOfWorld(world, model, goal.data()) && clearOfEarlier(models, i, goals, goal) &&
                 regionOf(model, goal) == home;
      }
    }
    if (!placed) return false;
    starts[i] = start;
    goals[i] = goal;
  }
  for (std::size_t i = 0; i < s.robots.size(); ++i) {
    s.robots[i].start = starts[i];
    s.robots[i].goal = goals[i];
  }
  return true;
}

// placeStartsAndGoals for mobile robots, each start and goal in one
// component (FreeSpaceGrid, kFreeSpaceCell) of the free space of the
// largest bounding disc among the robots; `free` tests a disc against the
// scenario's workspace and obstacles.
bool placeMobileRobots(Scenario& s, const CollisionWorld& world, const DiscFree& free, Random& rng) {
  double radius = 0.0;
  for (const auto& r : s.robots) radius = std::max(radius, makeRobotModel(r, s.resolution)->boundingRadius());
  const FreeSpaceGrid grid(s.workspace, kFreeSpaceCell, radius, free);
  return placeStartsAndGoals(s, world, rng, [&grid](const RobotModel& robot, const double* q) {
    return grid.componentOf(robot.boundingCenter(q));
  });
}

// Problems of the same kind as `base`: its workspace, obstacles, robots
// and resolution, every robot's start and goal drawn again (as
// placeMobileRobots places them when every robot is mobile, else as
// placeStartsAndGoals does). A function of (base, seed). Throws
// CrowdedError when no placement is found in a few attempts.
Scenario redrawStartsAndGoals(const Scenario& base, std::uint64_t seed) {
  constexpr int kAttempts = 20;
  Scenario s = base;
  const CollisionWorld world(s);
  const bool mobile = std::all_of(s.robots.begin(), s.robots.end(),
                                  [](const RobotSpec& r) { return r.kind == RobotKind::Mobile; });
  auto disc_free = [&world](geo::Vec2 c, double r) { return world.bodyFree(geo::Body::disc(c, r)); };
  Random rng(seed);
  for (int attempt = 0; attempt < kAttempts; ++attempt)
    if (mobile ? placeMobileRobots(s, world, disc_free, rng) : placeStartsAndGoals(s, world, rng, {})) return s;
  throw CrowdedError("could not place the " + std::to_string(s.robots.size()) + " robots of " + base.name +
                     " at new starts and goals in " + std::to_string(kAttempts) + " attempts");
}

}  // namespace earc::gen
