#include "earc/planning/lattice_lns.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>
#include <tuple>

#include "earc/util/random.hpp"
#include "lattice_search.hpp"
#include "tick_search.hpp"

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
// How each robot is replanned: shortest ways, or weighted A*, which on
// maps with many equally short ways (a warehouse's aisles) finds a way as
// good as the old one in a fraction of the expansions. In a dense crowd
// the shortest ways break ties towards staying off other robots' goals
// before they arrive: a robot whose goal others cross waits for the last.
struct SearchKind {
  double weight;
  bool avoid_goals;
};
constexpr std::array<SearchKind, 2> kSearches = {{{1.0, true}, {1.5, false}}};
// A crowd is dense from one robot per this many roadmap vertices.
constexpr int kDenseVertices = 5;
constexpr std::size_t kGroupSize = 4;

// Where the search runs: the roadmap's synchronous steps, or ticks with
// diagonals (tick_search.hpp). Both keep a vertex per time unit.
struct StepSpace {
  using Occupancy = lattice::Occupancy;
  using Search = lattice::StepSearch;
  const CrowdRoadmap& rm;
  const CrowdRoadmap& base() const { return rm; }
  long long distance(int i, int v) const { return rm.distanceToGoal(i, v); }
  template <class F>
  void forMoves(int v, F f) const {
    for (int w : rm.neighbours(v)) f(w, 1);
  }
};
struct TickSpace {
  using Occupancy = ticks::Occupancy;
  using Search = ticks::TickSearch;
  const ticks::Lattice& lat;
  const ticks::Lattice& base() const { return lat; }
  long long distance(int i, int v) const { return lat.distance(i, v); }
  template <class F>
  void forMoves(int v, F f) const {
    for (const auto& [w, a] : lat.moves(v)) f(w, ticks::ticksOf(a));
  }
};

// Large-neighbourhood search on the lattice. Which draw and search come
// next is chosen in proportion to weights that follow what each recently
// gained per second (adaptive LNS, as MAPF-LNS does, per unit of time).
// Groups of four: larger ones gained less per second on the MovingAI files.
template <class Space>
class LatticeLns {
 public:
  LatticeLns(const Space& space, const CrowdRoadmap& rm, std::vector<lattice::VertexPath>& paths, std::uint64_t seed)
      : space_(space), rm_(rm), paths_(paths), occ_(space.base(), paths), search_(space.base()), rng_(splitSeed(seed, 11)) {
    n_ = rm.robotCount();
    for (const auto& p : paths_) soc_ += pathCost(p);
    dense_ = kDenseVertices * n_ >= rm.vertexCount();
    for (int v = 0; v < rm.vertexCount(); ++v)
      if (rm.neighbours(v).size() >= 3) junctions_.push_back(v);
    weights_.fill(1.0);
  }

  long long sumOfCosts() const { return soc_; }
  int tried() const { return tried_; }
  int kept() const { return kept_; }
  long long expansions() const { return search_.expansions(); }
  const std::vector<RefinePoint>& history() const { return history_; }

  // A point of the cost history; with `always` false, only once 0.5% was
  // saved since the last one (a hundred points or so per phase).
  void record(const Deadline& deadline, bool always) {
    if (!always && !history_.empty() && 200 * (history_.back().sum_of_costs - soc_) < history_.back().sum_of_costs) return;
    history_.push_back({sincePhaseBegan(deadline), soc_, makespan()});
  }

  // The last point of the history: the plan as it ends. A change kept at an
  // equal sum of costs may have moved the makespan; then the last point after
  // the start says so at the end's time, keeping the sums falling point by point.
  void finish(const Deadline& deadline) {
    RefinePoint& last = history_.back();
    const long long m = makespan();
    if (last.sum_of_costs == soc_ && last.makespan == m) return;
    if (last.sum_of_costs == soc_ && history_.size() > 1) {
      last = {sincePhaseBegan(deadline), soc_, m};
      return;
    }
    record(deadline, true);
  }

  long long makespan() const {
    long long m = 0;
    for (const auto& p : paths_) m = std::max(m, pathCost(p));
    return m;
  }

