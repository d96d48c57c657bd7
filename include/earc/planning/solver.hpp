// ARC's hierarchy of subproblem solvers: an ordered list behind one
// interface, tried in turn for each subproblem (E-ARC puts its database
// solver first).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/plan_stats.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/planning/subproblem.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

// One roadmap per distinct robot body (mobile robots of equal geometry share
// one; an arm has its own), each built on first use; past `deadline` they
// come out short and unchecked. Not thread-safe.
class RoadmapSet {
 public:
  RoadmapSet(const CollisionWorld& world, std::vector<const RobotModel*> models, int samples, int neighbors,
             std::uint64_t seed, const Deadline& deadline = Deadline());
  Roadmap& forRobot(int robot);
  // Grows the robot's roadmap within `box` (Roadmap::growWithin); counted in buildSeconds().
  void growWithin(int robot, const ConfigBox& box);
  int initialSamples(int robot) const;
  std::size_t edgeChecks() const;
  // Vertices of all the roadmaps built, grown ones included.
  std::size_t vertices() const;
  // Roadmaps built so far (each when a robot first needed it), and the
  // seconds spent building and growing them.
  std::size_t built() const;
  double buildSeconds() const { return build_seconds_; }

  // Takes roadmaps from `cache` built for the same world (from `scenario`),
  // geometry, samples, neighbours and seed, and stores those it builds. Call
  // before any roadmap is asked for; `cache` must outlive this set's builds.
  void useCache(RoadmapCache& cache, const Scenario& scenario);
  // Of built(), those taken from the cache.
  std::size_t reused() const { return reused_; }

 private:
  const CollisionWorld& world_;
  std::vector<const RobotModel*> models_;
  int samples_;
  int neighbors_;
  std::uint64_t seed_;
  std::vector<int> slot_;  // robot -> roadmap index
  std::vector<bool> anywhere_;  // per roadmap: an arm's with nothing in reach
  // Per arm geometry of which some arm has something in reach: the
  // roadmap of its joint space with nothing in reach, built once; every
  // roadmap of that geometry starts as a copy of it (see forRobot).
  struct FreeSpace {
    int seed_slot = -1;  // the seed's: the geometry's shared roadmap's, else its first arm's
    std::optional<Roadmap::Snapshot> snapshot;
    bool cut_short = false;  // the deadline stopped its building
  };
  std::map<std::string, FreeSpace> free_;
  // The roadmap of `robot` (slot `slot`), built or copied; `cut_short`:
  // building it saw the deadline.
  std::unique_ptr<Roadmap> buildRoadmap(int robot, int slot, bool& cut_short);
  // The roadmap whose seed `robot`'s comes from: its own, or for an arm
  // the free space's of its geometry (FreeSpace::seed_slot).
  int seedSlot(int robot) const;
  RoadmapCache* cache_ = nullptr;
  std::vector<std::string> cache_keys_;  // per roadmap
  std::size_t reused_ = 0;
  std::vector<std::unique_ptr<Roadmap>> roadmaps_;
  double build_seconds_ = 0.0;
  Deadline deadline_;
};

// Another robot's motion seen as an obstacle: its configuration at local
// instant k (two instants a step) is that of `path` at instant
// 2 * offset + k; past the path's end it waits at its last state.
struct MovingObstacle {
  const RobotModel* model = nullptr;
  const Path* path = nullptr;
  std::size_t offset = 0;
  int robot = -1;
};

struct SolverContext {
  const CollisionWorld& world;
  const std::vector<const RobotModel*>& models;  // all robots of the scenario
  RoadmapSet& roadmaps;
  const std::vector<Path>& paths;                 // the current plan
  const Subproblem& sub;
  Deadline deadline;
  std::uint64_t seed = 0;
  // Multiplies the solvers' own time budgets; ARC raises it as a
  // subproblem keeps failing.
  double budget_scale = 1.0;
  // Plan as if the robots outside the subproblem were not there
  // (nearbyRobots() finds none); they meet the answer as later conflicts.
  bool ignore_others = false;
};

struct SolverOutcome {
  std::optional<LocalSolution> solution;
  std::string how;            // the solver's name, or a refinement ("repair")
  std::int64_t entry = -1;    // database entry used, if any
  double seconds = 0.0;       // time the solver took (set by the hierarchy)
  std::string detail = {};    // why it failed or how it succeeded, for traces
};

class SubproblemSolver {
 public:
  virtual ~SubproblemSolver() = default;
  // Short name for statistics and traces.
  virtual const char* name() const = 0;
  // A local solution of ctx.sub: one path per robot (ctx.sub.robots order),
  // of equal length, local starts to goals, valid at every step and midpoint;
  // an empty outcome when none is found within the budget or ctx.deadline.
  virtual SolverOutcome solve(SolverContext& ctx) = 0;
  // Told when the hierarchy accepted a solution, whichever solver found it.
  virtual void accepted(const SolverContext& /*ctx*/, const LocalSolution& /*sol*/, const SolverOutcome& /*by*/) {}
  // Told once when planning ends (the robot models are still alive): a
  // place to write what was learned and add the solver's own statistics.
  virtual void finish(PlanStats& /*stats*/) {}
};

