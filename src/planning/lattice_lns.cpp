#include "earc/planning/lattice_lns.hpp"

#include <algorithm>
#include <numeric>
#include <random>

#include "earc/util/random.hpp"
#include "lattice_search.hpp"

namespace earc {

namespace {

// A search's cap on expansions: one that floods the space-time graph
// finds no better way in a neighbourhood worth its time.
std::size_t searchCap(const CrowdRoadmap& rm) { return 64 * static_cast<std::size_t>(rm.vertexCount()) + 4096; }

// Steps until the robot is at its goal for good (trailing stays dropped).
void dropStays(lattice::VertexPath& p) {
  while (p.size() > 1 && p[p.size() - 2] == p.back()) p.pop_back();
}

long long pathCost(const lattice::VertexPath& p) { return static_cast<long long>(p.size()) - 1; }

}  // namespace

long long latticeSumOfCosts(const CrowdRoadmap& rm, const std::vector<std::vector<int>>& configs) {
  long long soc = 0;
  for (int i = 0; i < rm.robotCount(); ++i) {
    lattice::VertexPath p;
    for (const auto& c : configs) p.push_back(c[static_cast<std::size_t>(i)]);
    dropStays(p);
    soc += pathCost(p);
  }
  return soc;
}

nlohmann::json refineOnLattice(const CrowdRoadmap& rm, std::vector<std::vector<int>>& configs, const Deadline& deadline,
                               std::uint64_t seed, int max_rounds) {
  const int n = rm.robotCount();
  std::vector<lattice::VertexPath> paths(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (const auto& c : configs) paths[static_cast<std::size_t>(i)].push_back(c[static_cast<std::size_t>(i)]);
    dropStays(paths[static_cast<std::size_t>(i)]);
  }
  long long soc = 0;
  for (const auto& p : paths) soc += pathCost(p);
  const long long first = soc;
  lattice::StepSearch search(rm);
  std::mt19937_64 rng(splitSeed(seed, 11));
  lattice::Occupancy occ(rm, paths);
  int tried = 0, kept = 0;
  // Robots most delayed (steps beyond their own shortest way) first.
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  auto delay = [&](int i) { return pathCost(paths[static_cast<std::size_t>(i)]) - rm.distanceToGoal(i, rm.start(i)); };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return delay(a) > delay(b); });
  // Replans `group` one after another (random order) and keeps the new
  // paths when they cost no more (equal ones let the search move along a
  // plateau); else puts the old ones back.
  auto replanGroup = [&](const std::vector<int>& group) {
    std::vector<lattice::VertexPath> old;
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
      auto p = search.search(occ, i, deadline, 16, searchCap(rm));
      if (!p || (after += pathCost(*p)) > before) {
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
  constexpr std::size_t kNeighbourhood = 4;
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
      const int r = order[static_cast<std::size_t>(
          uniformIndex(rng, std::min<std::uint64_t>(static_cast<std::uint64_t>(n), 16)))];
      add(r);
      const lattice::VertexPath& p = paths[static_cast<std::size_t>(r)];
      const std::size_t t = uniformIndex(rng, p.size());
      const int v = p[t];
      for (std::size_t dt = 0; dt < 8 && group.size() < kNeighbourhood; ++dt)
        for (int i = 0; i < n; ++i) {
          const lattice::VertexPath& q = paths[static_cast<std::size_t>(i)];
          for (int w : rm.near(v))
            if (lattice::vertexAt(q, t + dt) == w || (t >= dt && lattice::vertexAt(q, t - dt) == w)) add(i);
        }
    }
    while (group.size() < std::min<std::size_t>(kNeighbourhood, static_cast<std::size_t>(n)))
      add(static_cast<int>(uniformIndex(rng, static_cast<std::uint64_t>(n))));
    std::sort(group.begin(), group.end());
    replanGroup(group);
    if (rng() % 8 == 0) std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return delay(a) > delay(b); });
  }
  std::size_t h = 1;
  for (const auto& p : paths) h = std::max(h, p.size());
  configs.assign(h, std::vector<int>(static_cast<std::size_t>(n)));
  for (std::size_t t = 0; t < h; ++t)
    for (int i = 0; i < n; ++i)
      configs[t][static_cast<std::size_t>(i)] = lattice::vertexAt(paths[static_cast<std::size_t>(i)], t);
  return {{"sum_of_costs_before", first},
          {"sum_of_costs_after", soc},
          {"neighbourhoods", tried},
          {"kept", kept},
          {"expansions", search.expansions()}};
}

}  // namespace earc
