#include "tick_search.hpp"

#include <algorithm>
#include <cmath>

namespace earc::ticks {

namespace {

constexpr int kDir[kMoveTypes][2] = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
constexpr int kStates = 21;

int typeOfState(int s) { return s == 0 ? 0 : (s <= 8 ? 1 + (s - 1) / 2 : 5 + (s - 9) / 3); }
int phaseOfState(int s) { return s == 0 ? 0 : (s <= 8 ? (s - 1) % 2 : (s - 9) % 3); }

// A tick in state s from a vertex at the origin, in cells: where it begins
// and how far it goes.
geo::Vec2 tickStart(int s) {
  const int a = typeOfState(s);
  const double f = static_cast<double>(phaseOfState(s)) / ticksOf(a);
  return {kDir[a][0] * f, kDir[a][1] * f};
}
geo::Vec2 tickMotion(int s) {
  const int a = typeOfState(s);
  return {static_cast<double>(kDir[a][0]) / ticksOf(a), static_cast<double>(kDir[a][1]) / ticksOf(a)};
}
// Its slot, in half cells from the vertex: the nearest half-cell point
// (a vertex, an edge's middle, a square's centre).
std::pair<int, int> slotOffset(int s) {
  const geo::Vec2 p = tickStart(s);
  return {static_cast<int>(std::lround(2.0 * p.x)), static_cast<int>(std::lround(2.0 * p.y))};
}

}  // namespace

int Lattice::state(int a, int phase) { return a == 0 ? 0 : (a <= 4 ? 1 + (a - 1) * 2 + phase : 9 + (a - 5) * 3 + phase); }

int Lattice::moveType(int u, int v) const {
  if (u == v) return 0;
  for (const auto& [w, a] : moves(u))
    if (w == v) return a;
  return -1;
}

bool Lattice::meet(int u, int a_state, int w, int b_state) const {
  const geo::Vec2 a0 = rm_->position(u) + tickStart(a_state), b0 = rm_->position(w) + tickStart(b_state);
  return closestApproach(a0, a0 + tickMotion(a_state), b0, b0 + tickMotion(b_state)) < 2.0 * rm_->radius() + 1e-9;
}

std::optional<Lattice> Lattice::make(const CrowdRoadmap& rm) {
  // Two robots in one square's centre slot stand within sqrt(2)/3 of each
  // other: with discs wider than that they conflict, so a slot holds one.
  if (!rm.gridAligned() || !rm.allOnLattice() || rm.stepsPerEdge() % 2 != 0 ||
      2.0 * rm.radius() <= std::sqrt(2.0) / 3.0 + 1e-6 || rm.vertexCount() == 0)
    return std::nullopt;
  Lattice lat(rm);
  const int nv = rm.vertexCount();
  lat.moves_.resize(static_cast<std::size_t>(nv));
  int cols = 0, rows = 0;
  lat.origin_ = rm.position(0);
  for (int v = 1; v < nv; ++v) {
    lat.origin_.x = std::min(lat.origin_.x, rm.position(v).x);
    lat.origin_.y = std::min(lat.origin_.y, rm.position(v).y);
  }
  auto edge = [&](int a, int b) {
    if (a < 0 || b < 0) return false;
    const auto& n = rm.neighbours(a);
    return std::find(n.begin(), n.end(), b) != n.end();
  };
  for (int v = 0; v < nv; ++v) {
    const geo::Vec2 p = rm.position(v);
    cols = std::max(cols, static_cast<int>(std::lround(p.x - lat.origin_.x)) + 1);
    rows = std::max(rows, static_cast<int>(std::lround(p.y - lat.origin_.y)) + 1);
    for (int a = 1; a < kMoveTypes; ++a) {
      const int w = rm.latticeOffset(v, kDir[a][0], kDir[a][1]);
      if (a <= 4) {
        if (edge(v, w)) lat.moves_[static_cast<std::size_t>(v)].emplace_back(w, a);
        continue;
      }
      // A diagonal only across a square of four free cells joined by their
      // edges: the disc (R < 1/2) stays inside the square.
      const int sx = rm.latticeOffset(v, kDir[a][0], 0), sy = rm.latticeOffset(v, 0, kDir[a][1]);
      if (edge(v, sx) && edge(v, sy) && edge(sx, w) && edge(sy, w)) lat.moves_[static_cast<std::size_t>(v)].emplace_back(w, a);
    }
  }
  // Two ticks meet only within 2R, the two motions and the two starts'
  // distances from their slots (sqrt(2)/6 at most) of each other.
  const int reach = static_cast<int>(std::ceil(2.0 * (2.0 * rm.radius() + 1.0 + std::sqrt(2.0) / 3.0)));
  lat.pad_ = reach + 2;
  lat.slot_w_ = 2 * cols + 2 * lat.pad_;
  lat.slot_h_ = 2 * rows + 2 * lat.pad_;
  const double touch = 2.0 * rm.radius() + 1e-9;
  for (int v = 0; v < nv; ++v) {
    const geo::Vec2 p = rm.position(v);
    const int x = 2 * static_cast<int>(std::lround(p.x - lat.origin_.x)) + lat.pad_;
    const int y = 2 * static_cast<int>(std::lround(p.y - lat.origin_.y)) + lat.pad_;
    lat.vslot_.push_back(static_cast<std::size_t>(y) * static_cast<std::size_t>(lat.slot_w_) + static_cast<std::size_t>(x));
  }
  for (int s = 0; s < kStates; ++s) {
    const auto [ox, oy] = slotOffset(s);
    lat.soff_[static_cast<std::size_t>(s)] = static_cast<std::ptrdiff_t>(oy) * lat.slot_w_ + ox;
  }
  lat.threats_.assign(kStates, {});
  for (int sa = 0; sa < kStates; ++sa) {
    const auto [ax, ay] = slotOffset(sa);
    const geo::Vec2 a0 = tickStart(sa), a1 = a0 + tickMotion(sa);
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        std::uint32_t mask = 0;
        for (int sb = 0; sb < kStates; ++sb) {
          const auto [bx, by] = slotOffset(sb);
          const int vx = ax + dx - bx, vy = ay + dy - by;  // b's vertex, in half cells
          if (vx % 2 != 0 || vy % 2 != 0) continue;
          const geo::Vec2 b0 = geo::Vec2{0.5 * vx, 0.5 * vy} + tickStart(sb);
          if (closestApproach(a0, a1, b0, b0 + tickMotion(sb)) < touch) mask |= 2u << sb;
        }
        if (mask) lat.threats_[static_cast<std::size_t>(sa)].push_back({dy * lat.slot_w_ + dx, mask});
      }
  }
  // Ticks to each distinct goal (Dijkstra on small integer costs, by buckets).
  for (int i = 0; i < rm.robotCount(); ++i) {
    const int g = rm.goal(i);
    std::size_t found = lat.dist_.size();
    for (int j = 0; j < i; ++j)
      if (rm.goal(j) == g) {
        found = lat.goal_slot_[static_cast<std::size_t>(j)];
        break;
      }
    if (found == lat.dist_.size()) {
      std::vector<int> d(static_cast<std::size_t>(nv), CrowdRoadmap::kUnreachable);
      std::vector<std::vector<int>> buckets(1, std::vector<int>{g});
      d[static_cast<std::size_t>(g)] = 0;
      for (std::size_t c = 0; c < buckets.size(); ++c)
        for (std::size_t x = 0; x < buckets[c].size(); ++x) {
          const int v = buckets[c][x];
          if (d[static_cast<std::size_t>(v)] != static_cast<int>(c)) continue;
          for (const auto& [w, a] : lat.moves(v)) {
            const int nd = static_cast<int>(c) + ticksOf(a);
            if (nd >= d[static_cast<std::size_t>(w)]) continue;
            d[static_cast<std::size_t>(w)] = nd;
            if (buckets.size() <= static_cast<std::size_t>(nd)) buckets.resize(static_cast<std::size_t>(nd) + 1);
            buckets[static_cast<std::size_t>(nd)].push_back(w);
          }
        }
      lat.dist_.push_back(std::move(d));
    }
    lat.goal_slot_.push_back(found);
  }
  return lat;
}

