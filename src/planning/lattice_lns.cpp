#include "earc/planning/lattice_lns.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <numeric>
#include <random>
#include <tuple>

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

// How a neighbourhood is drawn, as in MAPF-LNS: the robots in a delayed
// robot's way, the robots through a junction of the roadmap, or any.
enum class Draw { kInTheWay, kJunction, kRandom };
constexpr std::array<Draw, 3> kDraws = {Draw::kInTheWay, Draw::kJunction, Draw::kRandom};
// How greedily each robot is replanned: shortest ways, or weighted A*,
// which on maps with many equally short ways (a warehouse's aisles) finds
// a way as good as the old one in a fraction of the expansions.
constexpr std::array<double, 2> kWeights = {1.0, 1.5};
constexpr std::size_t kGroupSize = 4;

// Large-neighbourhood search on the lattice. Which draw and search come
// next is chosen in proportion to weights that follow what each recently
// gained per second (adaptive LNS, as MAPF-LNS does, per unit of time).
// Groups of four: larger ones gained less per second on the MovingAI files.
class LatticeLns {
 public:
  LatticeLns(const CrowdRoadmap& rm, std::vector<lattice::VertexPath>& paths, std::uint64_t seed)
      : rm_(rm), paths_(paths), occ_(rm, paths), search_(rm), rng_(splitSeed(seed, 11)) {
    n_ = rm.robotCount();
    for (const auto& p : paths_) soc_ += pathCost(p);
    for (int v = 0; v < rm.vertexCount(); ++v)
      if (rm.neighbours(v).size() >= 3) junctions_.push_back(v);
    weights_.fill(1.0);
  }

  long long sumOfCosts() const { return soc_; }
  int tried() const { return tried_; }
  int kept() const { return kept_; }
  long long expansions() const { return search_.expansions(); }

