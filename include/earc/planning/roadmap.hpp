// Probabilistic roadmaps in one robot's own configuration space (a PRM
// variant: k-nearest connections, edges validated lazily the first time a
// search wants them and cached), shared by every robot with the same
// geometry in the same environment.
#pragma once

#include <cstdint>
#include <list>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/subproblem.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/kdtree.hpp"

namespace earc {

class Roadmap {
 public:
  struct Edge {
    int to;
    int steps;  // time steps of the straight motion
    int id;     // index into the validity cache
  };

  // `deadline` is the plan's (not a solver's shorter budget): once it has
  // expired, growing stops early and edges are no longer checked.
  Roadmap(const CollisionWorld& world, const RobotModel& model, int neighbors, std::uint64_t seed,
          const Deadline& deadline = Deadline());

  // A roadmap's state apart from its world, robot and deadline: restored for
  // a world and robot of the same contents, it is the roadmap it was taken
  // from, random engine and edge checks included.
  struct Snapshot {
    int neighbors = 0;
    std::mt19937_64 rng;
    std::vector<double> configs;
    std::vector<std::vector<Edge>> adjacency;
    std::vector<std::pair<int, int>> edge_ends;
    std::vector<std::int8_t> edge_state;
    PointIndex index{0};
    std::size_t edge_checks = 0;
    std::vector<bool> dropped;
    std::vector<int> candidates;
  };
  Snapshot snapshot() const;
  Roadmap(const CollisionWorld& world, const RobotModel& model, const Snapshot& snapshot,
          const Deadline& deadline = Deadline());

  // Adds `samples` valid configurations (within `within` where given) and
  // connects each to its k nearest vertices, edges unchecked. Stops early,
  // leaving fewer vertices or some unconnected, once the deadline expired.
  void grow(int samples, const ConfigBox* within = nullptr);

  // Drops the vertices not valid in this world (for a roadmap copied from
  // another world) and rejoins those that lost neighbours; stops once the
  // deadline expires. Returns how many vertices it dropped.
  int dropInvalidVertices();
  bool dropped(int v) const { return static_cast<std::size_t>(v) < dropped_.size() && dropped_[static_cast<std::size_t>(v)]; }
  bool droppedAny() const { return !dropped_.empty(); }
  // Before the first grow: keep each vertex's 2k nearest, so that copies
  // whose vertices are dropped join the rest without a search.
  void keepCandidates() { keep_candidates_ = true; }

  // The box to grow the roadmap in around a cut-off part's configurations
  // (`configs`, one after another), widened a little; the sampling bounds
  // when `configs` is empty.
  ConfigBox boxAround(const std::vector<double>& configs) const;
  // The share of the sampling bounds' volume that `box` covers.
  double share(const ConfigBox& box) const;
  // Samples for four times the roadmap's density within `box`, at most as
  // many as the roadmap has (a box of everything doubles it), at least 64.
  void growWithin(const ConfigBox& box);

  int size() const { return static_cast<int>(configs_.size() / static_cast<std::size_t>(dim_)); }
  const double* config(int v) const { return configs_.data() + static_cast<std::size_t>(v) * static_cast<std::size_t>(dim_); }
  const std::vector<Edge>& edges(int v) const { return adjacency_[static_cast<std::size_t>(v)]; }

  // Whether the edge's motion is valid against the world (checked once).
  // False, and left unknown, when the deadline expires during the check.
  bool edgeValid(int id);
  bool knownInvalid(int id) const { return edge_state_[static_cast<std::size_t>(id)] < 0; }
  std::size_t edgeChecks() const { return edge_checks_; }

  // Up to k roadmap vertices nearest to q (approximately, in the metric).
  std::vector<int> nearest(const double* q, int k) const;

  const RobotModel& model() const { return model_; }
  const CollisionWorld& world() const { return world_; }
  // The deadline as this roadmap's checks poll it (see grow and edgeValid).
  DeadlinePoll& poll() { return poll_; }
  // Whether growing or an edge check found the deadline expired: a grow
  // may then have stopped short.
  bool deadlineSeen() const { return poll_.seenExpired(); }

