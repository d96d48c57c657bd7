#include "lattice_search.hpp"

#include <algorithm>
#include <limits>

namespace earc::lattice {

Occupancy::Occupancy(const CrowdRoadmap& rm, std::vector<VertexPath>& paths)
    : rm_(rm), paths_(paths), nv_(static_cast<std::size_t>(rm.vertexCount())) {
  if (rm.allOnLattice()) {
    // The conflict table's threats resolved to vertices once, so that a
    // check reads a short list instead of the roadmap's geometry.
    first_.reserve(5 * nv_ + 1);
    for (int v = 0; v < rm.vertexCount(); ++v)
      for (int a = 0; a < 5; ++a) {
        first_.push_back(static_cast<std::uint32_t>(threats_.size()));
        for (const CrowdRoadmap::LatticeThreat& th : rm.latticeThreats(a))
          if (const int w = rm.latticeOffset(v, th.dc, th.dr); w >= 0) threats_.push_back({w, th.mask});
      }
    first_.push_back(static_cast<std::uint32_t>(threats_.size()));
  }
  std::size_t h = 1;
  for (const auto& p : paths) h = std::max(h, p.size());
  grow(h);
  for (std::size_t i = 0; i < paths.size(); ++i) put(static_cast<int>(i));
}

void Occupancy::grow(std::size_t h) {
  if (rows_ == 0) {
    occ_.assign(nv_, -1);
    nearby_.assign(nv_, 0);
    step_.assign(nv_, 0);
    rows_ = 1;
  }
  if (h <= rows_) return;
  repeatLastRow(occ_, nv_, h);
  repeatLastRow(nearby_, nv_, h);
  repeatLastRow(step_, nv_, h);
  rows_ = h;
}

void Occupancy::count(int v, std::size_t t, int delta) {
  int* row = nearby_.data() + t * nv_;
  for (int w : rm_.near(v)) row[w] += delta;
}

void Occupancy::put(int i) {
  const VertexPath& p = paths_[static_cast<std::size_t>(i)];
  grow(p.size());
  countWork(rows_);
  for (std::size_t t = 0; t < rows_; ++t) {
    const int v = vertexAt(p, t);
    occ_[t * nv_ + static_cast<std::size_t>(v)] = i;
    step_[t * nv_ + static_cast<std::size_t>(v)] = static_cast<signed char>(rm_.latticeStep(v, vertexAt(p, t + 1)));
    count(v, t, +1);
  }
}

void Occupancy::remove(int i) {
  const VertexPath& p = paths_[static_cast<std::size_t>(i)];
  countWork(rows_);
  for (std::size_t t = 0; t < rows_; ++t) {
    const int v = vertexAt(p, t);
    int& o = occ_[t * nv_ + static_cast<std::size_t>(v)];
    if (o != i) continue;
    o = -1;
    count(v, t, -1);
  }
}

bool Occupancy::blockedOnLattice(int i, int u, int v, int a, std::size_t t) const {
  const std::size_t row = std::min(t, rows_ - 1) * nv_;
  const int* now = occ_.data() + row;
  const signed char* steps = step_.data() + row;
  const std::size_t k = 5 * static_cast<std::size_t>(u) + static_cast<std::size_t>(a);
  for (std::uint32_t x = first_[k]; x < first_[k + 1]; ++x) {
    const Threat& th = threats_[x];
    const int j = now[th.w];
    if (j < 0 || j == i) continue;
    if (const int b = steps[th.w]; b >= 0) {
      if (th.mask >> b & 1u) return true;
    } else if (rm_.conflict(i, {u, v}, j, {th.w, vertexAt(paths_[static_cast<std::size_t>(j)], t + 1)})) {
      return true;
    }
  }
  return false;
}

bool Occupancy::blocked(int i, int u, int v, std::size_t t) const {
  const std::size_t row = std::min(t, rows_ - 1);
  if (nearby_[row * nv_ + static_cast<std::size_t>(u)] == 0) return false;
  // On a lattice alone, the conflict table's few threatening cells decide
  // (the same answer as rm_.conflict on every robot near u, for less).
  if (!first_.empty())
    if (const int a = rm_.latticeStep(u, v); a >= 0) return blockedOnLattice(i, u, v, a, t);
  const int* now = occ_.data() + row * nv_;
  for (int w : rm_.near(u)) {
    const int j = now[w];
    if (j < 0 || j == i) continue;
    if (rm_.conflict(i, {u, v}, j, {w, vertexAt(paths_[static_cast<std::size_t>(j)], t + 1)})) return true;
  }
  return false;
}

void BucketQueue::clear() {
  // Buckets below lowest_ are empty already; none above highest_ was used.
  if (count_ > 0)
    for (std::size_t f = lowest_; f <= highest_; ++f) buckets_[f].clear();
  lowest_ = std::numeric_limits<std::size_t>::max();
  highest_ = 0;
  count_ = 0;
}

void BucketQueue::push(std::size_t f, int node) {
  if (f >= buckets_.size()) buckets_.resize(f + 1);
  buckets_[f].push_back(node);
  lowest_ = std::min(lowest_, f);
  highest_ = std::max(highest_, f);
  ++count_;
}

int BucketQueue::pop() {
  while (buckets_[lowest_].empty()) ++lowest_;
  const int k = buckets_[lowest_].back();
  buckets_[lowest_].pop_back();
  --count_;
  return k;
}

std::optional<VertexPath> StepSearch::search(const Occupancy& occ, int i, const Deadline& deadline, long long max_cost,
                                             std::size_t max_expansions, double weight, bool avoid_goals) {
  nodes_.clear();
  open_.clear();
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
  countWork(occ.horizon() - static_cast<std::size_t>(free_after + 1));
  auto h = [&](int v, long long t) { return std::max<long long>(rm_.distanceToGoal(i, v), free_after + 1 - t); };
  if (h(rm_.start(i), 0) > max_cost) return std::nullopt;
  // With avoid_goals, among equally good ways the one that spends the
  // fewest steps on other robots' goals before they arrive comes first.
  const int levels = avoid_goals ? kGoalLevels : 1;
  if (goal_of_.empty()) {
    goal_of_.assign(nv, -1);
    for (int k = 0; k < rm_.robotCount(); ++k) goal_of_[static_cast<std::size_t>(rm_.goal(k))] = k;
  }
  nodes_.push_back({rm_.start(i), 0, -1, 0});
  open_.push(static_cast<std::size_t>(h(rm_.start(i), 0)) * static_cast<std::size_t>(levels), 0);
  std::size_t expanded = 0;
  while (!open_.empty()) {
    const int k = open_.pop();
    const Node n = nodes_[static_cast<std::size_t>(k)];
    const std::size_t key = static_cast<std::size_t>(n.t) * nv + static_cast<std::size_t>(n.v);
    if (closed_[key] == stamp_) continue;
    closed_[key] = stamp_;
    if (++expanded > max_expansions || ((expanded & 255) == 0 && deadline.expired())) return std::nullopt;
    ++expansions_;
    countWork(1 + rm_.neighbours(n.v).size());
    if (n.v == goal && n.t > free_after) {
      VertexPath p;
      for (int x = k; x >= 0; x = nodes_[static_cast<std::size_t>(x)].parent)
        p.push_back(nodes_[static_cast<std::size_t>(x)].v);
      std::reverse(p.begin(), p.end());
      return p;
    }
    if (static_cast<std::size_t>(n.t) + 1 > limit) continue;
    auto consider = [&](int v) {
      if (!rm_.usableBy(i, v) || rm_.distanceToGoal(i, v) >= CrowdRoadmap::kUnreachable) return;
      if (n.t + 1 + h(v, n.t + 1) > max_cost) return;
      if (closed_[static_cast<std::size_t>(n.t + 1) * nv + static_cast<std::size_t>(v)] == stamp_) return;
      if (occ.blocked(i, n.v, v, static_cast<std::size_t>(n.t))) return;
      const int owner = goal_of_[static_cast<std::size_t>(v)];
      const int crossed = n.crossed + (owner >= 0 && owner != i && occ.arrival(owner) > static_cast<std::size_t>(n.t + 1) ? 1 : 0);
      nodes_.push_back({v, n.t + 1, k, crossed});
      const long long hv = h(v, n.t + 1);
      const auto f = static_cast<std::size_t>(n.t + 1 + (weight == 1.0 ? hv : static_cast<long long>(weight * static_cast<double>(hv))));
      open_.push(f * static_cast<std::size_t>(levels) + static_cast<std::size_t>(std::min(crossed, levels - 1)),
           static_cast<int>(nodes_.size()) - 1);
    };
    consider(n.v);
    for (int v : rm_.neighbours(n.v)) consider(v);
  }
  return std::nullopt;
}

}  // namespace earc::lattice
