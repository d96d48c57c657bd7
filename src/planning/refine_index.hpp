// The index of every robot's timed path that anytime refinement
// (refine.cpp) checks new paths against. Internal to src/planning.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/geometry/shapes.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc::refine {

// Steps a chunk of the index spans: each robot is bounded over a chunk at
// once, and only robots whose bounds meet are tested instant by instant.
inline constexpr std::size_t kChunkSteps = 16;
inline constexpr std::size_t kChunkInstants = 2 * kChunkSteps;

// Box of the robot's bounding disc over steps [s0, s1] of `path` (past its
// end: its last state).
geo::Aabb boundsOverSteps(const RobotModel& m, const Path& path, std::size_t s0, std::size_t s1);

enum class Check { Clear, Contact, OutOfTime };

// Every robot's timed path indexed for "does this new path of robot r touch
// anyone"; reads `paths` (which must outlive it), a robot's entry taken out
// before its path changes and put back after. Not thread-safe.
class Occupancy {
 public:
  Occupancy(const std::vector<const RobotModel*>& models, const std::vector<Path>& paths, const geo::Aabb& workspace);
  std::size_t steps(std::size_t r) const { return len_[r]; }
  void insert(std::size_t r);
  void remove(std::size_t r);
  // Whether robot r along `p` touches no other robot in the index at
  // instants k0..k1 (half steps, as stateAtInstant counts them); each test
  // counts as work on `poll`, which can end the check (OutOfTime).
  Check clear(std::size_t r, const Path& p, std::size_t k0, std::size_t k1, DeadlinePoll& poll);
  // Whether robot r at q touches no other robot in the index at instant k
  // (as clear does for one state).
  Check clearAt(std::size_t r, const double* q, std::size_t k, DeadlinePoll& poll);
  // The robots other than r whose boxes meet `box` during chunk c (or
  // parked there then), appended to out (unsorted, may repeat).
  void robotsNear(std::size_t r, std::size_t c, const geo::Aabb& box, std::vector<std::size_t>& out);

 private:
  struct Entry {
    std::uint32_t robot;
    geo::Aabb box;
  };
  struct Near {
    std::uint32_t robot;
    bool parked;
  };
  // near_ := the robots other than r that may meet `box` during chunk c;
  // returns the entries looked at.
  std::size_t gatherNear(std::size_t r, std::size_t c, const geo::Aabb& box);
  // Robot r at q against near_ at instant k.
  Check touchesNear(std::size_t r, const double* q, std::size_t k, DeadlinePoll& poll);
  template <class Visit>
  void forCells(const geo::Aabb& box, Visit&& visit);

  const std::vector<const RobotModel*>& models_;
  const std::vector<Path>& paths_;
  std::vector<std::size_t> len_;
  std::vector<char> in_;
  std::vector<geo::Aabb> goal_;
  std::vector<std::vector<Entry>> chunks_;
  geo::Aabb area_;
  double cell_ = 1.0;
  long nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::uint32_t>> grid_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t tick_ = 0;
  std::vector<Near> near_;
  std::vector<double> q_, qo_;
  RobotAgainst against_;
};

}  // namespace earc::refine
