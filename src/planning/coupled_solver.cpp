// Composite-space planning with OMPL's RRT-Connect.
//
// Validity is ours, not OMPL's: a composite state is valid when every robot
// is valid against the world and no two robots touch, and a composite
// motion is checked at exactly the instants (steps and midpoints) at which
// timeStampComposite will later place the robots, so the time-stamped
// result is valid by construction. Sampling is ours too (a seeded sampler),
// because OMPL's global seed can only be set once per process.
#include "earc/planning/coupled_solver.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "earc/planning/composite.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/random.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace earc {

namespace {

// Iterations of random shortcutting applied to a found composite path.
constexpr int kShortcutIterations = 60;

struct SpaceLayout {
  std::vector<const RobotModel*> robots;
  std::vector<ConfigBox> bounds;  // sampling bounds per robot
};

void toVectors(const SpaceLayout& layout, const ob::State* s, std::vector<std::vector<double>>& out) {
  const auto* cs = s->as<ob::CompoundState>();
  out.resize(layout.robots.size());
  for (std::size_t r = 0; r < layout.robots.size(); ++r) {
    const RobotModel& m = *layout.robots[r];
    out[r].resize(static_cast<std::size_t>(m.dim()));
    if (m.isMobile()) {
      const auto* se2 = cs->as<ob::SE2StateSpace::StateType>(static_cast<unsigned>(r));
      out[r][0] = se2->getX();
      out[r][1] = se2->getY();
      out[r][2] = se2->getYaw();
    } else {
      const auto* rv = cs->as<ob::RealVectorStateSpace::StateType>(static_cast<unsigned>(r));
      for (int j = 0; j < m.dim(); ++j) out[r][static_cast<std::size_t>(j)] = rv->values[j];
    }
  }
}

void fromVectors(const SpaceLayout& layout, const std::vector<std::vector<double>>& in, ob::State* s) {
  auto* cs = s->as<ob::CompoundState>();
  for (std::size_t r = 0; r < layout.robots.size(); ++r) {
    const RobotModel& m = *layout.robots[r];
    if (m.isMobile()) {
      auto* se2 = cs->as<ob::SE2StateSpace::StateType>(static_cast<unsigned>(r));
      se2->setX(in[r][0]);
      se2->setY(in[r][1]);
      // OMPL's SE(2) space silently rejects headings outside [-pi, pi].
      se2->setYaw(geo::wrapAngle(in[r][2]));
    } else {
      auto* rv = cs->as<ob::RealVectorStateSpace::StateType>(static_cast<unsigned>(r));
      for (int j = 0; j < m.dim(); ++j) rv->values[j] = in[r][static_cast<std::size_t>(j)];
    }
  }
}

// Uniform sampling inside the per-robot bounds from our own seeded engine.
class SeededSampler : public ob::StateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, const SpaceLayout* layout, std::uint64_t seed)
      : ob::StateSampler(space), layout_(layout), rng_(seed) {}
  void sampleUniform(ob::State* state) override {
    buf_.resize(layout_->robots.size());
    for (std::size_t r = 0; r < layout_->robots.size(); ++r) {
      const ConfigBox& b = layout_->bounds[r];
      buf_[r].resize(b.lo.size());
      for (std::size_t j = 0; j < b.lo.size(); ++j) buf_[r][j] = uniform(rng_, b.lo[j], b.hi[j]);
    }
    fromVectors(*layout_, buf_, state);
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    toVectors(*layout_, near, buf_);
    for (std::size_t r = 0; r < layout_->robots.size(); ++r) {
      const ConfigBox& b = layout_->bounds[r];
      for (std::size_t j = 0; j < b.lo.size(); ++j)
        buf_[r][j] = std::clamp(buf_[r][j] + uniform(rng_, -distance, distance), b.lo[j], b.hi[j]);
    }
    fromVectors(*layout_, buf_, state);
  }
  void sampleGaussian(ob::State* state, const ob::State* mean, double stdDev) override {
    sampleUniformNear(state, mean, stdDev);
  }

 private:
  const SpaceLayout* layout_;
  std::mt19937_64 rng_;
  std::vector<std::vector<double>> buf_;
};