  // Each delayed robot alone, most delayed first, by the cheaper search.
  void firstRound(const Deadline& deadline, int& rounds, int max_rounds) {
    std::vector<int> order(static_cast<std::size_t>(n_));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return delay(a) > delay(b); });
    for (int i : order) {
      if (rounds++ >= max_rounds || deadline.expired()) break;
      if (delay(i) > 0) replan({i}, deadline, kWeights.back());
    }
    last_ = now(deadline);  // the first step's gain is per its own time
  }

  // One drawn neighbourhood, replanned; updates the draw's weight.
  void step(const Deadline& deadline) {
    const std::size_t arm = pickArm();
    std::vector<int> group =
        drawGroup(kDraws[arm / kWeights.size()], std::min<std::size_t>(kGroupSize, static_cast<std::size_t>(n_)));
    const long long gain = replan(group, deadline, kWeights[arm % kWeights.size()]);
    const double t = now(deadline);
    const double per = 1e-3 * static_cast<double>(gain) / std::max(1e-9, t - last_);
    last_ = t;
    constexpr double kReaction = 0.05;
    weights_[arm] = (1 - kReaction) * weights_[arm] + kReaction * std::max(0.01, per);
  }

 private:
  // Seconds on the budget's clock: of work done when the budget counts
  // work (so that a run is the same run however loaded the machine).
  double now(const Deadline& deadline) const {
    if (deadline.countsWork()) return workSecondsDone();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
  }

  long long delay(int i) const {
    return pathCost(paths_[static_cast<std::size_t>(i)]) - rm_.distanceToGoal(i, rm_.start(i));
  }

  std::size_t pickArm() {
    double total = 0;
    for (double w : weights_) total += w;
    double x = std::uniform_real_distribution<double>(0, total)(rng_);
    for (std::size_t a = 0; a < weights_.size(); ++a)
      if ((x -= weights_[a]) <= 0) return a;
    return weights_.size() - 1;
  }

  // Robots drawn so far, up to a size.
  struct Group {
    std::vector<int> members;
    std::vector<char> in;
    std::size_t size;
    void add(int r) {
      if (r >= 0 && !in[static_cast<std::size_t>(r)] && !full()) {
        in[static_cast<std::size_t>(r)] = 1;
        members.push_back(r);
      }
    }
    bool full() const { return members.size() >= size; }
  };

  std::vector<int> drawGroup(Draw draw, std::size_t size) {
    Group g{{}, std::vector<char>(static_cast<std::size_t>(n_), 0), size};
    if (draw == Draw::kInTheWay) inTheWay(g);
    if (draw == Draw::kJunction && !junctions_.empty()) throughJunction(g);
    while (!g.full()) g.add(static_cast<int>(uniformIndex(rng_, static_cast<std::uint64_t>(n_))));
    std::sort(g.members.begin(), g.members.end());
    return g.members;
  }

  // The most delayed of eight robots drawn (not the last one chosen), then
  // the robots met by random walks from points of its path along steps
  // that could still make it shorter.
  void inTheWay(Group& g) {
    int r = -1;
    long long worst = 0;
    for (int tries = 0; tries < 8; ++tries) {
      const int c = static_cast<int>(uniformIndex(rng_, static_cast<std::uint64_t>(n_)));
      if (delay(c) > worst && c != last_delayed_) {
        worst = delay(c);
        r = c;
      }
    }
    if (r < 0) return;
    last_delayed_ = r;
    g.add(r);
    const lattice::VertexPath& p = paths_[static_cast<std::size_t>(r)];
    const long long cost = pathCost(p);
    for (int walk = 0; walk < 4 && !g.full(); ++walk) {
      std::size_t t = uniformIndex(rng_, p.size());
      int v = p[t];
      for (int len = 0; len < 2 * static_cast<int>(g.size) + 8 && !g.full(); ++len) {
        const std::vector<int>& next = rm_.neighbours(v);
        std::vector<int> ok;
        for (int w : next)
          if (rm_.usableBy(r, w) && static_cast<long long>(t) + 1 + rm_.distanceToGoal(r, w) < cost) ok.push_back(w);
        if (ok.empty()) break;
        v = ok[uniformIndex(rng_, ok.size())];
        ++t;
        for (int w : rm_.near(v)) g.add(occ_.at(w, t));
      }
    }
  }

  // The robots whose paths pass a random junction or the vertices nearest
  // it (breadth first), nearest first, until the group is full.
  void throughJunction(Group& g) {
    constexpr std::size_t kArea = 16;
    const int v0 = junctions_[uniformIndex(rng_, junctions_.size())];
    std::vector<int> area = {v0};
    rank_.assign(static_cast<std::size_t>(rm_.vertexCount()), -1);
    rank_[static_cast<std::size_t>(v0)] = 0;
    for (std::size_t k = 0; k < area.size() && area.size() < kArea; ++k)
      for (int w : rm_.neighbours(area[k]))
        if (rank_[static_cast<std::size_t>(w)] < 0 && area.size() < kArea) {
          rank_[static_cast<std::size_t>(w)] = static_cast<int>(area.size());
          area.push_back(w);
        }
    // (rank of the nearest area vertex on the path, random tie-break, robot)
    std::vector<std::tuple<int, std::uint64_t, int>> through;
    for (int i = 0; i < n_; ++i) {
      int best = -1;
      for (int w : paths_[static_cast<std::size_t>(i)]) {
        const int r = rank_[static_cast<std::size_t>(w)];
        if (r >= 0 && (best < 0 || r < best)) best = r;
      }
      if (best >= 0) through.emplace_back(best, rng_(), i);
    }
    std::sort(through.begin(), through.end());
    for (const auto& [r, tie, i] : through) g.add(i);
  }

  // Replans `group` one after another (random order) and keeps the new
  // paths when they cost no more (equal ones let the search move along a
  // plateau); else puts the old ones back. Returns the steps saved.
  long long replan(const std::vector<int>& group, const Deadline& deadline, double weight) {
    std::vector<lattice::VertexPath> old;
    for (int i : group) old.push_back(paths_[static_cast<std::size_t>(i)]);
    ++tried_;
    long long before = 0, rest = 0;
    for (int i : group) {
      before += pathCost(paths_[static_cast<std::size_t>(i)]);
      rest += rm_.distanceToGoal(i, rm_.start(i));
      occ_.remove(i);
    }
    std::vector<int> shuffled = group;
    std::shuffle(shuffled.begin(), shuffled.end(), rng_);
    long long after = 0;
    std::vector<int> placed;
    bool ok = true;
    for (int i : shuffled) {
      // What the robots still to plan need at least: a robot's way may
      // take what the group had, less that.
      rest -= rm_.distanceToGoal(i, rm_.start(i));
      auto p = search_.search(occ_, i, deadline, before - after - rest, searchCap(rm_), weight);
      if (!p || (after += pathCost(*p)) > before) {
        ok = false;
        break;
      }
      paths_[static_cast<std::size_t>(i)] = std::move(*p);
      occ_.put(i);
      placed.push_back(i);
    }
    if (ok) {
      soc_ += after - before;
      ++kept_;
      return before - after;
    }
    for (int i : placed) occ_.remove(i);
    for (std::size_t k = 0; k < group.size(); ++k) {
      paths_[static_cast<std::size_t>(group[k])] = std::move(old[k]);
      occ_.put(group[k]);
    }
    return 0;
  }

  const CrowdRoadmap& rm_;
  std::vector<lattice::VertexPath>& paths_;
  lattice::Occupancy occ_;
  lattice::StepSearch search_;
  std::mt19937_64 rng_;
  int n_ = 0;
  long long soc_ = 0;
  int tried_ = 0, kept_ = 0;
  int last_delayed_ = -1;
  const std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
  double last_ = 0.0;
  std::vector<int> junctions_;
  std::vector<int> rank_;  // throughJunction's area, per vertex
  std::array<double, kDraws.size() * kWeights.size()> weights_{};
};

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

LatticeRefineStats refineOnLattice(const CrowdRoadmap& rm, std::vector<std::vector<int>>& configs,
                                   const Deadline& deadline, std::uint64_t seed, int max_rounds) {
  const int n = rm.robotCount();
  std::vector<lattice::VertexPath> paths(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (const auto& c : configs) paths[static_cast<std::size_t>(i)].push_back(c[static_cast<std::size_t>(i)]);
    dropStays(paths[static_cast<std::size_t>(i)]);
  }
  LatticeLns lns(rm, paths, seed);
  const long long first = lns.sumOfCosts();
  int rounds = 0;
  lns.firstRound(deadline, rounds, max_rounds);
  while (rounds++ < max_rounds && !deadline.expired() && n > 1) lns.step(deadline);
  std::size_t h = 1;
  for (const auto& p : paths) h = std::max(h, p.size());
  configs.assign(h, std::vector<int>(static_cast<std::size_t>(n)));
  for (std::size_t t = 0; t < h; ++t)
    for (int i = 0; i < n; ++i)
      configs[t][static_cast<std::size_t>(i)] = lattice::vertexAt(paths[static_cast<std::size_t>(i)], t);
  LatticeRefineStats stats;
  stats.sum_of_costs_before = first;
  stats.sum_of_costs_after = lns.sumOfCosts();
  stats.neighbourhoods = lns.tried();
  stats.kept = lns.kept();
  stats.expansions = lns.expansions();
  return stats;
}

}  // namespace earc
