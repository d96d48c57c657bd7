// Robot models: what a planner needs to know about one robot's body and
// configuration space. A model is immutable after construction and safe to
// share between threads.
#pragma once

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "earc/geometry/shapes.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/scenario.hpp"

namespace earc {

// Thrown by stepsBetween (and exp::fitResolution) when no int counts the
// steps between two configurations (not a number, or beyond INT_MAX steps).
class NoStepCountError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class RobotModel {
 public:
  virtual ~RobotModel() = default;

  // Configuration dimension (3 for a mobile robot, one per link for an arm).
  virtual int dim() const = 0;

  // Time distance in steps: the least (fractional) number of steps to move
  // straight from a to b within the resolution. A metric; 0 iff the same configuration.
  virtual double distance(const double* a, const double* b) const = 0;

  // Whole number of steps a straight motion from a to b takes: ceil of
  // distance (minus a 1e-9 slack), 0 only when a equals b. Throws
  // NoStepCountError when that is no int.
  int stepsBetween(const double* a, const double* b) const;

  // out = the configuration at fraction s in [0, 1] of the straight motion
  // from a to b (headings along the shortest arc, joints linearly).
  virtual void interpolate(const double* a, const double* b, double s, double* out) const = 0;

  // The robot's body at q, in world coordinates, replacing out's contents:
  // one body for a mobile robot, one capsule per link for an arm.
  virtual void bodies(const double* q, std::vector<geo::Body>& out) const = 0;

  // A box, perhaps not the tightest, holding the robot's bodies at every
  // configuration within [lo, hi]; by default the bounding disc around every centre.
  virtual geo::Aabb boundsWithin(const double* lo, const double* hi) const;

  // True when two non-adjacent links of an arm touch (never for mobile robots).
  virtual bool selfCollides(const double* q) const = 0;
  // The same, decided on the robot's bodies at q (as bodies(q) gives them)
  // and their tight bounds, for callers that have placed them already.
  virtual bool selfCollides(const std::vector<geo::Body>& bodies, const std::vector<geo::Aabb>& bounds) const = 0;

  // True when q respects the joint limits (always for mobile robots).
  virtual bool withinLimits(const double* q) const = 0;

  // Radius of a disc around boundingCenter(q) holding the whole body at any
  // configuration (the centre moves linearly as interpolate moves q). Not
  // virtual: broad phases call it in their innermost loops.
  double boundingRadius() const { return bounding_radius_; }
  geo::Vec2 boundingCenter(const double* q) const { return center_is_position_ ? geo::Vec2{q[0], q[1]} : fixed_center_; }

  // A string that is equal for two robots exactly when their bodies and
  // configuration spaces are the same up to a rigid placement (the base of
  // an arm). Experiences are only ever shared between equal signatures.
  virtual std::string geometrySignature() const = 0;

  // Lower and upper bounds of each configuration coordinate for sampling:
  // mobile x and y from the workspace, heading [-pi, pi]; arm joint limits.
  virtual void samplingBounds(const geo::Aabb& workspace, std::vector<double>& lo,
                              std::vector<double>& hi) const = 0;

  // True for SE(2) robots (the third coordinate is a heading).
  virtual bool isMobile() const = 0;

  const RobotSpec& spec() const { return spec_; }
  const Resolution& resolution() const { return resolution_; }

 protected:
  RobotModel(RobotSpec spec, Resolution res) : spec_(std::move(spec)), resolution_(res) {}
  RobotSpec spec_;
  Resolution resolution_;
  // Set once by each kind's constructor (hypot per call was a fifth of
  // ARC's time): the bounding disc's radius, and its centre, either q's
  // first two coordinates or a fixed point.
  double bounding_radius_ = 0.0;
  bool center_is_position_ = false;
  geo::Vec2 fixed_center_;
};

std::unique_ptr<RobotModel> makeRobotModel(const RobotSpec& spec, const Resolution& res);

// Models for every robot of a scenario, in the scenario's order.
std::vector<std::shared_ptr<const RobotModel>> makeRobotModels(const Scenario& scenario);

// A scenario's models, owned, beside the plain pointers planners take.
struct RobotModels {
  std::vector<std::shared_ptr<const RobotModel>> owned;
  std::vector<const RobotModel*> raw;
  explicit RobotModels(const Scenario& scenario);
};

// Sets the states at the end of `path` that equal its last one up to
// rounding or a turn of 2 pi (by model.distance) to exactly the last one,
// so that dropping trailing waits ends the path where it arrived. Thread-safe.
void settleAtGoal(const RobotModel& model, Path& path);

// Forward kinematics of a planar arm: joint positions (n+1 points, the base
// first) for configuration q.
void armJointPositions(const RobotSpec& arm, const double* q, std::vector<geo::Vec2>& out);

}  // namespace earc