  // Each delayed robot alone, most delayed first, by the cheaper search.
  void firstRound(const Deadline& deadline, int& rounds, int max_rounds) {
    work0_ = t_work_done;
    began_ = std::chrono::steady_clock::now();
    record(deadline, true);
    history_.back().s = 0.0;
    std::vector<int> order(static_cast<std::size_t>(n_));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return delay(a) > delay(b); });
    for (int i : order) {
      if (rounds++ >= max_rounds || deadline.expired()) break;
      if (delay(i) > 0) replan({i}, deadline, kSearches[1]);
    }
    last_ = now(deadline);  // the first step's gain is per its own time
  }

  // One drawn neighbourhood, replanned; updates the draw's weight.
  void step(const Deadline& deadline) {
    const std::size_t arm = pickArm();
    std::vector<int> group =
        drawGroup(kDraws[arm / kSearches.size()], std::min<std::size_t>(kGroupSize, static_cast<std::size_t>(n_)));
    const long long gain = replan(group, deadline, kSearches[arm % kSearches.size()]);
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

  // Seconds since firstRound began on now()'s clock; counted work as a
  // difference of counts, so that the same run gives the same figure.
  double sincePhaseBegan(const Deadline& deadline) const {
    if (deadline.countsWork()) return static_cast<double>(t_work_done - work0_) / kWorkPerBudgetSecond;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - began_).count();
  }

  long long delay(int i) const {
    return pathCost(paths_[static_cast<std::size_t>(i)]) - space_.distance(i, rm_.start(i));
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
      while (p[t] < 0) --t;  // back to the vertex a move began on
      int v = p[t];
      for (int len = 0; len < 2 * static_cast<int>(g.size) + 8 && !g.full(); ++len) {
        std::vector<std::pair<int, int>> ok;
        space_.forMoves(v, [&](int w, int d) {
          if (rm_.usableBy(r, w) && static_cast<long long>(t) + d + space_.distance(r, w) < cost) ok.emplace_back(w, d);
        });
        if (ok.empty()) break;
        const auto [next, d] = ok[uniformIndex(rng_, ok.size())];
        v = next;
        t += static_cast<std::size_t>(d);
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
        if (w < 0) continue;  // moving between two vertices
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
  long long replan(const std::vector<int>& group, const Deadline& deadline, SearchKind kind) {
    std::vector<lattice::VertexPath> old;
    for (int i : group) old.push_back(paths_[static_cast<std::size_t>(i)]);
    ++tried_;
    long long before = 0, rest = 0;
    for (int i : group) {
      before += pathCost(paths_[static_cast<std::size_t>(i)]);
      rest += space_.distance(i, rm_.start(i));
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
      rest -= space_.distance(i, rm_.start(i));
      auto p = search_.search(occ_, i, deadline, before - after - rest, searchCap(rm_), kind.weight, kind.avoid_goals && dense_);
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
      if (after < before) record(deadline, false);
      return before - after;
    }
    for (int i : placed) occ_.remove(i);
    for (std::size_t k = 0; k < group.size(); ++k) {
      paths_[static_cast<std::size_t>(group[k])] = std::move(old[k]);
      occ_.put(group[k]);
    }
    return 0;
  }

  const Space& space_;
  const CrowdRoadmap& rm_;
  std::vector<lattice::VertexPath>& paths_;
  typename Space::Occupancy occ_;
  typename Space::Search search_;
  std::mt19937_64 rng_;
  int n_ = 0;
  bool dense_ = false;  // kDenseVertices
  long long soc_ = 0;
  int tried_ = 0, kept_ = 0;
  int last_delayed_ = -1;
  const std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
  double last_ = 0.0;
  std::uint64_t work0_ = 0;  // t_work_done when firstRound began
  std::chrono::steady_clock::time_point began_;
  std::vector<RefinePoint> history_;
  std::vector<int> junctions_;
  std::vector<int> rank_;  // throughJunction's area, per vertex
  std::array<double, kDraws.size() * kSearches.size()> weights_{};
};

// The search itself, with the figures refineOnLattice and
// refineWithDiagonals report.
template <class Space>
LatticeRefineStats runLns(const Space& space, const CrowdRoadmap& rm, std::vector<lattice::VertexPath>& paths,
                          const Deadline& deadline, std::uint64_t seed, int max_rounds) {
  LatticeLns<Space> lns(space, rm, paths, seed);
  const long long first = lns.sumOfCosts();
  int rounds = 0;
  lns.firstRound(deadline, rounds, max_rounds);
  while (rounds++ < max_rounds && !deadline.expired() && rm.robotCount() > 1) lns.step(deadline);
  lns.finish(deadline);
  LatticeRefineStats stats;
  stats.history = lns.history();
  stats.sum_of_costs_before = first;
  stats.sum_of_costs_after = lns.sumOfCosts();
  stats.neighbourhoods = lns.tried();
  stats.kept = lns.kept();
  stats.expansions = lns.expansions();
  return stats;
}

// Time-stamped paths of tick paths: `per_tick` time steps of straight
// motion per tick; headings turn from the first step at the robot's rate
// (every vertex is on the lattice, where the bounding disc stands for any
// heading), a robot turning on at its goal when its way is too short.
std::vector<Path> pathsOfTicks(const CrowdRoadmap& rm, const std::vector<ticks::TickPath>& paths, int per_tick,
                               const std::vector<std::vector<double>>& starts,
                               const std::vector<std::vector<double>>& goals) {
  std::vector<Path> out;
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const ticks::TickPath& tp = paths[k];
    const double rate = rm.model(static_cast<int>(k)).resolution().rotation;
    const double turn = geo::angleDiff(starts[k][2], goals[k][2]);
    const double sign = turn < 0 ? -1.0 : 1.0;
    double heading = starts[k][2], left = std::abs(turn);
    Path p(3);
    p.push(starts[k]);
    std::size_t t = 0;
    while (t + 1 < tp.size() || left > 0) {
      // From vertex u at tick t to the next vertex, ticks later.
      const int u = tp[std::min(t, tp.size() - 1)];
      std::size_t t1 = t + 1;
      while (t1 < tp.size() && tp[t1] < 0) ++t1;
      const geo::Vec2 a = rm.position(u), b = rm.position(ticks::vertexAt(tp, t1));
      const int steps = per_tick * static_cast<int>(t1 - t);
      for (int s = 1; s <= steps; ++s) {
        const double f = static_cast<double>(s) / steps;
        const double d = std::min(rate, left);
        heading += sign * d;
        left -= d;
        const double q[3] = {a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, heading};
        p.push(q);
      }
      t = t1;
    }
    std::copy(goals[k].begin(), goals[k].end(), p.mutableAt(p.size() - 1));
    std::copy(starts[k].begin(), starts[k].end(), p.mutableAt(0));
    out.push_back(std::move(p));
  }
  return out;
}

