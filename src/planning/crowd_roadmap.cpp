#include "earc/planning/crowd_roadmap.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>

namespace earc {

namespace {

bool integral(double x) { return std::abs(x - std::round(x)) < 1e-9; }

// A grid map's scenario (earc-scenario movingai): integral workspace and
// axis-aligned boxes with integral sides. Its cells' centres are then the
// natural lattice: robots of a benchmark file start and end on them.
bool gridWorld(const CollisionWorld& world) {
  const geo::Aabb& ws = world.workspace();
  if (!integral(ws.lo.x) || !integral(ws.lo.y) || !integral(ws.hi.x) || !integral(ws.hi.y)) return false;
  for (std::size_t i = 0; i < world.obstacleCount(); ++i) {
    const geo::Body& b = world.obstacle(i);
    if (b.kind != geo::CoreKind::Rect || b.radius != 0.0) return false;
    if (std::abs(b.axis.y) > 1e-12 && std::abs(b.axis.x) > 1e-12) return false;
    const geo::Aabb box = geo::bounds(b);
    if (!integral(box.lo.x) || !integral(box.lo.y) || !integral(box.hi.x) || !integral(box.hi.y)) return false;
  }
  return true;
}

}  // namespace

namespace {

// The squared closestApproach (no square root: the hot test compares it).
double closestApproachSquared(geo::Vec2 a0, geo::Vec2 a1, geo::Vec2 b0, geo::Vec2 b1) {
  // The relative position d(s) = d0 + s (d1 - d0) is linear in s: its
  // smallest norm over [0, 1] is at the clamped projection of the origin.
  const geo::Vec2 d0 = a0 - b0;
  const geo::Vec2 dd = (a1 - b1) - d0;
  const double len2 = geo::dot(dd, dd);
  double s = 0.0;
  if (len2 > 0.0) s = std::clamp(-geo::dot(d0, dd) / len2, 0.0, 1.0);
  const geo::Vec2 d = d0 + dd * s;
  return geo::dot(d, d);
}

}  // namespace

double closestApproach(geo::Vec2 a0, geo::Vec2 a1, geo::Vec2 b0, geo::Vec2 b1) {
  return std::sqrt(closestApproachSquared(a0, a1, b0, b1));
}

CrowdRoadmap::CrowdRoadmap(const CollisionWorld& world, const std::vector<const RobotModel*>& models,
                           const std::vector<int>& robots, const std::vector<std::vector<double>>& starts,
                           const std::vector<std::vector<double>>& goals) {
  for (int r : robots) {
    const RobotModel* m = models[static_cast<std::size_t>(r)];
    if (!m->isMobile())
      throw std::invalid_argument("robot " + m->spec().name + " is an arm: the crowd solver plans mobile robots only");
    group_models_.push_back(m);
    radius_ = std::max(radius_, m->boundingRadius());
  }
  const geo::Aabb& ws = world.workspace();
  // Every lattice vertex is R-clear of obstacles and walls. On a grid map
  // with robots narrower than a cell the lattice is the cells' centres;
  // elsewhere its spacing keeps robots on two lattice vertices apart.
  grid_ = gridWorld(world) && radius_ < 0.5 - 1e-9;
  spacing_ = grid_ ? 1.0 : 2.0 * radius_ + 0.01;
  const double width = ws.hi.x - ws.lo.x, height = ws.hi.y - ws.lo.y;
  if (grid_) {
    cols_ = static_cast<int>(std::lround(width));
    rows_ = static_cast<int>(std::lround(height));
    origin_ = {ws.lo.x + 0.5, ws.lo.y + 0.5};
  } else {
    cols_ = std::max(0, static_cast<int>(std::floor((width - 2.0 * radius_) / spacing_)) + 1);
    rows_ = std::max(0, static_cast<int>(std::floor((height - 2.0 * radius_) / spacing_)) + 1);
    origin_ = {ws.lo.x + 0.5 * (width - (cols_ - 1) * spacing_), ws.lo.y + 0.5 * (height - (rows_ - 1) * spacing_)};
  }
  lattice_.assign(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(std::max(rows_, 0)), -1);
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) {
      const geo::Vec2 p{origin_.x + c * spacing_, origin_.y + r * spacing_};
      if (world.bodyFree(geo::Body::disc(p, radius_))) {
        lattice_[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(c)] =
            addVertex(p, -1);
        cell_c_.back() = c;
        cell_r_.back() = r;
      }
    }
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) {
      const int v = latticeAt(c, r);
      if (v < 0) continue;
      for (auto [dc, dr] : {std::pair{1, 0}, std::pair{0, 1}}) {
        const int w = latticeAt(c + dc, r + dr);
        if (w >= 0 && world.bodyFree(geo::Body::capsule(pos_[static_cast<std::size_t>(v)],
                                                        pos_[static_cast<std::size_t>(w)], radius_)))
          addEdge(v, w);
      }
    }
  longest_edge_ = spacing_;
  for (const RobotModel* m : group_models_)
    steps_per_edge_ =
        std::max(steps_per_edge_, static_cast<int>(std::ceil(spacing_ / m->resolution().translation - 1e-9)));
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const int ri = static_cast<int>(i);
    start_.push_back(connectOwn(world, ri, starts[i], true));
    const geo::Vec2 s{starts[i][0], starts[i][1]}, g{goals[i][0], goals[i][1]};
    goal_.push_back(geo::norm(s - g) < 1e-9 ? start_.back() : connectOwn(world, ri, goals[i], false));
  }
  buildNear();
  buildLatticeConflicts();
  buildDistances();
  for (std::size_t i = 0; i < start_.size() && problem_.empty(); ++i)
    if (dist_[i][static_cast<std::size_t>(start_[i])] >= kUnreachable)
      problem_ = "robot " + group_models_[i]->spec().name +
                 ": no way from its start to its goal on the lattice of spacing " + std::to_string(spacing_);
}

