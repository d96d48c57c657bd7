#include "earc/planning/lacam.hpp"

#include <algorithm>
#include <deque>
#include <memory>
#include <numeric>
#include <random>
#include <unordered_map>

#include "crowd_spread.hpp"
#include "earc/util/random.hpp"

namespace earc {

namespace {

// Steps a spread-out way may take beyond the robot's shortest.
constexpr int kSpreadMargin = 10;
// The search's first restart: after this many expansions per roadmap
// vertex, and at least kFirstRestart (solveLacam).
constexpr std::size_t kRestartExpansions = 4;
constexpr std::size_t kFirstRestart = 1000;

// A low-level constraint: robot `who` goes to `where`, on top of the
// parent's constraints.
struct Constraint {
  const Constraint* parent = nullptr;
  int who = -1;
  int where = -1;
  int depth = 0;
};

struct Node {
  std::vector<int> config;
  const Node* parent = nullptr;
  std::vector<double> priority;
  std::vector<int> order;  // robots by priority, highest first
  std::deque<const Constraint*> tree;
};

struct ConfigHash {
  std::size_t operator()(const std::vector<int>& c) const noexcept {
    std::size_t h = c.size();
    for (int v : c) h ^= static_cast<std::size_t>(v) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    return h;
  }
};

// PIBT's one-step configuration generator with priority inheritance, on
// geometric conflicts. Undecided robots are taken to stay where they are;
// a robot whose step would meet an undecided one (its "blocker") asks it
// to move first. A decision made inside an attempt that then fails is
// undone, but a robot that found no step keeps staying: its stay meets
// only the attempts above it on the stack, which fail in turn. So every
// kept decision is compatible with every other and with the undecided
// robots staying, and the last check below only catches constraints that
// left a robot nowhere to go.
class Pibt {
 public:
  Pibt(const CrowdRoadmap& rm, const crowd::Spread& spread, std::mt19937_64& rng)
      : rm_(rm), spread_(spread), rng_(rng), occupant_(static_cast<std::size_t>(rm.vertexCount()), -1) {}

  bool generate(const Node& node, const Constraint* constraints, std::vector<int>& next) {
    const std::vector<int>& now = node.config;
    now_ = &now;
    next_.assign(now.size(), -1);
    stayed_.assign(now.size(), 0);
    log_.clear();
    for (std::size_t i = 0; i < now.size(); ++i) occupant_[static_cast<std::size_t>(now[i])] = static_cast<int>(i);
    for (const Constraint* c = constraints; c && c->who >= 0; c = c->parent) next_[static_cast<std::size_t>(c->who)] = c->where;
    for (int i : node.order)
      if (next_[static_cast<std::size_t>(i)] < 0) step(i);
    bool ok = true;
    for (std::size_t i = 0; i < now.size() && ok; ++i) {
      const int u = now[i];
      for (int w : rm_.near(u)) {
        const int j = occupant_[static_cast<std::size_t>(w)];
        if (j <= static_cast<int>(i)) continue;
        if (rm_.conflict(static_cast<int>(i), {u, next_[i]}, j, {w, next_[static_cast<std::size_t>(j)]})) {
          ok = false;
          break;
        }
      }
    }
    for (int v : now) occupant_[static_cast<std::size_t>(v)] = -1;
    next = next_;
    return ok;
  }

