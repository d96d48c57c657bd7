// The lattice refinement with diagonal steps on a grid map's cells: time in
// ticks of half a roadmap step (an axis move takes 2 ticks, a diagonal 3,
// a wait 1), who is where at every tick, and space-time A* against it.
// Internal to the lattice refinement (lattice_lns.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "earc/planning/crowd_roadmap.hpp"
#include "earc/util/deadline.hpp"
#include "lattice_search.hpp"

namespace earc::ticks {

// A vertex per tick where the robot stands on one, -1 while it moves between
// two; then the last vertex, for ever.
using TickPath = std::vector<int>;

inline int vertexAt(const TickPath& p, std::size_t t) { return t < p.size() ? p[t] : p.back(); }

// Move types: 0 wait, 1-4 the axis moves (+x, -x, +y, -y), 5-8 the diagonals.
inline constexpr int kMoveTypes = 9;
// Ticks a move of type a takes.
inline constexpr int ticksOf(int a) { return a == 0 ? 1 : (a <= 4 ? 2 : 3); }

// The roadmap's lattice with diagonals, the robots' distances in ticks, and
// the conflict table of one tick of two moves. Immutable once built.
class Lattice {
 public:
  // Nothing when the roadmap cannot take ticks (off a grid map, a robot off
  // the lattice, an odd stepsPerEdge, or discs so small that the occupancy's
  // one robot per slot would not hold).
  static std::optional<Lattice> make(const CrowdRoadmap& rm);

  const CrowdRoadmap& roadmap() const { return *rm_; }
  // Ticks from v to robot i's goal; CrowdRoadmap::kUnreachable for none.
  int distance(int i, int v) const { return dist_[goal_slot_[static_cast<std::size_t>(i)]][static_cast<std::size_t>(v)]; }
  // The moves out of v other than the wait: (vertex, type).
  const std::vector<std::pair<int, int>>& moves(int v) const { return moves_[static_cast<std::size_t>(v)]; }
  // The move type of u -> v (0 for u == v); -1 when it is not a move.
  int moveType(int u, int v) const;
  // Time steps per tick.
  int stepsPerTick() const { return rm_->stepsPerEdge() / 2; }

  // One tick's state of a robot: a move's type and how many ticks of it are
  // done (21 states); its place in the occupancy's grid of half cells.
  static int state(int a, int phase);
  std::size_t slot(int v, int state) const {
    return vslot_[static_cast<std::size_t>(v)] + static_cast<std::size_t>(soff_[static_cast<std::size_t>(state)]);
  }
  std::size_t slotCount() const { return static_cast<std::size_t>(slot_w_) * static_cast<std::size_t>(slot_h_); }
  // Where a robot's tick in state A meets one in state B (bit B + 1 of
  // mask; bit 0 clear) `delta` slots away, with closest approach under 2R
  // (exact, continuous).
  struct Threat {
    std::int32_t delta;
    std::uint32_t mask;
  };
  const std::vector<Threat>& threats(int state) const { return threats_[static_cast<std::size_t>(state)]; }
  // Whether a tick in state A from vertex u and one in state B from w meet.
  bool meet(int u, int a_state, int w, int b_state) const;

 private:
  explicit Lattice(const CrowdRoadmap& rm) : rm_(&rm) {}
  const CrowdRoadmap* rm_;
  std::vector<std::vector<std::pair<int, int>>> moves_;
  std::vector<std::vector<int>> dist_;  // per distinct goal, per vertex
  std::vector<std::size_t> goal_slot_;  // per robot: its row of dist_
  geo::Vec2 origin_;  // the lowest vertex coordinates: slot (pad, pad)
  int slot_w_ = 0, slot_h_ = 0, pad_ = 0;
  std::vector<std::vector<Threat>> threats_;
  std::vector<std::size_t> vslot_;  // per vertex: its slot in state 0
  std::array<std::ptrdiff_t, 21> soff_{};  // per state: its slot's offset from the vertex's
};

// Who is where at every tick, for the robots whose paths are in: at most one
// robot per half-cell slot and tick (2R > sqrt(2)/3 makes two in one
// conflict). Not thread-safe; refers to `paths`, which the caller keeps current.
class Occupancy {
 public:
  Occupancy(const Lattice& lat, std::vector<TickPath>& paths);
  void put(int i);
  void remove(int i);
  std::size_t horizon() const { return rows_; }
  // The robot standing on v at tick t; -1 for none.
  int at(int v, std::size_t t) const;
  // Ticks until robot k is at its goal for good, by its path.
  std::size_t arrival(int k) const { return paths_[static_cast<std::size_t>(k)].size() - 1; }
  // Whether robot i's move of type a from u, begun at tick t, meets anyone in.
  bool blocked(int i, int u, int a, std::size_t t) const;

 private:
  template <class F>
  void forEachTick(const TickPath& p, F f) const;
  void grow(std::size_t h);
  const Lattice& lat_;
  std::vector<TickPath>& paths_;
  std::size_t ns_ = 0, rows_ = 0;
  std::vector<int> occ_;             // [t * ns + slot]: robot or -1
  std::vector<std::uint8_t> state_;  // [t * ns + slot]: its state + 1; 0 for none
};

// Space-time A* in ticks for robot i (not in occ) to its goal, heuristic
// times `weight`, arriving for good by tick max_cost; nothing when there is
// none, after max_expansions or past the deadline; avoid_goals as StepSearch's.
class TickSearch {
 public:
  explicit TickSearch(const Lattice& lat) : lat_(lat) {}
  std::optional<TickPath> search(const Occupancy& occ, int i, const Deadline& deadline, long long max_cost,
                                 std::size_t max_expansions, double weight = 1.0, bool avoid_goals = false);
  long long expansions() const { return expansions_; }

 private:
  const Lattice& lat_;
  std::vector<std::uint32_t> closed_;  // per (tick, vertex): the search that closed it
  struct Node {
    int v;
    int t;
    int parent;
    int a;  // the move type from the parent
    int crossed;  // other robots' goals passed before they arrive
  };
  std::vector<Node> nodes_;
  std::vector<int> goal_of_;  // per vertex: the robot whose goal it is, or -1
  lattice::BucketQueue open_;
  std::uint32_t stamp_ = 0;
  long long expansions_ = 0;
};

}  // namespace earc::ticks