int CrowdRoadmap::latticeAt(int c, int r) const {
  if (c < 0 || r < 0 || c >= cols_ || r >= rows_) return -1;
  return lattice_[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(c)];
}

void CrowdRoadmap::placesFrom(int i, int u, std::vector<int>& out) const {
  out.assign(1, u);
  for (int v : neighbours(u))
    if (usableBy(i, v)) out.push_back(v);
}

int CrowdRoadmap::addVertex(geo::Vec2 p, int owner, double heading, bool start_side) {
  pos_.push_back(p);
  owner_.push_back(owner);
  heading_.push_back(heading);
  start_side_.push_back(start_side ? 1 : 0);
  cell_c_.push_back(-1);
  cell_r_.push_back(-1);
  adj_.emplace_back();
  return static_cast<int>(pos_.size()) - 1;
}

void CrowdRoadmap::addEdge(int a, int b) {
  adj_[static_cast<std::size_t>(a)].push_back(b);
  adj_[static_cast<std::size_t>(b)].push_back(a);
}

// A start or goal: the lattice vertex it stands on, or a vertex of the
// robot's own joined to the lattice vertices within one spacing, or where
// none of those can be reached, to the nearest free one within a few
// spacings by a chain of own vertices one spacing apart at most. Its
// joining motions keep the robot's heading there and are checked with its
// real footprint at the instants a plan's steps are validated (the robot
// may stand closer to a wall than its bounding disc allows). A robot
// leaves its own start for good: it is there only with its start heading.
int CrowdRoadmap::connectOwn(const CollisionWorld& world, int robot, const std::vector<double>& q, bool is_start) {
  const geo::Vec2 p{q[0], q[1]};
  const int c0 = static_cast<int>(std::floor((p.x - origin_.x) / spacing_));
  const int r0 = static_cast<int>(std::floor((p.y - origin_.y) / spacing_));
  for (int r = r0; r <= r0 + 1; ++r)
    for (int c = c0; c <= c0 + 1; ++c) {
      const int v = latticeAt(c, r);
      if (v >= 0 && geo::norm(pos_[static_cast<std::size_t>(v)] - p) < 1e-9) return v;
    }
  const RobotModel& m = *group_models_[static_cast<std::size_t>(robot)];
  auto motionFree = [&](geo::Vec2 a, geo::Vec2 b) {
    if (world.bodyFree(geo::Body::capsule(a, b, radius_))) return true;
    for (int k = 0; k <= 2 * steps_per_edge_; ++k) {
      const double s = static_cast<double>(k) / (2.0 * steps_per_edge_);
      const double x[3] = {a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s, q[2]};
      if (!world.stateValid(m, x)) return false;
    }
    return true;
  };
  auto join = [&](int from, int to) {
    if (is_start)
      adj_[static_cast<std::size_t>(from)].push_back(to);
    else
      addEdge(from, to);
  };
  const int own = addVertex(p, robot, q[2], is_start);
  std::vector<std::pair<double, int>> further;
  constexpr int kReach = 3;
  for (int r = r0 - kReach; r <= r0 + kReach + 1; ++r)
    for (int c = c0 - kReach; c <= c0 + kReach + 1; ++c) {
      const int v = latticeAt(c, r);
      if (v < 0) continue;
      const geo::Vec2 w = pos_[static_cast<std::size_t>(v)];
      const double d = geo::norm(w - p);
      if (d > spacing_ + 1e-9) {
        further.emplace_back(d, v);
      } else if (motionFree(p, w)) {
        join(own, v);
      }
    }
  if (!adj_[static_cast<std::size_t>(own)].empty()) return own;
  std::sort(further.begin(), further.end());
  for (const auto& [d, v] : further) {
    const geo::Vec2 w = pos_[static_cast<std::size_t>(v)];
    const int pieces = static_cast<int>(std::ceil(d / spacing_ - 1e-9));
    bool free = true;
    for (int k = 0; k < pieces && free; ++k)
      free = motionFree(p + (w - p) * (static_cast<double>(k) / pieces),
                        p + (w - p) * (static_cast<double>(k + 1) / pieces));
    if (!free) continue;
    int prev = own;
    for (int k = 1; k < pieces; ++k) {
      const int mid = addVertex(p + (w - p) * (static_cast<double>(k) / pieces), robot, q[2], is_start);
      join(prev, mid);
      prev = mid;
    }
    join(prev, v);
    break;
  }
  return own;
}