 private:
  void embed(const double* q, double* out) const;
  // Joins v to its k nearest; near and scratch are the caller's buffers.
  void connect(int v, std::vector<std::size_t>& near, std::vector<double>& scratch);
  const CollisionWorld& world_;
  const RobotModel& model_;
  int dim_;
  int neighbors_;
  std::mt19937_64 rng_;
  std::vector<double> lo_, hi_;
  std::vector<double> configs_;
  std::vector<std::vector<Edge>> adjacency_;
  std::vector<std::pair<int, int>> edge_ends_;
  std::vector<std::int8_t> edge_state_;  // 0 unknown, 1 valid, -1 invalid
  std::vector<bool> dropped_;  // by dropInvalidVertices; empty: none
  bool keep_candidates_ = false;
  std::vector<int> candidates_;  // 2k per vertex, nearest first, -1 past the last
  PointIndex index_;
  std::size_t edge_checks_ = 0;
  DeadlinePoll poll_;  // one count of work for all of the roadmap's checks
};

// Roadmaps as they came out of building, kept across plans by a key of all
// building depends on, so a kept roadmap plans as a fresh one; least recently
// used dropped past the capacity in bytes. Not thread-safe.
class RoadmapCache {
 public:
  struct Entry {
    Roadmap::Snapshot snapshot;
    std::uint64_t work = 0;
    std::size_t bytes = 0;
  };
  explicit RoadmapCache(std::size_t capacity_bytes) : capacity_(capacity_bytes) {}
  // The entry under `key`, now the most recently used; null if none.
  std::shared_ptr<const Entry> find(const std::string& key);
  void put(const std::string& key, Roadmap::Snapshot snapshot, std::uint64_t work);
  std::size_t size() const { return entries_.size(); }
  std::size_t bytes() const { return bytes_; }
  std::size_t capacity() const { return capacity_; }
  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }

 private:
  std::size_t capacity_;
  std::size_t bytes_ = 0;
  std::uint64_t hits_ = 0, misses_ = 0;
  // Most recently used first.
  std::list<std::pair<std::string, std::shared_ptr<const Entry>>> entries_;
};

// A roadmap (possibly another robot's with the same valid configurations)
// plus query vertices, optionally restricted to a region, for one robot; ids
// below roadmap.size() are roadmap vertices, query vertices follow.
class QueryGraph {
 public:
  QueryGraph(Roadmap& roadmap, const RobotModel& robot, const ConfigBox* region = nullptr);

  // Adds q as a vertex connected to its k nearest roadmap vertices inside
  // the region and to the query vertices added before it.
  int addVertex(const double* q, int k);

  int size() const { return roadmap_.size() + static_cast<int>(extra_.size()); }
  const double* config(int v) const;
  bool allowed(int v) const;  // inside the region (query vertices always)

  // Calls f(to, steps, edge_key) for every edge of v to an allowed vertex.
  template <class F>
  void forEachEdge(int v, F&& f) const {
    const int n = roadmap_.size();
    if (v < n) {
      for (const auto& e : roadmap_.edges(v))
        if (allowed(e.to)) f(e.to, e.steps, e.id);
      auto it = back_edges_.find(v);
      if (it != back_edges_.end())
        for (const auto& e : it->second) f(e.to, e.steps, e.id);
    } else {
      for (const auto& e : extra_[static_cast<std::size_t>(v - n)].edges) f(e.to, e.steps, e.id);
    }
  }

  // Validity of an edge given by its key (roadmap ids >= 0, query edges < 0);
  // false, left unknown, once the roadmap's deadline has expired.
  bool edgeValid(int key);
  // True when an earlier check, by this query or any query on the same
  // roadmap, found the edge invalid (no check is made here).
  bool knownInvalid(int key) const {
    return key >= 0 ? roadmap_.knownInvalid(key) : extra_edge_state_[static_cast<std::size_t>(-1 - key)] < 0;
  }
  Roadmap& roadmap() { return roadmap_; }
  const RobotModel& model() const { return robot_; }
  const ConfigBox* region() const { return region_; }  // null: everywhere

 private:
  struct Extra {
    std::vector<double> q;
    std::vector<Roadmap::Edge> edges;
  };
  int addEdge(int a, int b);
  Roadmap& roadmap_;
  const RobotModel& robot_;
  const ConfigBox* region_;
  std::vector<Extra> extra_;
  std::unordered_map<int, std::vector<Roadmap::Edge>> back_edges_;
  std::vector<std::pair<int, int>> extra_edge_ends_;
  std::vector<std::int8_t> extra_edge_state_;
};

// Units of work (Deadline::withWorkBudgets) of one vertex taken from a graph
// search's queue over a roadmap, its edges relaxed: about its time.
inline constexpr std::size_t kWorkPerGraphPop = 4;

// Shortest path in time steps from `from` to `to` (lazy edge checks), or
// nullopt; then, before the deadline, `reached` (if given) gets the vertices
// reachable from `from`.
std::optional<std::vector<int>> shortestPath(QueryGraph& graph, int from, int to, const Deadline& deadline,
                                             std::vector<int>* reached = nullptr);

// Time-stamps a sequence of configurations at the robot's resolution.
Path timeStamp(const RobotModel& model, const std::vector<std::vector<double>>& waypoints);

// Appends the straight motion a -> b after a at the robot's resolution: the
// states between, then b (nothing when a and b are less than a step apart).
void appendStraightMotion(const RobotModel& model, const double* a, const double* b, Path& out);

}  // namespace earc
