// The composite configuration space of a set of robots as an OMPL space:
// one flat vector of every robot's coordinates, with the metric of a
// compound of one SE2StateSpace per mobile robot and one
// RealVectorStateSpace per arm,
// validity and motion checking delegated to our CompositeChecker (motions
// at exactly the instants at which timeStampComposite places the robots,
// so a time-stamped result is valid by construction), sampling from our
// own seeded engine (OMPL's global seed can be set only once per process).
// Used by coupled planning (solveCoupled) and by the Lightning baseline.
#pragma once

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSpace.h>

#include <cstdint>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/subproblem.hpp"
#include "earc/scene/robot_model.hpp"

namespace earc {

// Sampling bounds per robot: region[r] when given (else the robot's whole
// sampling range, RobotModel::samplingBounds), widened to contain every
// state of must_contain; a mobile robot's heading always the whole circle.
std::vector<ConfigBox> compositeBounds(const CollisionWorld& world, const std::vector<const RobotModel*>& robots,
                                       const std::vector<ConfigBox>& region,
                                       const std::vector<CompositeState>& must_contain);

class OmplComposite {
 public:
  // Over the given sampling bounds (see compositeBounds), one per robot of
  // the checker. The checker must outlive this.
  OmplComposite(const CompositeChecker& checker, std::vector<ConfigBox> bounds);

  const ompl::base::StateSpacePtr& space() const { return space_; }
  // Space information with our state validity checker and motion validator
  // (CompositeChecker::stateValid / motionValid, so motions are checked at
  // the instants at which timeStampComposite places the robots). Set up.
  const ompl::base::SpaceInformationPtr& spaceInformation() const { return si_; }

  // OMPL state <-> per-robot configurations. Headings are wrapped into
  // [-pi, pi) on the way in: OMPL's SE(2) bounds reject others silently.
  void toComposite(const ompl::base::State* s, CompositeState& out) const;
  void fromComposite(const CompositeState& q, ompl::base::State* s) const;

  // Samplers allocated while `stream` is current in this thread draw from
  // splitSeed(seed, stream); samplers allocated elsewhere draw from a
  // per-allocation stream of seed. See SeededPlanningStream.
  void setSeed(std::uint64_t seed) { seed_ = seed; }
  std::uint64_t seed() const { return seed_; }

  std::size_t robotCount() const { return checker_.robots().size(); }
  const CompositeChecker& checker() const { return checker_; }

 private:
  const CompositeChecker& checker_;
  std::vector<ConfigBox> bounds_;
  std::vector<unsigned> offsets_;  // of each robot's coordinates in a state
  ompl::base::StateSpacePtr space_;
  ompl::base::SpaceInformationPtr si_;
  std::uint64_t seed_ = 1;
  friend class CompositeSampler;
};

// While alive, state samplers allocated by this thread (in OMPL's solve())
// are seeded from `stream`; set it on the thread that samples (Lightning's
// planners run on OMPL's own threads). Per thread.
class SeededPlanningStream {
 public:
  explicit SeededPlanningStream(std::uint64_t stream);
  ~SeededPlanningStream();
  SeededPlanningStream(const SeededPlanningStream&) = delete;
  SeededPlanningStream& operator=(const SeededPlanningStream&) = delete;

 private:
  bool had_previous_;
  std::uint64_t previous_;
};

}  // namespace earc
