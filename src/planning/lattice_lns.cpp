#include "earc/planning/lattice_lns.hpp"

#include <algorithm>
#include <numeric>
#include <optional>
#include <queue>
#include <random>

#include "earc/util/random.hpp"

namespace earc {

namespace {

using VertexPath = std::vector<int>;  // a vertex per roadmap step; then the last, for ever

int vertexAt(const VertexPath& p, std::size_t t) { return t < p.size() ? p[t] : p.back(); }

// Steps until the robot is at its goal for good (trailing stays dropped).
void dropStays(VertexPath& p) {
  while (p.size() > 1 && p[p.size() - 2] == p.back()) p.pop_back();
}

// Who stands where at every step, for the robots whose paths are in.
class LatticeOccupancy {
 public:
  LatticeOccupancy(const CrowdRoadmap& rm, std::vector<VertexPath>& paths) : rm_(rm), paths_(paths) {
    std::size_t h = 1;
    for (const auto& p : paths) h = std::max(h, p.size());
    grow(h);
    for (std::size_t i = 0; i < paths.size(); ++i) put(static_cast<int>(i));
  }

  void put(int i) {
    const VertexPath& p = paths_[static_cast<std::size_t>(i)];
    grow(p.size());
    for (std::size_t t = 0; t < occ_.size(); ++t) occ_[t][static_cast<std::size_t>(vertexAt(p, t))] = i;
  }
  void remove(int i) {
    const VertexPath& p = paths_[static_cast<std::size_t>(i)];
    for (std::size_t t = 0; t < occ_.size(); ++t) {
      int& o = occ_[t][static_cast<std::size_t>(vertexAt(p, t))];
      if (o == i) o = -1;
    }
  }
  std::size_t horizon() const { return occ_.size(); }

  // Whether robot i's step u -> v from step t meets anyone in.
  bool blocked(int i, int u, int v, std::size_t t) const {
    const std::vector<int>& now = occ_[std::min(t, occ_.size() - 1)];
    for (int w : rm_.near(u)) {
      const int j = now[static_cast<std::size_t>(w)];
      if (j < 0 || j == i) continue;
      if (rm_.conflict(i, {u, v}, j, {w, vertexAt(paths_[static_cast<std::size_t>(j)], t + 1)})) return true;
    }
    return false;
  }
  // The last step from which staying on g meets someone (-1: none).
  long long lastBlocked(int i, int g) const {
    for (std::size_t t = occ_.size(); t-- > 0;)
      if (blocked(i, g, g, t)) return static_cast<long long>(t);
    return -1;
  }