struct DecoupledSettings {
  double time_budget_s = 0.25;
  std::size_t max_expansions = 60000;  // space-time states expanded per robot
  // And at most this many per step of the search's horizon (0: no such
  // cap), times the hierarchy's budget scale.
  std::size_t expansions_per_horizon_step = 32;
  // Each robot arrives within horizon_windows x the window's steps +
  // horizon_steps (past ARC's last level, that times the hierarchy's
  // budget scale, up to the long horizon below).
  double horizon_windows = 1.0;
  std::size_t horizon_steps = 50;
  // The long horizon: the whole-problem prioritized baseline's, whose one
  // window is the plan.
  static constexpr double kLongHorizonWindows = 4;
  static constexpr std::size_t kLongHorizonSteps = 100;
  int connect_neighbors = 10;
  int max_orders = 4;                   // priority orders tried
  bool avoid_others = true;             // treat robots outside the subproblem as moving obstacles
  // The space-time search's heuristic: each vertex's distance to the goal
  // over the roadmap (see spaceTimeSearch) instead of in a straight line.
  bool graph_heuristic = true;
  // Before an order that may push a robot parked at its goal, plan the
  // others around the parked robots over their whole roadmaps, once.
  bool parked_detour = false;
};

// Prioritized planning in space-time over the robots' roadmaps, waiting
// allowed, in the order listed, then in nextPriorityOrder's orders up to
// max_orders. Not thread-safe.
class DecoupledSolver : public SubproblemSolver {
 public:
  explicit DecoupledSolver(DecoupledSettings s = {}) : settings_(s) {}
  const char* name() const override { return "decoupled"; }
  SolverOutcome solve(SolverContext& ctx) override;

 private:
  DecoupledSettings settings_;
};

// The order to try after `tried` (whose last failed at robot index `failed`):
// that order with the robot moved to the front; if tried, an untried one at
// random; empty once every order was tried.
std::vector<std::size_t> nextPriorityOrder(const std::vector<std::vector<std::size_t>>& tried, std::size_t failed,
                                           std::mt19937_64& rng);

struct CoupledSolverSettings {
  double time_budget_s = 0.5;
  // First plan the robots not parked at their goals, the parked ones held
  // as obstacles, on a quarter of the budget.
  bool parked_held = false;
};

// OMPL RRT-Connect in the composite space of the subproblem's robots,
// restricted to the subproblem's region. Not thread-safe.
class CoupledSubproblemSolver : public SubproblemSolver {
 public:
  explicit CoupledSubproblemSolver(CoupledSolverSettings s = {}) : settings_(s) {}
  const char* name() const override { return "coupled"; }
  SolverOutcome solve(SolverContext& ctx) override;

 private:
  // The answer with the mobile robots parked at their goals kept there;
  // nothing when there are none, or no other robots, or none was found.
  std::optional<LocalSolution> solveAroundParked(const SolverContext& ctx) const;
  CoupledSolverSettings settings_;
};

// How a search ended. NoWay: no arrival by the horizon among these
// obstacles (so none among more either); Capped, OutOfTime: it stopped at
// max_expansions or the deadline before it could tell.
enum class SearchEnd { Found, NoWay, Capped, OutOfTime };
const char* searchEndName(SearchEnd end);

// Space-time A* for one robot from `start` at local time 0 to `goal` by step
// `horizon`, avoiding `obstacles`, then free to wait there through
// `hold_until`; nullopt when none is found (why in `end`, when given).
std::optional<Path> spaceTimeSearch(QueryGraph& graph, int start, int goal,
                                    const std::vector<MovingObstacle>& obstacles, std::size_t horizon,
                                    std::size_t hold_until, const Deadline& deadline, std::size_t max_expansions,
                                    bool graph_heuristic = false, SearchEnd* end = nullptr);

// Robots outside the subproblem whose motion during local steps
// [0, span] may come near the subproblem's region, as moving obstacles;
// none when the context says to ignore them.
std::vector<MovingObstacle> nearbyRobots(const SolverContext& ctx, std::size_t span);

// True when `local` (a time-stamped path of `model`, local step 0 being
// the subproblem's t_start) touches none of the moving obstacles at any
// step or midpoint, counting the obstacles' waits at their path ends.
bool clearOfMoving(const RobotModel& model, const Path& local, const std::vector<MovingObstacle>& obstacles);

}  // namespace earc