 private:
  bool step(int i) {
    const int u = (*now_)[static_cast<std::size_t>(i)];
    std::vector<int> cands;
    rm_.placesFrom(i, u, cands);
    std::shuffle(cands.begin(), cands.end(), rng_);
    std::stable_sort(cands.begin(), cands.end(),
                     [&](int a, int b) { return rm_.distanceToGoal(i, a) < rm_.distanceToGoal(i, b); });
    // The next vertex of the robot's spread-out way, where it has one, first.
    if (const int guide = spread_.next(i, u); guide >= 0)
      if (auto it = std::find(cands.begin(), cands.end(), guide); it != cands.end()) std::rotate(cands.begin(), it, it + 1);
    // Head-on in a corridor, the robot ahead cannot make way by stepping
    // aside: the robot turns back instead and pulls the other after it
    // (the swap of LaCAM3's PIBT, Okumura 2024).
    const int partner = swapPartner(i, u, cands.front());
    if (partner >= 0) std::reverse(cands.begin(), cands.end());
    std::vector<int> blockers;
    bool first = true;
    for (int v : cands) {
      const bool was_first = first;
      first = false;
      if (rm_.distanceToGoal(i, v) >= CrowdRoadmap::kUnreachable) continue;
      blockers.clear();
      if (!admissible(i, u, v, blockers)) continue;
      if (v == u && !blockers.empty()) continue;
      const std::size_t mark = log_.size();
      decide(i, v);
      bool ok = true;
      for (int j : blockers) {
        const int nj = next_[static_cast<std::size_t>(j)];
        const int wj = (*now_)[static_cast<std::size_t>(j)];
        if (nj >= 0 ? rm_.conflict(i, {u, v}, j, {wj, nj}) : !step(j)) {
          ok = false;
          break;
        }
      }
      if (ok) {
        if (was_first && partner >= 0) pull(partner, u);
        return true;
      }
      undo(mark);
    }
    decide(i, u);
    stayed_[static_cast<std::size_t>(i)] = 1;
    return false;
  }

  // Whether robot i's step u -> v meets no decided step; the undecided
  // robots it would meet (were they to stay) go to `blockers`.
  bool admissible(int i, int u, int v, std::vector<int>& blockers) const {
    for (int w : rm_.near(u)) {
      const int j = occupant_[static_cast<std::size_t>(w)];
      if (j < 0 || j == i) continue;
      const int nj = next_[static_cast<std::size_t>(j)];
      if (nj >= 0) {
        if (rm_.conflict(i, {u, v}, j, {w, nj})) return false;
      } else if (rm_.conflict(i, {u, v}, j, {w, w})) {
        blockers.push_back(j);
      }
    }
    return true;
  }

  // The robot that should swap places with robot i (at u, wanting `best`
  // most), or -1: the one on `best` when it needs i's place to get by and
  // a pull can open a way; else a neighbour of i that i blocks that way.
  int swapPartner(int i, int u, int best) const {
    const int j = occupant_[static_cast<std::size_t>(best)];
    if (j >= 0 && j != i && next_[static_cast<std::size_t>(j)] < 0 && swapRequired(i, j, u, best) &&
        swapPossible(best, u))
      return j;
    for (int w : rm_.neighbours(u)) {
      const int k = occupant_[static_cast<std::size_t>(w)];
      if (k < 0 || k == i || w == best) continue;
      if (swapRequired(k, i, u, best) && swapPossible(best, u)) return k;
    }
    return -1;
  }

  // Ways out of v other than `from`, not counting dead ends where a robot
  // rests on its goal; `other` gets one of them.
  int waysOut(int v, int from, int& other) const {
    int n = 0;
    for (int w : rm_.neighbours(v)) {
      const int r = occupant_[static_cast<std::size_t>(w)];
      if (w == from || (rm_.neighbours(w).size() == 1 && r >= 0 && rm_.goal(r) == w)) continue;
      ++n;
      other = w;
    }
    return n;
  }

  // Whether pusher (at vp) and puller (at vq) must pass each other: along
  // the corridor ahead of the pusher there is no side way, and each would
  // get nearer its goal by being where the other is.
  bool swapRequired(int pusher, int puller, int vp, int vq) const {
    for (int guard = 0; rm_.distanceToGoal(pusher, vq) < rm_.distanceToGoal(pusher, vp) &&
                        guard < rm_.vertexCount();
         ++guard) {
      int next = -1;
      const int n = waysOut(vq, vp, next);
      if (n >= 2) return false;
      if (n <= 0) break;
      vp = vq;
      vq = next;
    }
    return rm_.distanceToGoal(puller, vp) < rm_.distanceToGoal(puller, vq) &&
           (rm_.distanceToGoal(pusher, vp) == 0 || rm_.distanceToGoal(pusher, vq) < rm_.distanceToGoal(pusher, vp));
  }