void CrowdRoadmap::buildNear() {
  // Two vertices' steps can meet only when the vertices are closer than
  // 2R plus two edges: a bucket grid of that pitch finds the candidates,
  // and every pair of their steps (stays included) decides.
  const double reach = 2.0 * radius_ + 2.0 * longest_edge_ + 1e-9;
  geo::Aabb box;
  for (const auto& p : pos_) box.expand({p, p});
  const double cell = reach;
  const int bc = std::max(1, static_cast<int>((box.hi.x - box.lo.x) / cell) + 1);
  const int br = std::max(1, static_cast<int>((box.hi.y - box.lo.y) / cell) + 1);
  std::vector<std::vector<int>> bucket(static_cast<std::size_t>(bc) * static_cast<std::size_t>(br));
  auto key = [&](geo::Vec2 p) {
    const int c = std::clamp(static_cast<int>((p.x - box.lo.x) / cell), 0, bc - 1);
    const int r = std::clamp(static_cast<int>((p.y - box.lo.y) / cell), 0, br - 1);
    return std::pair{c, r};
  };
  for (int v = 0; v < vertexCount(); ++v) {
    auto [c, r] = key(pos_[static_cast<std::size_t>(v)]);
    bucket[static_cast<std::size_t>(r) * static_cast<std::size_t>(bc) + static_cast<std::size_t>(c)].push_back(v);
  }
  near_.assign(pos_.size(), {});
  const double touch = 2.0 * radius_;
  for (int v = 0; v < vertexCount(); ++v) {
    const geo::Vec2 pv = pos_[static_cast<std::size_t>(v)];
    auto [c, r] = key(pv);
    for (int rr = r - 1; rr <= r + 1; ++rr)
      for (int cc = c - 1; cc <= c + 1; ++cc) {
        if (cc < 0 || rr < 0 || cc >= bc || rr >= br) continue;
        for (int w :
             bucket[static_cast<std::size_t>(rr) * static_cast<std::size_t>(bc) + static_cast<std::size_t>(cc)]) {
          const geo::Vec2 pw = pos_[static_cast<std::size_t>(w)];
          if (geo::norm(pw - pv) > reach) continue;
          bool meets = w == v;
          const auto& av = adj_[static_cast<std::size_t>(v)];
          const auto& aw = adj_[static_cast<std::size_t>(w)];
          for (std::size_t a = 0; !meets && a <= av.size(); ++a)
            for (std::size_t b = 0; !meets && b <= aw.size(); ++b) {
              const geo::Vec2 va = a < av.size() ? pos_[static_cast<std::size_t>(av[a])] : pv;
              const geo::Vec2 wb = b < aw.size() ? pos_[static_cast<std::size_t>(aw[b])] : pw;
              meets = closestApproach(pv, va, pw, wb) < touch + 1e-9;
            }
          if (meets) near_[static_cast<std::size_t>(v)].push_back(w);
        }
      }
  }
}

