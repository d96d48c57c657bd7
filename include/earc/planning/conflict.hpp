// FindConflict: the earliest instant (a step or the midpoint of a step, as
// the contract validates) at which two robots' time-stamped paths touch.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "earc/geometry/shapes.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

struct Conflict {
  int a = -1;  // scenario robot indices, a < b
  int b = -1;
  double t = 0;  // time step; x.5 for a midpoint
  geo::Vec2 place;
};

// Configuration of a robot at instant k / 2 of its path (odd k: the midpoint
// of steps k/2 and k/2 + 1; past the end: the last state).
void stateAtInstant(const RobotModel& model, const Path& path, std::size_t k, double* out);

// A box holding the robot's bodies at every instant k0..k1 (inclusive, half
// steps) of its path; q, lo and hi are scratch.
geo::Aabb boundsOverInstants(const RobotModel& model, const Path& path, std::size_t k0, std::size_t k1,
                             std::vector<double>& q, std::vector<double>& lo, std::vector<double>& hi);

class ConflictDetector {
 public:
  explicit ConflictDetector(std::vector<const RobotModel*> models);
  // With a deadline (which must outlive this), first() gives up once it has
  // expired, polled every kWorkPerClockRead units of work.
  ConflictDetector(std::vector<const RobotModel*> models, const Deadline& deadline);

  // Earliest conflict among `paths` (nullptr: robot absent) at instants of
  // steps `from` through `to`, only pairs with a `focus` robot when given;
  // nothing either when the deadline expired first (ask interrupted()).
  std::optional<Conflict> first(const std::vector<const Path*>& paths, std::size_t from = 0,
                                std::size_t to = static_cast<std::size_t>(-1),
                                const std::vector<char>* focus = nullptr);

  std::size_t exactTests() const { return exact_tests_; }
  // Whether the last first() gave up at the deadline.
  bool interrupted() const { return interrupted_; }

 private:
  std::vector<const RobotModel*> models_;
  std::vector<geo::Aabb> boxes_;
  std::vector<std::vector<double>> q_;
  std::vector<geo::Body> bodies_;
  static constexpr std::size_t kChunk = 16;  // instants bounded at once
  std::size_t exact_tests_ = 0;
  const Deadline* deadline_ = nullptr;
  bool interrupted_ = false;
};

// All robots' paths as the detector's pointer view.
std::vector<const Path*> pathPointers(const std::vector<Path>& paths);

}  // namespace earc
