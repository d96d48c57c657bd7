// One robot's way through the others' steps on the crowd roadmap: who
// stands where at every roadmap step, and space-time A* against it. Internal to
// the lattice refinement (lattice_lns.cpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "earc/planning/crowd_roadmap.hpp"
#include "earc/util/deadline.hpp"

namespace earc::lattice {

using VertexPath = std::vector<int>;  // a vertex per roadmap step; then the last, for ever

inline int vertexAt(const VertexPath& p, std::size_t t) { return t < p.size() ? p[t] : p.back(); }

// Grows `rows` of `width` entries to h rows, each new row a copy of the last.
template <class T>
void repeatLastRow(std::vector<T>& rows, std::size_t width, std::size_t h) {
  const std::size_t old = rows.size() / width;
  rows.resize(h * width);
  for (std::size_t t = old; t < h; ++t)
    std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>((old - 1) * width), width,
                rows.begin() + static_cast<std::ptrdiff_t>(t * width));
}

// Who stands where at every step, for the robots whose paths are in, with
// per vertex and step the number of robots near it (a quick all-clear).
// Not thread-safe; refers to `paths`, which the caller keeps current.
class Occupancy {
 public:
  // Puts every robot's path in.
  Occupancy(const CrowdRoadmap& rm, std::vector<VertexPath>& paths);

  void put(int i);
  void remove(int i);
  // Rows kept; the last one holds for ever after.
  std::size_t horizon() const { return rows_; }
  // The robot standing on v at step t; -1 for none.
  int at(int v, std::size_t t) const { return occ_[std::min(t, rows_ - 1) * nv_ + static_cast<std::size_t>(v)]; }
  // Steps until robot k is at its goal for good, by its path.
  std::size_t arrival(int k) const { return paths_[static_cast<std::size_t>(k)].size() - 1; }
  // Whether robot i's step u -> v from step t meets anyone in.
  bool blocked(int i, int u, int v, std::size_t t) const;

 private:
  // A cell from which some lattice step conflicts with a step from a
  // vertex: the vertex there and the conflicting step types (bit b).
  struct Threat {
    int w;
    unsigned mask;
  };
  void grow(std::size_t h);
  void count(int v, std::size_t t, int delta);
  bool blockedOnLattice(int i, int u, int v, int a, std::size_t t) const;
  const CrowdRoadmap& rm_;
  std::vector<VertexPath>& paths_;
  std::size_t nv_ = 0, rows_ = 0;
  std::vector<int> occ_;     // [t * nv + v]: robot or -1
  std::vector<int> nearby_;  // [t * nv + v]: robots on near(v)
  std::vector<signed char> step_;  // [t * nv + v]: the lattice step type of the robot there; -1 off it
  // With every vertex on the lattice: per vertex and step type (5 v + a),
  // threats_[first_[5 v + a] .. first_[5 v + a + 1]).
  std::vector<std::uint32_t> first_;
  std::vector<Threat> threats_;
};

// Sub-levels of f for avoid_goals: steps on others' goals, counted up to this.
inline constexpr int kGoalLevels = 16;

// The searches' open list: node indices in buckets by f, lowest f first,
// last in first out within one (the deeper of equally good nodes, so that a
// search among equally good ways follows one to the goal). Not thread-safe.
class BucketQueue {
 public:
  void clear();
  void push(std::size_t f, int node);
  int pop();  // not when empty
  bool empty() const { return count_ == 0; }

 private:
  std::vector<std::vector<int>> buckets_;
  std::size_t lowest_ = 0, highest_ = 0, count_ = 0;
};

// Space-time A* for robot i (not in occ) to its goal, heuristic x `weight`, arriving for
// good by max_cost (none past max_expansions or the deadline); avoid_goals: ties go to
// the way least on goals of robots not yet arrived. Not thread-safe.
class StepSearch {
 public:
  explicit StepSearch(const CrowdRoadmap& rm) : rm_(rm) {}
  std::optional<VertexPath> search(const Occupancy& occ, int i, const Deadline& deadline, long long max_cost,
                                   std::size_t max_expansions, double weight = 1.0, bool avoid_goals = false);
  long long expansions() const { return expansions_; }

 private:
  const CrowdRoadmap& rm_;
  std::vector<std::uint32_t> closed_;  // per (step, vertex): the search that closed it
  struct Node {
    int v;
    int t;
    int parent;
    int crossed;  // other robots' goals passed before they arrive
  };
  std::vector<Node> nodes_;
  std::vector<int> goal_of_;  // per vertex: the robot whose goal it is, or -1
  BucketQueue open_;
  std::uint32_t stamp_ = 0;
  long long expansions_ = 0;
};

}  // namespace earc::lattice