  // Whether pulling from vq away from vp reaches a branching before a dead end.
  bool swapPossible(int vp, int vq) const {
    const int origin = vp;
    for (int guard = 0; vq != origin && guard < rm_.vertexCount(); ++guard) {
      int next = -1;
      const int n = waysOut(vq, vp, next);
      if (n >= 2) return true;
      if (n <= 0) return false;
      vp = vq;
      vq = next;
    }
    return false;
  }

  // Robot j follows into u when that meets nothing decided or staying.
  void pull(int j, int u) {
    if (next_[static_cast<std::size_t>(j)] >= 0) return;
    const int w = (*now_)[static_cast<std::size_t>(j)];
    if (!rm_.usableBy(j, u)) return;
    std::vector<int> blockers;
    if (admissible(j, w, u, blockers) && blockers.empty()) decide(j, u);
  }

  void decide(int i, int v) {
    next_[static_cast<std::size_t>(i)] = v;
    log_.push_back(i);
  }

  void undo(std::size_t mark) {
    std::size_t keep = mark;
    for (std::size_t k = mark; k < log_.size(); ++k) {
      const int r = log_[k];
      if (stayed_[static_cast<std::size_t>(r)]) {
        log_[keep++] = r;
      } else {
        next_[static_cast<std::size_t>(r)] = -1;
      }
    }
    log_.resize(keep);
  }

  const CrowdRoadmap& rm_;
  const crowd::Spread& spread_;
  std::mt19937_64& rng_;
  std::vector<int> occupant_;
  const std::vector<int>* now_ = nullptr;
  std::vector<int> next_;
  std::vector<char> stayed_;
  std::vector<int> log_;
};

}  // namespace

namespace {

// How one search attempt ended.
enum class Attempt { kSolved, kExhausted, kOverBudget, kTimedOut };

// LaCAM's search from the starts with the given PIBT, within `max_expansions`
// (0: no cap) and the deadline; on success the configurations go to result.
Attempt searchOnce(const CrowdRoadmap& rm, Pibt& pibt, std::mt19937_64& rng, const Deadline& deadline,
                   std::size_t max_expansions, LacamResult& result) {
  const int n = rm.robotCount();
  std::vector<int> goals(static_cast<std::size_t>(n)), starts(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    goals[static_cast<std::size_t>(i)] = rm.goal(i);
    starts[static_cast<std::size_t>(i)] = rm.start(i);
  }
  std::deque<Node> nodes;
  std::deque<Constraint> constraints;
  const Constraint* root_constraint = &constraints.emplace_back();
  std::unordered_map<std::vector<int>, Node*, ConfigHash> explored;
  std::vector<Node*> open;

  auto makeNode = [&](std::vector<int> config, const Node* parent) {
    Node& node = nodes.emplace_back();
    node.config = std::move(config);
    node.parent = parent;
    node.priority.resize(static_cast<std::size_t>(n));
    // PIBT's priorities: a robot away from its goal gains one a step, and
    // one at its goal drops back to its fraction; the first ones order by
    // distance (the fraction keeps them below one).
    const double scale = 1.0 / std::max(1, rm.vertexCount());
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const bool at_goal = node.config[k] == goals[k];
      if (!parent) {
        node.priority[k] = rm.distanceToGoal(i, node.config[k]) * scale;
      } else {
        const double p = parent->priority[k];
        node.priority[k] = at_goal ? p - std::floor(p) : p + 1.0;
      }
    }
    node.order.resize(static_cast<std::size_t>(n));
    std::iota(node.order.begin(), node.order.end(), 0);
    std::stable_sort(node.order.begin(), node.order.end(), [&](int a, int b) {
      return node.priority[static_cast<std::size_t>(a)] > node.priority[static_cast<std::size_t>(b)];
    });
    node.tree.push_back(root_constraint);
    explored.emplace(node.config, &node);
    ++result.nodes;
    return &node;
  };

