// Collision checking against the static world (workspace and obstacles) and
// between robots, with the contract's semantics: bodies touch when they
// overlap by more than geo::kContactTolerance, and a body may stick out of
// the workspace by at most that much.
//
// Obstacle candidates come from a plain AABB loop for a few obstacles and
// from an FCL broad phase (dynamic AABB tree) for many; every candidate is
// then decided by the exact planar signed distance of geo::, so FCL's own
// contact rule never decides validity. All methods are const and
// thread-safe.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "earc/geometry/shapes.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

struct PlacedBodies;
class ObstacleCells;

// Checks that poll a deadline read the clock once per this many units of
// work, a unit being one coordinate of a robot placed.
inline constexpr std::size_t kWorkPerClockRead = 4096;

class CollisionWorld {
 public:
  // How obstacle candidates are found: Auto picks by obstacle count; Loop and
  // Tree force one, for benchmarks and tests. Every mode gives the same answers.
  enum class BroadphaseMode { Auto, Loop, Tree };

  explicit CollisionWorld(const Scenario& scenario);
  CollisionWorld(const Scenario& scenario, BroadphaseMode mode);
  ~CollisionWorld();
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;

  const geo::Aabb& workspace() const { return workspace_; }
  std::size_t obstacleCount() const { return obstacles_.size(); }
  const geo::Body& obstacle(std::size_t i) const { return obstacles_[i]; }
  // True when obstacle queries go through FCL's tree.
  bool usesTree() const { return broadphase_ != nullptr; }

  // True when the body is inside the workspace and touches no obstacle.
  // Thread-safe.
  bool bodyFree(const geo::Body& body) const;
  // The same for a body whose tight bounds are known.
  bool bodyFree(const geo::Body& body, const geo::Aabb& bounds) const;

  // Indices of the obstacles the body touches, appended to out (ascending).
  void touchedObstacles(const geo::Body& body, std::vector<int>& out) const;

  // A configuration is valid when it respects the joint limits, has no
  // self-collision and every body part is free. Thread-safe.
  bool stateValid(const RobotModel& robot, const double* q) const;
  // The same, leaving the robot's placed bodies in `placed` for further
  // checks of the same configuration (complete only when it returns true).
  bool stateValid(const RobotModel& robot, const double* q, PlacedBodies& placed) const;

  // Whether the straight motion a -> b is valid at every instant (steps and
  // midpoints) at which a solution of it is validated. Thread-safe.
  bool motionValid(const RobotModel& robot, const double* a, const double* b) const;
  // The same, or nothing when `poll`'s deadline expires before the answer
  // is known (each instant counts the robot's dim() units of work).
  std::optional<bool> motionValid(const RobotModel& robot, const double* a, const double* b,
                                  DeadlinePoll& poll) const;

  // Number of invalid instants along a -> b, sampled as in motionValid.
  int countInvalidInstants(const RobotModel& robot, const double* a, const double* b) const;

 private:
  struct Broadphase;
  // Calls visit(i) for each obstacle i whose AABB overlaps box, until visit
  // returns true (stop); returns whether it stopped.
  template <class Visit>
  bool forEachCandidate(const geo::Aabb& box, Visit&& visit) const;
  geo::Aabb workspace_;
  std::vector<geo::Body> obstacles_;
  std::vector<geo::Aabb> obstacle_bounds_;
  std::unique_ptr<Broadphase> broadphase_;
  std::unique_ptr<ObstacleCells> cells_;  // with the tree only
};

// A robot's bodies at one configuration with their bounds: placed once and
// kept by checks that meet the same configuration many times.
struct PlacedBodies {
  std::vector<geo::Body> bodies;
  std::vector<geo::Aabb> bounds;
  void place(const RobotModel& model, const double* q);
  bool empty() const { return bodies.empty(); }
};

// True when two placed robots touch (the exact test on every pair of body
// parts whose bounds overlap; no bounding-disc test).
bool bodiesTouch(const PlacedBodies& a, const PlacedBodies& b);

// True when the robots' bounding discs meet: a necessary condition for
// robotsTouch, and most pairs of an instant fail it.
bool boundingDiscsMeet(const RobotModel& a, const double* qa, const RobotModel& b, const double* qb);

// One robot at one configuration against others in turn: the bounding-disc
// test first, its bodies placed at the first pair that passes it, once for
// all. Not thread-safe (scratch of its own); keeps q, which must outlive it.
class RobotAgainst {
 public:
  enum class Result { Apart, Clear, Touch };  // Apart: bounding discs apart
  void set(const RobotModel& model, const double* q);
  Result check(const RobotModel& other, const double* q_other);

 private:
  const RobotModel* model_ = nullptr;
  const double* q_ = nullptr;
  geo::Vec2 centre_{};
  bool placed_ = false;
  PlacedBodies mine_, theirs_;
};

// True when two robots at configurations qa and qb touch (bounding discs
// first, then the exact test on every pair of body parts).
bool robotsTouch(const RobotModel& a, const double* qa, const RobotModel& b, const double* qb);

// Signed distance between two robots (smallest over their body parts).
double robotDistance(const RobotModel& a, const double* qa, const RobotModel& b, const double* qb);

}  // namespace earc
