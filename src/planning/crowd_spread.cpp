#include "crowd_spread.hpp"

#include <algorithm>
#include <numeric>
#include <queue>
#include <random>
#include <tuple>

namespace earc::crowd {

namespace {

// How many ways stand on each vertex at each step, and when ways end on
// a vertex (their robots stay there after).
class WayTable {
 public:
  explicit WayTable(int vertices) : at_(static_cast<std::size_t>(vertices)), ends_(static_cast<std::size_t>(vertices)) {}

  // Meetings a robot makes by being on v at step t.
  long long cost(int v, int t) const {
    const auto& row = at_[static_cast<std::size_t>(v)];
    long long c = static_cast<std::size_t>(t) < row.size() ? row[static_cast<std::size_t>(t)] : 0;
    for (int end : ends_[static_cast<std::size_t>(v)])
      if (t > end) ++c;
    return c;
  }
  // Adds (+1) or removes (-1) a way; returns the meetings it makes.
  long long apply(const std::vector<int>& way, int sign) {
    if (way.empty()) return 0;
    long long met = 0;
    if (sign < 0) change(way, -1);
    for (std::size_t t = 1; t < way.size(); ++t) met += cost(way[t], static_cast<int>(t));
    // Ways passing its goal after it arrives.
    const auto& row = at_[static_cast<std::size_t>(way.back())];
    for (std::size_t t = way.size(); t < row.size(); ++t) met += row[t];
    if (sign > 0) change(way, +1);
    return met;
  }

 private:
  void change(const std::vector<int>& way, int sign) {
    for (std::size_t t = 0; t < way.size(); ++t) {
      auto& row = at_[static_cast<std::size_t>(way[t])];
      if (row.size() <= t) row.resize(t + 1, 0);
      row[t] += sign;
    }
    auto& ends = ends_[static_cast<std::size_t>(way.back())];
    const int end = static_cast<int>(way.size()) - 1;
    if (sign > 0) {
      ends.push_back(end);
    } else if (auto it = std::find(ends.begin(), ends.end(), end); it != ends.end()) {
      ends.erase(it);
    }
  }
  std::vector<std::vector<int>> at_;
  std::vector<std::vector<int>> ends_;
};

// Units of work (Deadline::withWorkBudgets) counted per node popped.
constexpr std::size_t kWorkPerPop = 3;

// Robot i's way of at most its distance + margin steps with the fewest
// meetings, then the fewest steps; a vertex is entered once (a spatial
// search whose steps count time, as LaCAM3's). Empty when the deadline ends it.
std::vector<int> spreadWay(const CrowdRoadmap& rm, const WayTable& table, int i, int margin,
                           std::vector<int>& parent, const Deadline& deadline) {
  // (meetings, f, vertex, g, parent): fewest meetings, then shortest.
  using Entry = std::tuple<long long, int, int, int, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  std::vector<int> used;
  const int s = rm.start(i), goal = rm.goal(i);
  const int bound = rm.distanceToGoal(i, s) + margin;
  open.emplace(0, rm.distanceToGoal(i, s), s, 0, -2);
  std::vector<int> way;
  std::size_t pops = 0;
  while (!open.empty()) {
    const auto [met, f, v, g, from] = open.top();
    open.pop();
    if (parent[static_cast<std::size_t>(v)] != -1) continue;
    parent[static_cast<std::size_t>(v)] = from;
    used.push_back(v);
    // A pop and its few neighbours: about three bodies placed.
    countWork(kWorkPerPop);
    if ((++pops & 255) == 0 && deadline.expired()) break;
    if (v == goal) {
      for (int x = v; x >= 0; x = parent[static_cast<std::size_t>(x)]) way.push_back(x);
      std::reverse(way.begin(), way.end());
      break;
    }
    for (int u : rm.neighbours(v)) {
      if (u == s || parent[static_cast<std::size_t>(u)] != -1 || !rm.usableBy(i, u)) continue;
      const int d = rm.distanceToGoal(i, u);
      if (d >= CrowdRoadmap::kUnreachable || g + 1 + d > bound) continue;
      open.emplace(met + table.cost(u, g + 1), g + 1 + d, u, g + 1, v);
    }
  }
  for (int v : used) parent[static_cast<std::size_t>(v)] = -1;
  return way;
}

}  // namespace

Spread::Spread(const CrowdRoadmap& rm, int margin, const Deadline& deadline, std::uint64_t seed)
    : next_(static_cast<std::size_t>(rm.robotCount())) {
  const int n = rm.robotCount();
  WayTable table(rm.vertexCount());
  std::vector<std::vector<int>> ways(static_cast<std::size_t>(n));
  std::vector<int> parent(static_cast<std::size_t>(rm.vertexCount()), -1);
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  long long met = 0;
  std::vector<std::vector<int>> kept;
  long long kept_met = -1;
  // Each pass replans every robot against the others' current ways; the
  // passes go on while the meetings drop (at least two).
  for (int pass = 0; !deadline.expired(); ++pass) {
    std::shuffle(order.begin(), order.end(), rng);
    for (int i : order) {
      if (deadline.expired()) break;
      auto& way = ways[static_cast<std::size_t>(i)];
      met -= table.apply(way, -1);
      std::vector<int> fresh = spreadWay(rm, table, i, margin, parent, deadline);
      if (!fresh.empty()) way = std::move(fresh);
      met += table.apply(way, +1);
    }
    if (deadline.expired() && pass > 0) break;
    const bool better = kept_met < 0 || met < kept_met;
    if (better) {
      kept = ways;
      kept_met = met;
    }
    if (met == 0 || (pass >= 1 && !better)) break;
  }
  meetings_ = std::max<long long>(kept_met, 0);
  for (int i = 0; i < n && !kept.empty(); ++i) {
    const auto& way = kept[static_cast<std::size_t>(i)];
    for (std::size_t t = 0; t + 1 < way.size(); ++t) next_[static_cast<std::size_t>(i)][way[t]] = way[t + 1];
  }
}

int Spread::next(int i, int v) const {
  const auto& m = next_[static_cast<std::size_t>(i)];
  const auto it = m.find(v);
  return it == m.end() ? -1 : it->second;
}

}  // namespace earc::crowd