class CompositeStateChecker : public ob::StateValidityChecker {
 public:
  CompositeStateChecker(const ob::SpaceInformationPtr& si, const SpaceLayout* layout, const CompositeChecker* checker)
      : ob::StateValidityChecker(si), layout_(layout), checker_(checker) {}
  bool isValid(const ob::State* s) const override {
    std::vector<std::vector<double>> q;
    toVectors(*layout_, s, q);
    return checker_->stateValid(q);
  }

 private:
  const SpaceLayout* layout_;
  const CompositeChecker* checker_;
};

class CompositeMotionChecker : public ob::MotionValidator {
 public:
  CompositeMotionChecker(const ob::SpaceInformationPtr& si, const SpaceLayout* layout, const CompositeChecker* checker)
      : ob::MotionValidator(si), layout_(layout), checker_(checker) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    std::vector<std::vector<double>> a, b;
    toVectors(*layout_, s1, a);
    toVectors(*layout_, s2, b);
    bool ok = checker_->motionValid(a, b);
    if (ok) ++valid_; else ++invalid_;
    return ok;
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    std::vector<std::vector<double>> a, b;
    toVectors(*layout_, s1, a);
    toVectors(*layout_, s2, b);
    double frac = checker_->lastValidFraction(a, b);
    bool ok = frac >= 1.0;
    if (!ok) {
      if (lastValid.first != nullptr) si_->getStateSpace()->interpolate(s1, s2, frac, lastValid.first);
      lastValid.second = frac;
      ++invalid_;
    } else {
      ++valid_;
    }
    return ok;
  }

 private:
  const SpaceLayout* layout_;
  const CompositeChecker* checker_;
};

ob::StateSpacePtr makeSpace(const SpaceLayout& layout) {
  auto space = std::make_shared<ob::CompoundStateSpace>();
  for (std::size_t r = 0; r < layout.robots.size(); ++r) {
    const RobotModel& m = *layout.robots[r];
    const ConfigBox& b = layout.bounds[r];
    if (m.isMobile()) {
      auto se2 = std::make_shared<ob::SE2StateSpace>();
      ob::RealVectorBounds bounds(2);
      for (unsigned j = 0; j < 2; ++j) {
        bounds.setLow(j, b.lo[j]);
        bounds.setHigh(j, b.hi[j]);
      }
      se2->setBounds(bounds);
      space->addSubspace(se2, 1.0);
    } else {
      auto rv = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(m.dim()));
      ob::RealVectorBounds bounds(static_cast<unsigned>(m.dim()));
      for (unsigned j = 0; j < static_cast<unsigned>(m.dim()); ++j) {
        bounds.setLow(j, b.lo[j]);
        bounds.setHigh(j, std::max(b.hi[j], b.lo[j] + 1e-9));
      }
      rv->setBounds(bounds);
      space->addSubspace(rv, 1.0);
    }
  }
  space->lock();
  return space;
}

// Bounds per robot: the query's region when given (widened to contain the
// start and goal), otherwise the robot's whole sampling range.
std::vector<ConfigBox> samplingBoxes(const CollisionWorld& world, const CoupledQuery& q) {
  std::vector<ConfigBox> boxes(q.robots.size());
  for (std::size_t r = 0; r < q.robots.size(); ++r) {
    const RobotModel& m = *q.robots[r];
    ConfigBox full;
    m.samplingBounds(world.workspace(), full.lo, full.hi);
    ConfigBox box = (r < q.region.size() && !q.region[r].lo.empty()) ? q.region[r] : full;
    for (std::size_t j = 0; j < box.lo.size(); ++j) {
      if (m.isMobile() && j == 2) {  // headings are always free
        box.lo[j] = -std::numbers::pi;
        box.hi[j] = std::numbers::pi;
        continue;
      }
      box.lo[j] = std::min({box.lo[j], q.starts[r][j], q.goals[r][j]});
      box.hi[j] = std::max({box.hi[j], q.starts[r][j], q.goals[r][j]});
    }
    boxes[r] = std::move(box);
  }
  return boxes;
}

}  // namespace

