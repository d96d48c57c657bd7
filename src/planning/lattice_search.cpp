#include "lattice_search.hpp"

#include <algorithm>
#include <queue>
#include <tuple>

namespace earc::lattice {

Occupancy::Occupancy(const CrowdRoadmap& rm, std::vector<VertexPath>& paths) : rm_(rm), paths_(paths) {
  std::size_t h = 1;
  for (const auto& p : paths) h = std::max(h, p.size());
  grow(h);
  for (std::size_t i = 0; i < paths.size(); ++i) put(static_cast<int>(i));
}

void Occupancy::grow(std::size_t h) {
  const auto nv = static_cast<std::size_t>(rm_.vertexCount());
  if (occ_.empty()) {
    occ_.assign(1, std::vector<int>(nv, -1));
    nearby_.assign(1, std::vector<int>(nv, 0));
  }
  while (occ_.size() < h) {
    occ_.push_back(occ_.back());
    nearby_.push_back(nearby_.back());
  }
}

void Occupancy::count(int v, std::size_t t, int delta) {
  std::vector<int>& row = nearby_[t];
  for (int w : rm_.near(v)) row[static_cast<std::size_t>(w)] += delta;
}

void Occupancy::put(int i) {
  const VertexPath& p = paths_[static_cast<std::size_t>(i)];
  grow(p.size());
  for (std::size_t t = 0; t < occ_.size(); ++t) {
    const int v = vertexAt(p, t);
    occ_[t][static_cast<std::size_t>(v)] = i;
    count(v, t, +1);
  }
}

void Occupancy::remove(int i) {
  const VertexPath& p = paths_[static_cast<std::size_t>(i)];
  for (std::size_t t = 0; t < occ_.size(); ++t) {
    const int v = vertexAt(p, t);
    int& o = occ_[t][static_cast<std::size_t>(v)];
    if (o != i) continue;
    o = -1;
    count(v, t, -1);
  }
}

bool Occupancy::blocked(int i, int u, int v, std::size_t t) const {
  const std::size_t row = std::min(t, occ_.size() - 1);
  if (nearby_[row][static_cast<std::size_t>(u)] == 0) return false;
  const std::vector<int>& now = occ_[row];
  for (int w : rm_.near(u)) {
    const int j = now[static_cast<std::size_t>(w)];
    if (j < 0 || j == i) continue;
    if (rm_.conflict(i, {u, v}, j, {w, vertexAt(paths_[static_cast<std::size_t>(j)], t + 1)})) return true;
  }
  return false;
}

std::optional<VertexPath> StepSearch::search(const Occupancy& occ, int i, const Deadline& deadline, long long max_cost,
                                             std::size_t max_expansions, double weight) {
  struct Node {
    int v;
    int t;
    int parent;
  };
  std::vector<Node> nodes;
  // (f, -t, node), smallest first: ties go to the deeper node, so that a
  // search among equally good ways follows one of them to the goal.
  using Entry = std::tuple<long long, long long, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  const auto nv = static_cast<std::size_t>(rm_.vertexCount());
  const int goal = rm_.goal(i);
  // Beyond the horizon everyone stands still: a way much longer than the
  // horizon and the robot's own distance waits for nothing.
  const long long own = rm_.distanceToGoal(i, rm_.start(i));
  max_cost = std::min<long long>(max_cost, static_cast<long long>(occ.horizon()) + own + 16);
  if (max_cost < own) return std::nullopt;
  const auto limit = static_cast<std::size_t>(max_cost);
  if (closed_.size() < (limit + 2) * nv) closed_.resize((limit + 2) * nv, 0);
  if (++stamp_ == 0) {
    std::fill(closed_.begin(), closed_.end(), 0);
    stamp_ = 1;
  }
  // The last step from which staying on the goal meets someone: arriving
  // for good cannot happen before the step after it.
  long long free_after = -1;
  for (std::size_t t = occ.horizon(); t-- > 0;)
    if (occ.blocked(i, goal, goal, t)) {
      free_after = static_cast<long long>(t);
      break;
    }
  auto h = [&](int v, long long t) { return std::max<long long>(rm_.distanceToGoal(i, v), free_after + 1 - t); };
  if (h(rm_.start(i), 0) > max_cost) return std::nullopt;
  nodes.push_back({rm_.start(i), 0, -1});
  open.emplace(h(rm_.start(i), 0), 0, 0);
  std::size_t expanded = 0;
  while (!open.empty()) {
    const int k = std::get<2>(open.top());
    open.pop();
    const Node n = nodes[static_cast<std::size_t>(k)];
    const std::size_t key = static_cast<std::size_t>(n.t) * nv + static_cast<std::size_t>(n.v);
    if (closed_[key] == stamp_) continue;
    closed_[key] = stamp_;
    if (++expanded > max_expansions || ((expanded & 255) == 0 && deadline.expired())) return std::nullopt;
    ++expansions_;
    if (n.v == goal && n.t > free_after) {
      VertexPath p;
      for (int x = k; x >= 0; x = nodes[static_cast<std::size_t>(x)].parent)
        p.push_back(nodes[static_cast<std::size_t>(x)].v);
      std::reverse(p.begin(), p.end());
      return p;
    }
    if (static_cast<std::size_t>(n.t) + 1 > limit) continue;
    auto consider = [&](int v) {
      if (!rm_.usableBy(i, v) || rm_.distanceToGoal(i, v) >= CrowdRoadmap::kUnreachable) return;
      if (n.t + 1 + h(v, n.t + 1) > max_cost) return;
      if (closed_[static_cast<std::size_t>(n.t + 1) * nv + static_cast<std::size_t>(v)] == stamp_) return;
      if (occ.blocked(i, n.v, v, static_cast<std::size_t>(n.t))) return;
      nodes.push_back({v, n.t + 1, k});
      const long long hv = h(v, n.t + 1);
      open.emplace(n.t + 1 + (weight == 1.0 ? hv : static_cast<long long>(weight * static_cast<double>(hv))), -(n.t + 1),
                   static_cast<int>(nodes.size()) - 1);
    };
    consider(n.v);
    for (int v : rm_.neighbours(n.v)) consider(v);
  }
  return std::nullopt;
}

}  // namespace earc::lattice