  open.push_back(makeNode(starts, nullptr));
  std::vector<int> next;
  std::vector<int> cands;
  std::size_t expansions = 0;
  while (!open.empty()) {
    if ((result.expansions & 15) == 0 && deadline.expired()) return Attempt::kTimedOut;
    if (max_expansions > 0 && expansions >= max_expansions) return Attempt::kOverBudget;
    Node* top = open.back();
    if (top->config == goals) {
      for (const Node* v = top; v; v = v->parent) result.configs.push_back(v->config);
      std::reverse(result.configs.begin(), result.configs.end());
      return Attempt::kSolved;
    }
    if (top->tree.empty()) {
      open.pop_back();
      continue;
    }
    const Constraint* c = top->tree.front();
    top->tree.pop_front();
    if (c->depth < n) {
      // The next robot in priority order gets one child constraint per
      // place it may go to, in random order.
      const int i = top->order[static_cast<std::size_t>(c->depth)];
      const int u = top->config[static_cast<std::size_t>(i)];
      rm.placesFrom(i, u, cands);
      std::shuffle(cands.begin(), cands.end(), rng);
      for (int v : cands) top->tree.push_back(&constraints.emplace_back(Constraint{c, i, v, c->depth + 1}));
    }
    ++result.expansions;
    ++expansions;
    if (!pibt.generate(*top, c, next)) continue;
    auto it = explored.find(next);
    if (it != explored.end()) {
      // Known already: search on from there (LaCAM's re-insertion keeps
      // the search complete without revisiting its subtree from scratch).
      open.push_back(it->second);
      continue;
    }
    open.push_back(makeNode(next, top));
  }
  return Attempt::kExhausted;
}

}  // namespace

LacamResult solveLacam(const CrowdRoadmap& rm, const Deadline& deadline, std::uint64_t seed, std::size_t first_restart) {
  LacamResult result;
  if (!rm.problem().empty()) {
    result.why = rm.problem();
    return result;
  }
  // Up to a quarter of the time left (at most a second) spreads the ways out.
  const crowd::Spread spread(rm, kSpreadMargin, deadline.capped(std::min(1.0, deadline.remaining() / 4)),
                             splitSeed(seed, 8));
  result.spread_meetings = spread.meetings();
  // The search's time is heavy-tailed: most seeds go nearly straight to the
  // goals (expansions about the plan's steps), a few wander for thousands.
  // So it restarts with fresh random choices after kRestartExpansions per
  // roadmap vertex, twice as many each time; the searches being complete,
  // growing caps keep the whole complete. The first attempt is the search
  // without restarts for as long as it stays under the first cap.
  std::mt19937_64 rng(splitSeed(seed, 7));
  Pibt pibt(rm, spread, rng);
  std::size_t cap = first_restart > 0 ? first_restart
                                      : std::max<std::size_t>(kFirstRestart,
                                                              kRestartExpansions * static_cast<std::size_t>(rm.vertexCount()));
  for (std::uint64_t attempt = 0;; ++attempt) {
    if (attempt > 0) rng.seed(splitSeed(seed, 7 + (attempt << 8)));
    switch (searchOnce(rm, pibt, rng, deadline, cap, result)) {
      case Attempt::kSolved:
        result.solved = true;
        return result;
      case Attempt::kExhausted:
        result.why = "the roadmap has no conflict-free way to the goals";
        return result;
      case Attempt::kTimedOut:
        result.timed_out = true;
        result.why = "time limit";
        return result;
      case Attempt::kOverBudget:
        ++result.restarts;
        cap *= 2;
        break;
    }
  }
}

}  // namespace earc
