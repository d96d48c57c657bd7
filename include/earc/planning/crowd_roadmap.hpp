// The crowd solver's roadmap: a square lattice of positions over the free
// plane (the cells' centres on a grid map), shared by a group of mobile
// robots, plus each robot's own start and goal where they are off the
// lattice. All robots step together: one step moves every robot along an
// edge or keeps it in place, each robot bounded by one disc of radius R.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/geometry/shapes.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

// One robot's step: from vertex `from` to vertex `to` (equal: it stays).
struct CrowdMove {
  int from = -1;
  int to = -1;
};

// Smallest distance between two points moving linearly and synchronously,
// a0 -> a1 and b0 -> b1 over the same interval. Exact; thread-safe.
double closestApproach(geo::Vec2 a0, geo::Vec2 a1, geo::Vec2 b0, geo::Vec2 b1);

class CrowdRoadmap {
 public:
  // Builds the roadmap for robots[i] (indices into models, mobile robots
  // only) going from starts[i] to goals[i] ([x, y, theta] each). Throws
  // std::invalid_argument naming the robot when one is not mobile.
  CrowdRoadmap(const CollisionWorld& world, const std::vector<const RobotModel*>& models,
               const std::vector<int>& robots, const std::vector<std::vector<double>>& starts,
               const std::vector<std::vector<double>>& goals);

  int vertexCount() const { return static_cast<int>(pos_.size()); }
  geo::Vec2 position(int v) const { return pos_[static_cast<std::size_t>(v)]; }
  // The robot (group index) whose own start or goal vertex v is; -1 for a lattice vertex.
  int owner(int v) const { return owner_[static_cast<std::size_t>(v)]; }
  const std::vector<int>& neighbours(int v) const { return adj_[static_cast<std::size_t>(v)]; }
  // Vertices w such that some step from v and some step from w conflict
  // (the conflict table); includes v.
  const std::vector<int>& near(int v) const { return near_[static_cast<std::size_t>(v)]; }
  int start(int i) const { return start_[static_cast<std::size_t>(i)]; }
  int goal(int i) const { return goal_[static_cast<std::size_t>(i)]; }
  // Steps from v to robot i's goal over the vertices robot i may use;
  // kUnreachable where there is no way.
  int distanceToGoal(int i, int v) const { return dist_[static_cast<std::size_t>(i)][static_cast<std::size_t>(v)]; }
  static constexpr int kUnreachable = 1 << 29;
  // Whether robot i may stand on v (lattice vertices and its own).
  bool usableBy(int i, int v) const { return owner(v) < 0 || owner(v) == i; }
  // Where robot i may be one step after standing on u: u itself first,
  // then the neighbours it may use. Thread-safe.
  void placesFrom(int i, int u, std::vector<int>& out) const;

  // Whether robot i stepping m_i and robot j stepping m_j at once touch:
  // bounding discs, and real footprints at the validated instants where a
  // robot is on or beside its own start or goal (heading known). Thread-safe.
  bool conflict(int i, CrowdMove mi, int j, CrowdMove mj) const;

  // Where robot steps between lattice vertices meet a step of type a (0
  // stays, 1-4 the axis moves) from the origin: each cell offset with the
  // mask of the step types there that conflict (bit b). Thread-safe.
  struct LatticeThreat {
    int dc, dr;
    unsigned mask;
  };
  const std::vector<LatticeThreat>& latticeThreats(int a) const { return threats_[static_cast<std::size_t>(a)]; }
  // The type of the step u -> v between lattice vertices; -1 otherwise.
  int latticeStep(int u, int v) const {
    const int c0 = cell_c_[static_cast<std::size_t>(u)], c1 = cell_c_[static_cast<std::size_t>(v)];
    if (c0 < 0 || c1 < 0) return -1;
    const int dc = c1 - c0, dr = cell_r_[static_cast<std::size_t>(v)] - cell_r_[static_cast<std::size_t>(u)];
    if (dr == 0 && dc >= -1 && dc <= 1) return dc == 0 ? 0 : (dc == 1 ? 1 : 2);
    if (dc == 0 && (dr == 1 || dr == -1)) return dr == 1 ? 3 : 4;
    return -1;
  }
  // The lattice vertex dc columns and dr rows from lattice vertex v; -1 for none.
  int latticeOffset(int v, int dc, int dr) const {
    return latticeAt(cell_c_[static_cast<std::size_t>(v)] + dc, cell_r_[static_cast<std::size_t>(v)] + dr);
  }
  // Whether every vertex is on the lattice (no robot has an own vertex off it).
  bool allOnLattice() const { return all_on_lattice_; }

  double radius() const { return radius_; }    // the bounding disc R
  double spacing() const { return spacing_; }  // lattice spacing
  bool gridAligned() const { return grid_; }   // lattice on a grid map's cell centres
  // The heading its owner has at an own vertex (its start or goal heading).
  double headingAt(int v) const;
  // Whether v is on its owner's start side (left for good once left).
  bool startSide(int v) const { return start_side_[static_cast<std::size_t>(v)] != 0; }
  // Robots in the group, and the longest edge.
  int robotCount() const { return static_cast<int>(start_.size()); }
  double longestEdge() const { return longest_edge_; }
  // Time steps a roadmap step takes: the longest edge at the robots' resolution.
  int stepsPerEdge() const { return steps_per_edge_; }
  // Robot i's model.
  const RobotModel& model(int i) const { return *group_models_[static_cast<std::size_t>(i)]; }
  // Why the roadmap cannot serve the group ("" when it can): a robot whose
  // start or goal joins no lattice vertex, or whose goal is unreachable.
  const std::string& problem() const { return problem_; }

 private:
  int latticeAt(int c, int r) const;  // vertex id, or -1 (blocked or outside)
  int addVertex(geo::Vec2 p, int owner, double heading = 0.0, bool start_side = false);
  void addEdge(int a, int b);
  int connectOwn(const CollisionWorld& world, int robot, const std::vector<double>& q, bool is_start);
  void buildNear();
  void buildDistances();
  void buildLatticeConflicts();
  // Whether two steps between lattice vertices conflict: 0 or 1; -1 when not on the table.
  int latticeConflict(CrowdMove mi, CrowdMove mj) const;

  double radius_ = 0.0;
  double spacing_ = 1.0;
  double longest_edge_ = 0.0;
  int steps_per_edge_ = 1;
  bool grid_ = false;
  geo::Vec2 origin_;
  int cols_ = 0, rows_ = 0;
  std::vector<int> lattice_;          // cols_ x rows_, vertex id or -1
  std::vector<int> cell_c_, cell_r_;  // per vertex: its lattice column and row; -1 off it
  int table_reach_ = 0;               // the conflict table's offsets between the robots, in cells
  std::vector<signed char> lattice_conflicts_;
  std::vector<std::vector<LatticeThreat>> threats_;
  bool all_on_lattice_ = false;
  std::vector<geo::Vec2> pos_;
  std::vector<int> owner_;
  std::vector<std::vector<int>> adj_;
  std::vector<std::vector<int>> near_;
  std::vector<int> start_, goal_;
  std::vector<double> heading_;   // per vertex: its owner's heading there
  std::vector<char> start_side_;  // per vertex
  std::vector<const RobotModel*> group_models_;
  std::vector<std::vector<int>> dist_;  // per robot, per vertex
  std::string problem_;
};

}  // namespace earc