Occupancy::Occupancy(const Lattice& lat, std::vector<TickPath>& paths) : lat_(lat), paths_(paths), ns_(lat.slotCount()) {
  std::size_t h = 1;
  for (const auto& p : paths) h = std::max(h, p.size());
  grow(h);
  for (std::size_t i = 0; i < paths.size(); ++i) put(static_cast<int>(i));
}

void Occupancy::grow(std::size_t h) {
  if (rows_ == 0) {
    occ_.assign(ns_, -1);
    state_.assign(ns_, 0);
    rows_ = 1;
  }
  if (h <= rows_) return;
  // Beyond the old horizon everyone stands on their goal: its last row.
  lattice::repeatLastRow(occ_, ns_, h);
  lattice::repeatLastRow(state_, ns_, h);
  rows_ = h;
}

template <class F>
void Occupancy::forEachTick(const TickPath& p, F f) const {
  std::size_t t = 0;
  while (t < rows_) {
    if (t + 1 >= p.size()) {
      f(t++, p.back(), 0);
      continue;
    }
    const int u = p[t];
    std::size_t t1 = t + 1;
    while (p[t1] < 0) ++t1;
    const int a = lat_.moveType(u, p[t1]);
    for (std::size_t k = t; k < t1 && k < rows_; ++k) f(k, u, Lattice::state(a, static_cast<int>(k - t)));
    t = t1;
  }
}