LocalSolution timeStampComposite(const std::vector<const RobotModel*>& robots,
                                 const std::vector<std::vector<std::vector<double>>>& waypoints) {
  LocalSolution sol;
  for (const RobotModel* m : robots) sol.paths.emplace_back(m->dim());
  if (waypoints.empty()) return sol;
  for (std::size_t r = 0; r < robots.size(); ++r) sol.paths[r].push(waypoints[0][r].data());
  std::vector<double> q;
  for (std::size_t w = 1; w < waypoints.size(); ++w) {
    int n = compositeSteps(robots, waypoints[w - 1], waypoints[w]);
    for (int k = 1; k <= n; ++k) {
      double s = static_cast<double>(k) / n;
      for (std::size_t r = 0; r < robots.size(); ++r) {
        q.resize(static_cast<std::size_t>(robots[r]->dim()));
        if (k == n)
          q = waypoints[w][r];
        else
          robots[r]->interpolate(waypoints[w - 1][r].data(), waypoints[w][r].data(), s, q.data());
        sol.paths[r].push(q.data());
      }
    }
  }
  return sol;
}

std::optional<LocalSolution> solveCoupled(const CollisionWorld& world, const CoupledQuery& query,
                                          const CoupledSettings& settings, std::uint64_t seed) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  CompositeChecker checker(world, query.robots);
  if (!checker.stateValid(query.starts) || !checker.stateValid(query.goals)) return std::nullopt;
  std::vector<std::vector<std::vector<double>>> waypoints;
  // The straight composite motion is the common answer for small, local
  // subproblems; try it before building any tree.
  if (checker.motionValid(query.starts, query.goals)) {
    waypoints = {query.starts, query.goals};
    return timeStampComposite(query.robots, waypoints);
  }

  SpaceLayout layout{query.robots, samplingBoxes(world, query)};
  ob::StateSpacePtr space = makeSpace(layout);
  std::uint64_t sampler_seed = splitSeed(seed, 0x5eed);
  space->setStateSamplerAllocator([&layout, sampler_seed](const ob::StateSpace* s) -> ob::StateSamplerPtr {
    return std::make_shared<SeededSampler>(s, &layout, sampler_seed);
  });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<CompositeStateChecker>(si, &layout, &checker));
  si->setMotionValidator(std::make_shared<CompositeMotionChecker>(si, &layout, &checker));
  si->setup();

  ob::ScopedState<> start(space), goal(space);
  fromVectors(layout, query.starts, start.get());
  fromVectors(layout, query.goals, goal.get());
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal);
  auto planner = std::make_shared<og::RRTConnect>(si);
  planner->setProblemDefinition(pdef);
  planner->setup();
  // The time limit, or sooner when the process is asked to stop (a signal
  // to `earc-plan serve`, see requestStop in earc/util/deadline.hpp).
  const ob::PlannerTerminationCondition ptc = ob::plannerOrTerminationCondition(
      ob::timedPlannerTerminationCondition(settings.time_limit_s),
      ob::PlannerTerminationCondition([] { return stopRequested(); }));
  ob::PlannerStatus status = planner->solve(ptc);
  if (status != ob::PlannerStatus::EXACT_SOLUTION) return std::nullopt;

  auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
  waypoints.clear();
  for (std::size_t i = 0; i < path->getStateCount(); ++i) {
    std::vector<std::vector<double>> q;
    toVectors(layout, path->getState(i), q);
    waypoints.push_back(std::move(q));
  }
  // OMPL hands back the goal with its wrapped heading; restore the exact
  // query endpoints (equal modulo 2 pi, so motions are unchanged).
  waypoints.front() = query.starts;
  waypoints.back() = query.goals;
  if (settings.simplify) {
    std::mt19937_64 rng(splitSeed(seed, 0x5c07));
    shortcutComposite(checker, waypoints, kShortcutIterations, rng);
  }
  return timeStampComposite(query.robots, waypoints);
}

}  // namespace earc
