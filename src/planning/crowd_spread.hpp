// Paths that keep out of each other's way, as a guide for PIBT: each robot
// gets a way on the crowd roadmap at most `margin` steps longer than its
// shortest that meets the other robots' ways as seldom as it can (the
// space-utilisation idea of Okumura's LaCAM3). Internal to lacam.cpp.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "earc/planning/crowd_roadmap.hpp"
#include "earc/util/deadline.hpp"

namespace earc::crowd {

class Spread {
 public:
  // Plans the ways, robots in random order by `seed`, again while the
  // meetings drop, until the deadline. Not thread-safe while it builds.
  Spread(const CrowdRoadmap& rm, int margin, const Deadline& deadline, std::uint64_t seed);
  // The vertex robot i's way goes to next from v; -1 when its way has no v.
  // Thread-safe.
  int next(int i, int v) const;
  // Meetings left between the ways (two robots on one vertex at one step,
  // or one on another's goal after it arrived).
  long long meetings() const { return meetings_; }

 private:
  std::vector<std::unordered_map<int, int>> next_;
  long long meetings_ = 0;
};

}  // namespace earc::crowd
