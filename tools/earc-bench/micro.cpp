// earc-bench micro: checks per second of the collision layer.
//
//   instant-32      one time instant of 32 box robots (0.6 x 0.4) at random
//                   poses in a 20 x 20 workspace: all 496 pairs through
//                   robotsTouch, as a conflict search does at every instant
//   state-12        CollisionWorld::stateValid of a box robot against 12
//                   random boxes (20 x 20 workspace)
//   state-1000      the same against a 1000-cell grid map (64 x 64, ~25 %
//                   blocked, like a MovingAI random map)
//   broad phase     stateValid per query with the plain AABB loop and with
//                   FCL's tree for growing grid maps: the measurement behind
//                   kTreeMinObstacles in src/collision/collision_world.cpp
//
// Every figure is the median over --repeats batches of random queries,
// timed in process CPU time (std::clock) so that other load on a shared
// machine inflates the figures less than wall time would.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "earc/bench/options.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/collision/collision_world.hpp"
#include "earc/io/input_error.hpp"

namespace earc {
namespace {

struct MicroOptions {
  std::uint64_t seed = 1;
  int repeats = 7;
  double batch_seconds = 0.05;  // long enough to swamp the clock's resolution
};

// Median rate, in operations per second, of `run(iterations)` which performs
// iterations x ops_per_iteration operations.
template <class Run>
double medianRate(const MicroOptions& o, double ops_per_iteration, Run&& run) {
  auto seconds = [&](long n) {
    const std::clock_t t0 = std::clock();
    run(n);
    return static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  };
  long n = 1;
  while (seconds(n) < o.batch_seconds && n < (1L << 40)) n *= 2;
  std::vector<double> rates;
  for (int r = 0; r < o.repeats; ++r) rates.push_back(static_cast<double>(n) * ops_per_iteration / seconds(n));
  std::nth_element(rates.begin(), rates.begin() + static_cast<std::ptrdiff_t>(rates.size() / 2), rates.end());
  return rates[rates.size() / 2];
}

RobotSpec boxRobot(int i) { return RobotSpec::mobileBox("m" + std::to_string(i), {0.6, 0.4}); }

// n random poses inside ws (flat x, y, theta triples).
std::vector<double> randomPoses(std::mt19937_64& rng, const geo::Aabb& ws, std::size_t n) {
  std::uniform_real_distribution<double> x(ws.lo.x, ws.hi.x), y(ws.lo.y, ws.hi.y), th(-std::numbers::pi, std::numbers::pi);
  std::vector<double> q;
  for (std::size_t i = 0; i < n; ++i) q.insert(q.end(), {x(rng), y(rng), th(rng)});
  return q;
}

Scenario randomBoxes(std::mt19937_64& rng, int count) {
  Scenario s;
  s.workspace = {{0, 0}, {20, 20}};
  std::uniform_real_distribution<double> pos(0, 20), size(1, 3), ang(-std::numbers::pi, std::numbers::pi);
  for (int i = 0; i < count; ++i) s.obstacles.push_back(Obstacle::makeBox({pos(rng), pos(rng)}, {size(rng), size(rng)}, ang(rng)));
  return s;
}

// count distinct unit cells of a square grid about 25 % blocked.
Scenario gridMap(std::mt19937_64& rng, int count) {
  const int side = std::max(2, static_cast<int>(std::ceil(std::sqrt(4.0 * count))));
  std::vector<int> cells(static_cast<std::size_t>(side * side));
  for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = static_cast<int>(i);
  std::shuffle(cells.begin(), cells.end(), rng);
  Scenario s;
  s.workspace = {{0, 0}, {static_cast<double>(side), static_cast<double>(side)}};
  for (int i = 0; i < count; ++i) {
    const int cell = cells[static_cast<std::size_t>(i)];
    s.obstacles.push_back(Obstacle::makeBox({cell % side + 0.5, cell / side + 0.5}, {1, 1}));
  }
  return s;
}

volatile long g_sink;  // keeps the measured work from being optimised away

constexpr std::size_t kQueries = 4096;  // distinct random queries cycled through

// stateValid checks per second and the fraction of valid states.
std::pair<double, double> stateRate(const MicroOptions& o, const Scenario& s, CollisionWorld::BroadphaseMode mode,
                                    std::uint64_t seed) {
  const CollisionWorld world(s, mode);
  const auto robot = makeRobotModel(boxRobot(0), s.resolution);
  std::mt19937_64 rng(seed);
  const std::vector<double> q = randomPoses(rng, s.workspace, kQueries);
  long valid = 0;
  for (std::size_t i = 0; i < kQueries; ++i) valid += world.stateValid(*robot, &q[3 * i]);
  const double rate = medianRate(o, 1.0, [&](long n) {
    long v = 0;
    for (long i = 0; i < n; ++i) v += world.stateValid(*robot, &q[3 * (static_cast<std::size_t>(i) % kQueries)]);
    g_sink = v;
  });
  return {rate, static_cast<double>(valid) / kQueries};
}

void row(const char* what, double rate, const char* unit, const char* note) {
  std::printf("%-34s %14.0f %-14s %s\n", what, rate, unit, note);
}

void runMicro(const MicroOptions& o) {
  std::printf("%-34s %14s %-14s %s\n", "measurement", "rate", "unit", "notes");

  {  // (a) one instant of 32 robots, all pairs
    constexpr int kRobots = 32;
    constexpr int kInstants = 256;
    std::vector<std::unique_ptr<RobotModel>> robots;
    for (int i = 0; i < kRobots; ++i) robots.push_back(makeRobotModel(boxRobot(i), {}));
    std::mt19937_64 rng(o.seed);
    const std::vector<double> q = randomPoses(rng, {{0, 0}, {20, 20}}, kRobots * kInstants);
    constexpr double kPairs = kRobots * (kRobots - 1) / 2;
    auto instant = [&](std::size_t k) {
      const double* base = &q[3 * kRobots * k];
      long touching = 0;
      for (int i = 0; i < kRobots; ++i)
        for (int j = i + 1; j < kRobots; ++j) touching += robotsTouch(*robots[static_cast<std::size_t>(i)], base + 3 * i,
                                                                     *robots[static_cast<std::size_t>(j)], base + 3 * j);
      return touching;
    };
    long touching = 0;
    for (std::size_t k = 0; k < kInstants; ++k) touching += instant(k);
    const double rate = medianRate(o, 1.0, [&](long n) {
      long t = 0;
      for (long i = 0; i < n; ++i) t += instant(static_cast<std::size_t>(i) % kInstants);
      g_sink = t;
    });
    char note[96];
    std::snprintf(note, sizeof note, "%.0f robot pairs/s; %.2f touching pairs per instant", rate * kPairs,
                  static_cast<double>(touching) / kInstants);
    row("instant-32 (all pairs)", rate, "instants/s", note);
  }

  std::mt19937_64 rng(o.seed + 1);
  {  // (b) 12 boxes
    const auto [rate, valid] = stateRate(o, randomBoxes(rng, 12), CollisionWorld::BroadphaseMode::Auto, o.seed + 2);
    char note[64];
    std::snprintf(note, sizeof note, "%.0f%% of states valid", 100 * valid);
    row("state-12 (stateValid)", rate, "checks/s", note);
  }
  {  // (c) 1000 grid cells
    const Scenario map = gridMap(rng, 1000);
    for (auto [mode, name] : {std::pair{CollisionWorld::BroadphaseMode::Auto, "state-1000 (stateValid, auto)"},
                              std::pair{CollisionWorld::BroadphaseMode::Loop, "state-1000 (stateValid, loop)"}}) {
      const auto [rate, valid] = stateRate(o, map, mode, o.seed + 3);
      char note[64];
      std::snprintf(note, sizeof note, "%.0f%% of states valid", 100 * valid);
      row(name, rate, "checks/s", note);
    }
  }

  std::printf("\nbroad phase: ns per stateValid on ~25%% blocked grid maps\n%10s %10s %10s\n", "obstacles", "loop", "tree");
  for (int count : {4, 8, 16, 24, 32, 48, 64, 96, 128, 256, 1000, 4000}) {
    const Scenario map = gridMap(rng, count);
    const double loop = stateRate(o, map, CollisionWorld::BroadphaseMode::Loop, o.seed + 4).first;
    const double tree = stateRate(o, map, CollisionWorld::BroadphaseMode::Tree, o.seed + 4).first;
    std::printf("%10d %10.1f %10.1f\n", count, 1e9 / loop, 1e9 / tree);
  }
}

void setupMicro(CLI::App& app) {
  auto opts = std::make_shared<MicroOptions>();
  auto* cmd = app.add_subcommand("micro", "Collision-checking micro benchmark (checks per second, plain text)");
  cmd->add_option("--seed", opts->seed, "Seed for the random poses and obstacles")->check(earc::cli::kWholeNumber)->capture_default_str();
  // 0 batches or 0 seconds would time nothing: "inf checks/s".
  cmd->add_option("--repeats", opts->repeats, "Batches per measurement; the median is reported")
      ->check(earc::cli::kPositiveWholeNumber)
      ->capture_default_str();
  cmd->add_option("--batch-seconds", opts->batch_seconds, "Least duration of one batch")
      ->check(earc::cli::kFinitePositive)
      ->capture_default_str();
  cmd->callback([opts] {
    if (opts->batch_seconds < 0.001)
      throw InputError("", "--batch-seconds", "must be at least 0.001 (a shorter batch may take 0 clock ticks)");
    runMicro(*opts);
  });
}

cli::Registrar registered_micro("earc-bench", "micro", setupMicro);

}  // namespace
}  // namespace earc