// The share of refineWithDiagonals' time spent on ticks, after the cheaper
// steps (0.3, 0.5 and 0.8 within 0.3% of each other in the rooms).
constexpr double kDiagonalShare = 0.3;

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
  const StepSpace space{rm};
  LatticeRefineStats stats = runLns(space, rm, paths, deadline, seed, max_rounds);
  std::size_t h = 1;
  for (const auto& p : paths) h = std::max(h, p.size());
  configs.assign(h, std::vector<int>(static_cast<std::size_t>(n)));
  for (std::size_t t = 0; t < h; ++t)
    for (int i = 0; i < n; ++i)
      configs[t][static_cast<std::size_t>(i)] = lattice::vertexAt(paths[static_cast<std::size_t>(i)], t);
  return stats;
}

std::optional<std::vector<Path>> refineWithDiagonals(const CrowdRoadmap& rm, const std::vector<std::vector<int>>& configs,
                                                     const Deadline& deadline, std::uint64_t seed,
                                                     const std::vector<std::vector<double>>& starts,
                                                     const std::vector<std::vector<double>>& goals, LatticeRefineStats& stats,
                                                     int max_rounds) {
  const std::optional<ticks::Lattice> lat = ticks::Lattice::make(rm);
  if (!lat) return std::nullopt;
  // First on the roadmap's steps, whose searches are cheaper: they undo
  // LaCAM's jams faster; then on ticks, where the diagonals cut corners.
  std::vector<std::vector<int>> steps = configs;
  const double share = kDiagonalShare;
  const LatticeRefineStats axis = refineOnLattice(rm, steps, deadline.capped((1.0 - share) * deadline.remaining()), seed,
                                              static_cast<int>((1.0 - share) * max_rounds));
  // A roadmap step is two ticks: a wait of two, or an axis move.
  const int n = rm.robotCount();
  std::vector<ticks::TickPath> paths(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    ticks::TickPath& p = paths[static_cast<std::size_t>(i)];
    p.push_back(steps.front()[static_cast<std::size_t>(i)]);
    for (std::size_t t = 1; t < steps.size(); ++t) {
      const int v = steps[t][static_cast<std::size_t>(i)];
      p.push_back(v == steps[t - 1][static_cast<std::size_t>(i)] ? v : -1);
      p.push_back(v);
    }
    dropStays(p);
  }
  const TickSpace space{*lat};
  stats = runLns(space, rm, paths, deadline, splitSeed(seed, 13), max_rounds - static_cast<int>((1.0 - share) * max_rounds));
  stats.axis = axis;
  stats.steps_per_tick = lat->stepsPerTick();  // the sums of costs are in ticks
  return pathsOfTicks(rm, paths, lat->stepsPerTick(), starts, goals);
}

}  // namespace earc