void CrowdRoadmap::buildDistances() {
  dist_.assign(start_.size(), {});
  // Robots with the same goal vertex (only lattice goals can be shared)
  // share one search.
  for (std::size_t i = 0; i < start_.size(); ++i) {
    const int g = goal_[i];
    bool shared = false;
    if (owner(g) < 0)
      for (std::size_t j = 0; j < i && !shared; ++j)
        if (goal_[j] == g && owner(start_[j]) < 0 && owner(start_[i]) < 0) {
          dist_[i] = dist_[j];
          shared = true;
        }
    if (shared) continue;
    std::vector<int>& d = dist_[i];
    d.assign(pos_.size(), kUnreachable);
    std::deque<int> queue{g};
    d[static_cast<std::size_t>(g)] = 0;
    // Every edge but a start's goes both ways: search back from the goal
    // over them, then a start is one step more than its best exit.
    while (!queue.empty()) {
      const int v = queue.front();
      queue.pop_front();
      for (int w : adj_[static_cast<std::size_t>(v)]) {
        if (!usableBy(static_cast<int>(i), w) || d[static_cast<std::size_t>(w)] != kUnreachable) continue;
        d[static_cast<std::size_t>(w)] = d[static_cast<std::size_t>(v)] + 1;
        queue.push_back(w);
      }
    }
    // The start side's vertices were made start first: take them last first.
    for (int v = vertexCount() - 1; v >= 0; --v) {
      if (owner(v) != static_cast<int>(i) || !start_side_[static_cast<std::size_t>(v)] || v == g) continue;
      for (int w : adj_[static_cast<std::size_t>(v)])
        d[static_cast<std::size_t>(v)] = std::min(d[static_cast<std::size_t>(v)], d[static_cast<std::size_t>(w)] + 1);
    }
  }
}

double CrowdRoadmap::headingAt(int v) const { return heading_[static_cast<std::size_t>(v)]; }

