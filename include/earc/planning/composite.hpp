// Validity in the composite space of a few robots: every robot valid
// against the world, and no two of them touching.
#pragma once

#include <atomic>
#include <random>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

using CompositeState = std::vector<std::vector<double>>;  // [robot][coordinate]

// The composite state of time-stamped paths at step t (a path that has
// ended answers its last state: the robot waits there).
CompositeState stateAt(const std::vector<Path>& paths, std::size_t t);

// Steps a straight composite motion takes: the most any robot needs, so
// that all robots move together and arrive at once.
int compositeSteps(const std::vector<const RobotModel*>& robots, const CompositeState& a, const CompositeState& b);

// What a caller of CompositeChecker's motion checks already knows to be
// valid, so that it is not checked again. The answer is the same whenever
// what the caller claims is true.
struct KnownValid {
  bool start = false;  // the state a itself (every robot), e.g. as the end of the motion before
  bool end = false;    // the state b itself (every robot), e.g. a waypoint of a valid path
  bool world = false;  // robotMotionValid only: robot r's own motion against the world
};

// Robots' bodies along their time-stamped paths, placed once for many checks
// of another robot's motions against them. The paths must outlive this; tell
// it when a robot's path changes. Not thread-safe.
class BodiesAlongPaths {
 public:
  BodiesAlongPaths(const std::vector<const RobotModel*>& robots, const std::vector<Path>& paths)
      : robots_(robots), paths_(paths), placed_(paths.size()) {}
  const PlacedBodies& at(std::size_t w, std::size_t t, int k);
  // Robot w's path changed from step t on.
  void forget(std::size_t w, std::size_t t);

 private:
  const std::vector<const RobotModel*>& robots_;
  const std::vector<Path>& paths_;
  std::vector<std::vector<PlacedBodies>> placed_;  // [w][2 t + k], empty until placed (as MotionGuard's)
  std::vector<double> q_;
};

class CompositeChecker {
 public:
  CompositeChecker(const CollisionWorld& world, std::vector<const RobotModel*> robots)
      : world_(world), robots_(std::move(robots)) {
    for (const RobotModel* m : robots_) work_per_instant_ += static_cast<std::size_t>(m->dim());
  }
  // Once `deadline` (which must outlive this) has expired, states and motions
  // read as invalid; the clock is read here and every kWorkPerClockRead
  // units of work on the thread.
  CompositeChecker(const CollisionWorld& world, std::vector<const RobotModel*> robots, const Deadline& deadline)
      : CompositeChecker(world, std::move(robots)) {
    deadline_ = &deadline;
    expired_.store(deadline.expired(), std::memory_order_relaxed);
  }

  // Every robot valid and no pair touching.
  bool stateValid(const CompositeState& q) const;
  // Valid at every instant k/(2n), k = 0..2n, n = compositeSteps(a, b): the
  // steps and midpoints of the time-stamped motion.
  bool motionValid(const CompositeState& a, const CompositeState& b, KnownValid known = {}) const;
  // Fraction of a -> b before the first invalid instant (1 when valid; 0
  // once the deadline, if any, has expired).
  double lastValidFraction(const CompositeState& a, const CompositeState& b, KnownValid known = {}) const;
  // Robot r's part of the motion a -> b (one state per robot): r valid and
  // touching no other robot at each instant motionValid checks. When the
  // other robots' part is known valid, the same answer as motionValid.
  bool robotMotionValid(std::size_t r, const std::vector<const double*>& a, const std::vector<const double*>& b,
                        KnownValid known = {}) const;
  // The same for step t -> t+1 of time-stamped paths (a at t, b at t + 1),
  // the other robots' bodies taken from `along` when the step is one
  // resolution step.
  bool robotStepValid(std::size_t r, const std::vector<const double*>& a, const std::vector<const double*>& b,
                      KnownValid known, BodiesAlongPaths& along, std::size_t t) const;

  const std::vector<const RobotModel*>& robots() const { return robots_; }
  // Whether the deadline, if any, has expired (reads the clock unless a
  // check has already found it so).
  bool outOfTime() const;

 private:
  bool robotMotionValid(std::size_t r, const std::vector<const double*>& a, const std::vector<const double*>& b,
                        KnownValid known, BodiesAlongPaths* along, std::size_t t) const;
  bool instantValid(const CompositeState& a, const CompositeState& b, double s, CompositeState& scratch) const;
  // lastValidFraction, or (earliest false) 0 as soon as any instant fails.
  double lastValidFraction(const CompositeState& a, const CompositeState& b, KnownValid known, bool earliest) const;
  const CollisionWorld& world_;
  std::vector<const RobotModel*> robots_;
  // Counts `work` done on this thread; whether the deadline has expired,
  // read every kWorkPerClockRead units (a plain check per state would
  // cost a small robot's planner a few percent).
  bool outOfTimeAfter(std::size_t work) const;
  // stateValid without the deadline.
  bool checkState(const CompositeState& q) const;
  const Deadline* deadline_ = nullptr;
  std::size_t work_per_instant_ = 0;
  mutable std::atomic<bool> expired_{false};  // once seen; planners check from several threads
};

// Random shortcutting of a composite waypoint sequence of valid states: a
// part between two waypoints becomes the straight motion where that is valid.
// Stops early at the deadline (the path stays valid, only less short).
void shortcutComposite(const CompositeChecker& checker, std::vector<CompositeState>& waypoints, int iterations,
                       std::mt19937_64& rng, const Deadline& deadline = Deadline());

// Shortcuts a sequence of valid waypoints at its two ends: the first goes
// straight to the furthest waypoint it reaches, and into the last from the
// furthest that reaches it. Returns the waypoints removed.
std::size_t shortcutEnds(const CompositeChecker& checker, std::vector<CompositeState>& waypoints);

// Shortens valid time-stamped paths one robot at a time (a straight motion
// between two of its states, the rest earlier), keeping ends and validity;
// paths may come out of different lengths. Stops early at the deadline.
void retimeShortcut(const CompositeChecker& checker, std::vector<Path>& paths, int iterations, std::mt19937_64& rng,
                    const Deadline& deadline = Deadline());

}  // namespace earc