 private:
  void grow(std::size_t h) {
    if (occ_.empty()) occ_.assign(1, std::vector<int>(static_cast<std::size_t>(rm_.vertexCount()), -1));
    while (occ_.size() < h) occ_.push_back(occ_.back());
  }
  const CrowdRoadmap& rm_;
  std::vector<VertexPath>& paths_;
  std::vector<std::vector<int>> occ_;
};

// Space-time A* for robot i against the occupancy; nothing when no path
// arrives by `limit` steps or the deadline passes.
// StepStamps (vertex, step) pairs, stamped so that a search clears nothing.
struct StepStamps {
  std::vector<std::uint32_t> stamp;
  std::uint32_t now = 0;
  void reset(std::size_t size) {
    if (stamp.size() < size) stamp.resize(size, 0);
    if (++now == 0) {
      std::fill(stamp.begin(), stamp.end(), 0);
      now = 1;
    }
  }
  bool has(std::size_t k) const { return stamp[k] == now; }
  bool insert(std::size_t k) {
    if (stamp[k] == now) return false;
    stamp[k] = now;
    return true;
  }
};

std::optional<VertexPath> spaceTimeAStar(const CrowdRoadmap& rm, const LatticeOccupancy& occ, int i, std::size_t limit,
                                         const Deadline& deadline, StepStamps& closed) {
  struct Node {
    int v;
    std::size_t t;
    int parent;
  };
  std::vector<Node> nodes;
  using Entry = std::pair<long long, int>;  // (f, node), smaller first; ties: later node (deeper)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  const auto nv = static_cast<std::size_t>(rm.vertexCount());
  closed.reset((limit + 2) * nv);
  const int goal = rm.goal(i);
  const long long free_after = occ.lastBlocked(i, goal);
  nodes.push_back({rm.start(i), 0, -1});
  open.emplace(rm.distanceToGoal(i, rm.start(i)), 0);
  std::size_t expanded = 0;
  while (!open.empty()) {
    const int k = open.top().second;
    open.pop();
    const Node n = nodes[static_cast<std::size_t>(k)];
    if (!closed.insert(n.t * nv + static_cast<std::size_t>(n.v))) continue;
    if ((++expanded & 1023) == 0 && deadline.expired()) return std::nullopt;
    if (n.v == goal && static_cast<long long>(n.t) > free_after) {
      VertexPath p;
      for (int x = k; x >= 0; x = nodes[static_cast<std::size_t>(x)].parent) p.push_back(nodes[static_cast<std::size_t>(x)].v);
      std::reverse(p.begin(), p.end());
      return p;
    }
    if (n.t + 1 > limit) continue;
    auto consider = [&](int v) {
      if (!rm.usableBy(i, v) || rm.distanceToGoal(i, v) >= CrowdRoadmap::kUnreachable) return;
      if (closed.has((n.t + 1) * nv + static_cast<std::size_t>(v))) return;
      if (occ.blocked(i, n.v, v, n.t)) return;
      nodes.push_back({v, n.t + 1, k});
      open.emplace(static_cast<long long>(n.t + 1) + rm.distanceToGoal(i, v), static_cast<int>(nodes.size()) - 1);
    };
    consider(n.v);
    for (int v : rm.neighbours(n.v)) consider(v);
  }
  return std::nullopt;
}

long long pathCost(const VertexPath& p) { return static_cast<long long>(p.size()) - 1; }

}  // namespace

long long latticeSumOfCosts(const CrowdRoadmap& rm, const std::vector<std::vector<int>>& configs) {
  long long soc = 0;
  for (int i = 0; i < rm.robotCount(); ++i) {
    VertexPath p;
    for (const auto& c : configs) p.push_back(c[static_cast<std::size_t>(i)]);
    dropStays(p);
    soc += pathCost(p);
  }
  return soc;
}

nlohmann::json refineOnLattice(const CrowdRoadmap& rm, std::vector<std::vector<int>>& configs,
                               const Deadline& deadline, std::uint64_t seed, int max_rounds) {
  const int n = rm.robotCount();
  std::vector<VertexPath> paths(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (const auto& c : configs) paths[static_cast<std::size_t>(i)].push_back(c[static_cast<std::size_t>(i)]);
    dropStays(paths[static_cast<std::size_t>(i)]);
  }
  long long soc = 0;
  for (const auto& p : paths) soc += pathCost(p);
  const long long first = soc;
  LatticeOccupancy occ(rm, paths);
  StepStamps closed;
  std::mt19937_64 rng(splitSeed(seed, 11));
  int tried = 0, kept = 0;
  // Robots most delayed (steps beyond their own shortest way) first.
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  auto delay = [&](int i) { return pathCost(paths[static_cast<std::size_t>(i)]) - rm.distanceToGoal(i, rm.start(i)); };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return delay(a) > delay(b); });
  // Replans `group` one after another (random order) and keeps the new
  // paths when they cost less; else puts the old ones back.
  auto replanGroup = [&](const std::vector<int>& group) {
    std::vector<VertexPath> old;
    for (int i : group) old.push_back(paths[static_cast<std::size_t>(i)]);
    ++tried;
    long long before = 0;
    for (int i : group) {
      before += pathCost(paths[static_cast<std::size_t>(i)]);
      occ.remove(i);
    }
    std::vector<int> shuffled = group;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    long long after = 0;
    std::vector<int> placed;
    bool ok = true;
    for (int i : shuffled) {
      const std::size_t limit = occ.horizon() + static_cast<std::size_t>(rm.distanceToGoal(i, rm.start(i))) + 16;
      auto p = spaceTimeAStar(rm, occ, i, limit, deadline, closed);
      if (!p || (after += pathCost(*p)) >= before) {
        ok = false;
        break;
      }
      paths[static_cast<std::size_t>(i)] = std::move(*p);
      occ.put(i);
      placed.push_back(i);
    }
    if (ok) {
      soc += after - before;
      ++kept;
      return;
    }
    for (int i : placed) occ.remove(i);
    for (std::size_t k = 0; k < group.size(); ++k) {
      paths[static_cast<std::size_t>(group[k])] = std::move(old[k]);
      occ.put(group[k]);
    }
  };
  int rounds = 0;
  for (int i : order) {
    if (rounds++ >= max_rounds || deadline.expired()) break;
    if (delay(i) > 0) replanGroup({i});
  }
  // Then neighbourhoods: random robots, or the robots around a random
  // vertex on a delayed robot's path (where robots get in each other's way).
  constexpr std::size_t kNeighbourhood = 8;
  while (rounds++ < max_rounds && !deadline.expired() && n > 1) {
    std::vector<int> group;
    std::vector<char> in(static_cast<std::size_t>(n), 0);
    auto add = [&](int r) {
      if (!in[static_cast<std::size_t>(r)] && group.size() < kNeighbourhood) {
        in[static_cast<std::size_t>(r)] = 1;
        group.push_back(r);
      }
    };
    if (rng() % 2 == 0) {
      const int r = order[static_cast<std::size_t>(uniformIndex(rng, std::min<std::uint64_t>(static_cast<std::uint64_t>(n), 16)))];
      add(r);
      const VertexPath& p = paths[static_cast<std::size_t>(r)];
      const std::size_t t = uniformIndex(rng, p.size());
      const int v = p[t];
      for (std::size_t dt = 0; dt < 8 && group.size() < kNeighbourhood; ++dt)
        for (int i = 0; i < n; ++i) {
          const VertexPath& q = paths[static_cast<std::size_t>(i)];
          for (int w : rm.near(v))
            if (vertexAt(q, t + dt) == w || (t >= dt && vertexAt(q, t - dt) == w)) add(i);
        }
    }
    while (group.size() < std::min<std::size_t>(kNeighbourhood, static_cast<std::size_t>(n)))
      add(static_cast<int>(uniformIndex(rng, static_cast<std::uint64_t>(n))));
    std::sort(group.begin(), group.end());
    replanGroup(group);
    if (rng() % 8 == 0)
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return delay(a) > delay(b); });
  }
  std::size_t h = 1;
  for (const auto& p : paths) h = std::max(h, p.size());
  configs.assign(h, std::vector<int>(static_cast<std::size_t>(n)));
  for (std::size_t t = 0; t < h; ++t)
    for (int i = 0; i < n; ++i) configs[t][static_cast<std::size_t>(i)] = vertexAt(paths[static_cast<std::size_t>(i)], t);
  return {{"sum_of_costs_before", first}, {"sum_of_costs_after", soc}, {"neighbourhoods", tried}, {"kept", kept}};
}

}  // namespace earc