// Two lattice robots' steps conflict or not by their cells' offsets
// alone: a table of them all, computed once, answers the hot test.
void CrowdRoadmap::buildLatticeConflicts() {
  table_reach_ = static_cast<int>(std::ceil((2.0 * radius_ + 2.0 * longest_edge_) / spacing_));
  const int side = 2 * table_reach_ + 1;
  lattice_conflicts_.assign(static_cast<std::size_t>(5 * side * side * 5), 0);
  static constexpr int kStep[5][2] = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  const double touch = 2.0 * radius_ + 1e-9;
  for (int a = 0; a < 5; ++a)
    for (int dr = -table_reach_; dr <= table_reach_; ++dr)
      for (int dc = -table_reach_; dc <= table_reach_; ++dc)
        for (int b = 0; b < 5; ++b) {
          const geo::Vec2 a0{0.0, 0.0}, a1{kStep[a][0] * spacing_, kStep[a][1] * spacing_};
          const geo::Vec2 b0{dc * spacing_, dr * spacing_};
          const geo::Vec2 b1{b0.x + kStep[b][0] * spacing_, b0.y + kStep[b][1] * spacing_};
          const std::size_t k =
              static_cast<std::size_t>(((a * side + (dr + table_reach_)) * side + (dc + table_reach_)) * 5 + b);
          lattice_conflicts_[k] = closestApproachSquared(a0, a1, b0, b1) < touch * touch ? 1 : 0;
        }
  threats_.assign(5, {});
  for (int a = 0; a < 5; ++a)
    for (int dr = -table_reach_; dr <= table_reach_; ++dr)
      for (int dc = -table_reach_; dc <= table_reach_; ++dc) {
        unsigned mask = 0;
        for (int b = 0; b < 5; ++b)
          if (lattice_conflicts_[static_cast<std::size_t>(((a * side + (dr + table_reach_)) * side + (dc + table_reach_)) * 5 + b)])
            mask |= 1u << b;
        if (mask) threats_[static_cast<std::size_t>(a)].push_back({dc, dr, mask});
      }
  all_on_lattice_ = std::all_of(cell_c_.begin(), cell_c_.end(), [](int c) { return c >= 0; });
}

int CrowdRoadmap::latticeConflict(CrowdMove mi, CrowdMove mj) const {
  const int a = latticeStep(mi.from, mi.to), b = latticeStep(mj.from, mj.to);
  if (a < 0 || b < 0) return -1;
  const int dc = cell_c_[static_cast<std::size_t>(mj.from)] - cell_c_[static_cast<std::size_t>(mi.from)];
  const int dr = cell_r_[static_cast<std::size_t>(mj.from)] - cell_r_[static_cast<std::size_t>(mi.from)];
  if (std::abs(dc) > table_reach_ || std::abs(dr) > table_reach_) return 0;
  const int side = 2 * table_reach_ + 1;
  return lattice_conflicts_[static_cast<std::size_t>(
      ((a * side + (dr + table_reach_)) * side + (dc + table_reach_)) * 5 + b)];
}

bool CrowdRoadmap::conflict(int i, CrowdMove mi, int j, CrowdMove mj) const {
  if (const int known = latticeConflict(mi, mj); known >= 0) return known == 1;
  const double touch = 2.0 * radius_ + 1e-9;
  if (closestApproachSquared(position(mi.from), position(mi.to), position(mj.from), position(mj.to)) >= touch * touch)
    return false;
  // A robot on or beside its own start or goal has a known heading there
  // (crowdPaths turns robots on the lattice only, before they first reach
  // their own goal): its real footprint decides, at the instants at which
  // a plan's steps are validated; a robot on the lattice is its disc.
  const bool known_i = owner(mi.from) == i || owner(mi.to) == i;
  const bool known_j = owner(mj.from) == j || owner(mj.to) == j;
  if (!known_i && !known_j) return true;
  std::vector<geo::Body> bi, bj;
  auto place = [&](int r, CrowdMove m, bool known, double s, std::vector<geo::Body>& out) {
    out.clear();
    const geo::Vec2 a = position(m.from), b = position(m.to);
    const geo::Vec2 p = a + (b - a) * s;
    if (known) {
      const double q[3] = {p.x, p.y, headingAt(owner(m.from) == r ? m.from : m.to)};
      model(r).bodies(q, out);
    } else {
      out.push_back(geo::Body::disc(p, radius_));
    }
  };
  const int instants = 2 * steps_per_edge_;
  for (int k = 0; k <= instants; ++k) {
    const double s = static_cast<double>(k) / instants;
    place(i, mi, known_i, s, bi);
    place(j, mj, known_j, s, bj);
    for (const auto& a : bi)
      for (const auto& b : bj)
        if (geo::touches(a, b)) return true;
  }
  return false;
}

}  // namespace earc
