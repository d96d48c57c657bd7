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

// Robots' bodies along their time-stamped paths (one resolution step per
// step), placed once for many checks of another robot's motions against
// them: retiming checks the same steps of the others again for every
// attempt. Entry (w, t, k): robot w at instant k/2 of its step t -> t+1,
// k = 0, 1 or 2, interpolated as robotMotionValid interpolates it. The
// paths must outlive this; tell it when a robot's path changes.
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
  // Once `deadline` has expired, states and motions read as invalid (safe:
  // nothing unchecked is ever called valid). The clock is read here, so
  // that a checker made after its deadline calls everything invalid, and
  // then every kWorkPerClockRead units of work done on the thread (a state
  // being the robots' summed dim()), inside motions and states alike: one
  // motion of thousands of robots, or one state of arms of thousands of
  // links, takes long, and OMPL's planners and path simplifier check
  // thousands more after their own termination condition (a round of
  // simplification however late; repairs sampling near each state). The
  // planner's own checks of its time limit come only between them. (A
  // read per motion would cost the coupled planner on a few small robots
  // some percent.) The deadline must outlive this.
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
  // The same for step t -> t+1 of time-stamped paths, a = the paths at t
  // and b at t + 1 (for every robot but r, the states of along's paths),
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

// Random shortcutting of a composite waypoint sequence: replace the part
// between two waypoints by the straight motion when that motion is valid.
// The waypoints must be valid states (those of a valid path): only the
// motions between them are checked. Stops early at the deadline (the path
// stays valid, only less short).
void shortcutComposite(const CompositeChecker& checker, std::vector<CompositeState>& waypoints, int iterations,
                       std::mt19937_64& rng, const Deadline& deadline = Deadline());

// Shortcuts a waypoint sequence at its two ends: the first waypoint goes
// by one straight motion to the furthest waypoint it reaches, and the
// furthest waypoint from which the last is reached goes straight to it.
// Tried at waypoints geometrically nearer the end, each a quarter nearer
// (last, 3/4, 9/16, ... of the way), the first valid motion kept: a few
// checks each. For a path joined to a start and a goal it was not made
// for, where the detours are. The waypoints must be valid states; returns
// the waypoints removed.
std::size_t shortcutEnds(const CompositeChecker& checker, std::vector<CompositeState>& waypoints);

// Shortens time-stamped paths one robot at a time: robot r goes straight
// from its state at step i to its state at a later step j in the fewest
// steps the resolution allows, and the rest of its path comes that many
// steps earlier. A change is kept when every step and midpoint from i on
// is valid with the other robots where they are at that step (a robot
// whose path has ended waits at its last state). Composite shortcutting
// moves all robots together, so one robot's detour holds up the others;
// this lets each arrive when it can. Ends are kept; paths may come out of
// different lengths (the caller holds them at their ends). Stops early at
// the deadline. The paths must be valid on entry: only the changed robot's
// part of each motion is checked.
void retimeShortcut(const CompositeChecker& checker, std::vector<Path>& paths, int iterations, std::mt19937_64& rng,
                    const Deadline& deadline = Deadline());

}  // namespace earc