void Occupancy::put(int i) {
  const TickPath& p = paths_[static_cast<std::size_t>(i)];
  grow(p.size());
  countWork(rows_);
  forEachTick(p, [&](std::size_t t, int u, int s) {
    const std::size_t k = t * ns_ + lat_.slot(u, s);
    occ_[k] = i;
    state_[k] = static_cast<std::uint8_t>(s + 1);
  });
}

void Occupancy::remove(int i) {
  countWork(rows_);
  forEachTick(paths_[static_cast<std::size_t>(i)], [&](std::size_t t, int u, int s) {
    const std::size_t k = t * ns_ + lat_.slot(u, s);
    if (occ_[k] != i) return;
    occ_[k] = -1;
    state_[k] = 0;
  });
}

int Occupancy::at(int v, std::size_t t) const { return occ_[std::min(t, rows_ - 1) * ns_ + lat_.slot(v, 0)]; }

bool Occupancy::blocked(int i, int u, int a, std::size_t t) const {
  for (int k = 0; k < ticksOf(a); ++k) {
    const int s = Lattice::state(a, k);
    const std::size_t base = std::min(t + static_cast<std::size_t>(k), rows_ - 1) * ns_ + lat_.slot(u, s);
    // The state bytes alone decide but for robot i itself: bit 0 of a
    // mask is clear, so an empty slot (0) never threatens.
    const std::uint8_t* st = state_.data() + base;
    for (const Lattice::Threat& th : lat_.threats(s))
      if ((th.mask >> st[th.delta] & 1u) && occ_[base + static_cast<std::size_t>(static_cast<std::ptrdiff_t>(th.delta))] != i)
        return true;
  }
  return false;
}

std::optional<TickPath> TickSearch::search(const Occupancy& occ, int i, const Deadline& deadline, long long max_cost,
                                           std::size_t max_expansions, double weight, bool avoid_goals) {
  // As lattice::StepSearch, on ticks: buckets by f, deepest first; a move
  // is checked against the others when its node is taken from the open
  // list, not when it is put there (most nodes put are never taken).
  // Work is counted as StepSearch counts it, per expansion and move out:
  // both phases then count at about one rate of CPU time.
  nodes_.clear();
  open_.clear();
  const CrowdRoadmap& rm = lat_.roadmap();
  const auto nv = static_cast<std::size_t>(rm.vertexCount());
  const int goal = rm.goal(i), start = rm.start(i);
  const long long own = lat_.distance(i, start);
  max_cost = std::min<long long>(max_cost, static_cast<long long>(occ.horizon()) + own + 16);
  if (max_cost < own) return std::nullopt;
  const auto limit = static_cast<std::size_t>(max_cost);
  if (closed_.size() < (limit + 4) * nv) closed_.resize((limit + 4) * nv, 0);
  if (++stamp_ == 0) {
    std::fill(closed_.begin(), closed_.end(), 0);
    stamp_ = 1;
  }
  long long free_after = -1;
  for (std::size_t t = occ.horizon(); t-- > 0;)
    if (occ.blocked(i, goal, 0, t)) {
      free_after = static_cast<long long>(t);
      break;
    }
  countWork(occ.horizon() - static_cast<std::size_t>(free_after + 1));
  auto h = [&](int v, long long t) { return std::max<long long>(lat_.distance(i, v), free_after + 1 - t); };
  if (h(start, 0) > max_cost) return std::nullopt;
  // With avoid_goals, among equally good ways the one that spends the
  // fewest steps on other robots' goals before they arrive comes first.
  const int levels = avoid_goals ? lattice::kGoalLevels : 1;
  if (goal_of_.empty()) {
    goal_of_.assign(nv, -1);
    for (int r = 0; r < lat_.roadmap().robotCount(); ++r) goal_of_[static_cast<std::size_t>(lat_.roadmap().goal(r))] = r;
  }
  nodes_.push_back({start, 0, -1, 0, 0});
  open_.push(static_cast<std::size_t>(h(start, 0)) * static_cast<std::size_t>(levels), 0);
  std::size_t expanded = 0;
  while (!open_.empty()) {
    const int k = open_.pop();
    const Node n = nodes_[static_cast<std::size_t>(k)];
    const std::size_t key = static_cast<std::size_t>(n.t) * nv + static_cast<std::size_t>(n.v);
    if (closed_[key] == stamp_) continue;
    if (n.parent >= 0) {
      const Node& from = nodes_[static_cast<std::size_t>(n.parent)];
      if (occ.blocked(i, from.v, n.a, static_cast<std::size_t>(from.t))) continue;
    }
    closed_[key] = stamp_;
    if (++expanded > max_expansions || ((expanded & 255) == 0 && deadline.expired())) return std::nullopt;
    ++expansions_;
    countWork(1 + lat_.moves(n.v).size());
    if (n.v == goal && n.t > free_after) {
      TickPath p(static_cast<std::size_t>(n.t) + 1, -1);
      for (int x = k; x >= 0; x = nodes_[static_cast<std::size_t>(x)].parent)
        p[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(x)].t)] = nodes_[static_cast<std::size_t>(x)].v;
      return p;
    }
    auto consider = [&](int v, int a) {
      const long long t1 = n.t + ticksOf(a);
      if (static_cast<std::size_t>(t1) > limit || lat_.distance(i, v) >= CrowdRoadmap::kUnreachable) return;
      const long long hv = h(v, t1);
      if (t1 + hv > max_cost) return;
      if (closed_[static_cast<std::size_t>(t1) * nv + static_cast<std::size_t>(v)] == stamp_) return;
      const int owner = goal_of_[static_cast<std::size_t>(v)];
      const int crossed = n.crossed + (owner >= 0 && owner != i && occ.arrival(owner) > static_cast<std::size_t>(t1) ? 1 : 0);
      nodes_.push_back({v, static_cast<int>(t1), k, a, crossed});
      const auto f = static_cast<std::size_t>(t1 + (weight == 1.0 ? hv : static_cast<long long>(weight * static_cast<double>(hv))));
      open_.push(f * static_cast<std::size_t>(levels) + static_cast<std::size_t>(std::min(crossed, levels - 1)),
           static_cast<int>(nodes_.size()) - 1);
    };
    consider(n.v, 0);
    for (const auto& [v, a] : lat_.moves(n.v)) consider(v, a);
  }
  return std::nullopt;
}

}  // namespace earc::ticks
