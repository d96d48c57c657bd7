#include "earc/planning/refine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <random>

#include "earc/planning/conflict.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/planning/solver.hpp"
#include "earc/util/random.hpp"

namespace earc {

namespace {

// Steps a chunk of the occupancy index spans: each robot is bounded over
// a chunk at once, and only robots whose bounds meet are tested instant
// by instant.
constexpr std::size_t kChunkSteps = 16;
constexpr std::size_t kChunkInstants = 2 * kChunkSteps;

// Box of the robot's bounding disc over steps [s0, s1] of `path` (past its
// end: its last state). A midpoint's centre lies between its steps'.
geo::Aabb boundsOverSteps(const RobotModel& m, const Path& path, std::size_t s0, std::size_t s1) {
  geo::Aabb box;
  s1 = std::min(s1, path.size() - 1);
  s0 = std::min(s0, s1);
  for (std::size_t t = s0; t <= s1; ++t) {
    const geo::Vec2 c = m.boundingCenter(path.at(t));
    box.expand({c, c});
  }
  return box.inflated(m.boundingRadius());
}

enum class Check { Clear, Contact, OutOfTime };

// Every robot's timed path indexed for "does this new path of robot r
// touch anyone": per chunk of steps, the robots still on their way then
// with the box their bodies stay in; and a grid of the goals where the
// robots that have arrived stand.
class Occupancy {
 public:
  Occupancy(const std::vector<const RobotModel*>& models, const std::vector<Path>& paths, const geo::Aabb& workspace)
      : models_(models), paths_(paths), len_(paths.size(), 0), in_(paths.size(), 0), goal_(paths.size()),
        stamp_(paths.size(), 0) {
    double radius = 0.0;
    for (const RobotModel* m : models_) radius = std::max(radius, m->boundingRadius());
    area_ = workspace;
    const double w = area_.hi.x - area_.lo.x, h = area_.hi.y - area_.lo.y;
    cell_ = std::max({2.0 * radius, w / 256.0, h / 256.0, 1e-9});
    nx_ = std::max<long>(1, static_cast<long>(std::ceil(w / cell_)));
    ny_ = std::max<long>(1, static_cast<long>(std::ceil(h / cell_)));
    grid_.resize(static_cast<std::size_t>(nx_ * ny_));
    for (std::size_t r = 0; r < paths_.size(); ++r) insert(r);
  }

  std::size_t steps(std::size_t r) const { return len_[r]; }

  void insert(std::size_t r) {
    const Path& p = paths_[r];
    if (in_[r] || p.empty()) return;
    in_[r] = 1;
    len_[r] = p.size() - 1;
    const RobotModel& m = *models_[r];
    const std::size_t chunks = len_[r] == 0 ? 0 : (len_[r] - 1) / kChunkSteps + 1;
    if (chunks_.size() < chunks) chunks_.resize(chunks);
    for (std::size_t c = 0; c < chunks; ++c)
      chunks_[c].push_back({static_cast<std::uint32_t>(r), boundsOverSteps(m, p, c * kChunkSteps, (c + 1) * kChunkSteps)});
    goal_[r] = boundsOverSteps(m, p, len_[r], len_[r]);
    forCells(goal_[r], [&](std::vector<std::uint32_t>& cell) { cell.push_back(static_cast<std::uint32_t>(r)); });
  }

  void remove(std::size_t r) {
    if (!in_[r]) return;
    in_[r] = 0;
    const std::size_t chunks = len_[r] == 0 ? 0 : (len_[r] - 1) / kChunkSteps + 1;
    for (std::size_t c = 0; c < chunks; ++c) {
      auto& list = chunks_[c];
      for (std::size_t i = 0; i < list.size(); ++i)
        if (list[i].robot == r) {
          list[i] = list.back();
          list.pop_back();
          break;
        }
    }
    forCells(goal_[r], [&](std::vector<std::uint32_t>& cell) {
      auto it = std::find(cell.begin(), cell.end(), static_cast<std::uint32_t>(r));
      if (it != cell.end()) {
        *it = cell.back();
        cell.pop_back();
      }
    });
  }

  // Whether robot r along `p` touches no other robot in the index at
  // instants k0..k1 (half steps, as stateAtInstant counts them).
  Check clear(std::size_t r, const Path& p, std::size_t k0, std::size_t k1, DeadlinePoll& poll) {
    const RobotModel& m = *models_[r];
    q_.resize(static_cast<std::size_t>(m.dim()));
    for (std::size_t c = k0 / kChunkInstants; c <= k1 / kChunkInstants; ++c) {
      const std::size_t ia = std::max(k0, c * kChunkInstants), ib = std::min(k1, c * kChunkInstants + kChunkInstants - 1);
      const geo::Aabb box = boundsOverSteps(m, p, ia / 2, (ib + 1) / 2);
      near_.clear();
      std::size_t tests = 1;
      if (c < chunks_.size()) {
        tests += chunks_[c].size();
        for (const auto& e : chunks_[c])
          if (e.robot != r && e.box.overlaps(box)) near_.push_back({e.robot, false});
      }
      ++tick_;
      forCells(box, [&](std::vector<std::uint32_t>& cell) {
        for (std::uint32_t o : cell) {
          ++tests;
          if (o == r || stamp_[o] == tick_ || len_[o] > c * kChunkSteps) continue;
          stamp_[o] = tick_;
          if (goal_[o].overlaps(box)) near_.push_back({o, true});
        }
      });
      if (poll.expired(tests / 8 + 1)) return Check::OutOfTime;
      if (near_.empty()) continue;
      for (std::size_t k = ia; k <= ib; ++k) {
        stateAtInstant(m, p, k, q_.data());
        const geo::Vec2 cr = m.boundingCenter(q_.data());
        bool placed = false;
        for (const Near& n : near_) {
          const RobotModel& mo = *models_[n.robot];
          const double* qo = paths_[n.robot].back();
          if (!n.parked) {
            qo_.resize(static_cast<std::size_t>(mo.dim()));
            stateAtInstant(mo, paths_[n.robot], k, qo_.data());
            qo = qo_.data();
          }
          const geo::Vec2 co = mo.boundingCenter(qo);
          const double reach = m.boundingRadius() + mo.boundingRadius();
          const double dx = cr.x - co.x, dy = cr.y - co.y;
          if (dx * dx + dy * dy > reach * reach) continue;
          if (!placed) {
            mine_.place(m, q_.data());
            placed = true;
          }
          theirs_.place(mo, qo);
          if (bodiesTouch(mine_, theirs_)) return Check::Contact;
          if (poll.expired(static_cast<std::size_t>(m.dim() + mo.dim()))) return Check::OutOfTime;
        }
        if (poll.expired(near_.size() / 8 + 1)) return Check::OutOfTime;
      }
    }
    return Check::Clear;
  }

  // The robots other than r whose boxes meet `box` during chunk c (or
  // parked there then), appended to out (unsorted, may repeat).
  void robotsNear(std::size_t r, std::size_t c, const geo::Aabb& box, std::vector<std::size_t>& out) {
    if (c < chunks_.size())
      for (const auto& e : chunks_[c])
        if (e.robot != r && e.box.overlaps(box)) out.push_back(e.robot);
    forCells(box, [&](std::vector<std::uint32_t>& cell) {
      for (std::uint32_t o : cell)
        if (o != r && len_[o] <= c * kChunkSteps && goal_[o].overlaps(box)) out.push_back(o);
    });
  }

  std::size_t chunkCount() const { return chunks_.size(); }

 private:
  struct Entry {
    std::uint32_t robot;
    geo::Aabb box;
  };
  struct Near {
    std::uint32_t robot;
    bool parked;
  };

  template <class Visit>
  void forCells(const geo::Aabb& box, Visit&& visit) {
    auto ix = [&](double x) { return std::clamp(static_cast<long>(std::floor((x - area_.lo.x) / cell_)), 0L, nx_ - 1); };
    auto iy = [&](double y) { return std::clamp(static_cast<long>(std::floor((y - area_.lo.y) / cell_)), 0L, ny_ - 1); };
    const long x0 = ix(box.lo.x), x1 = ix(box.hi.x), y0 = iy(box.lo.y), y1 = iy(box.hi.y);
    for (long y = y0; y <= y1; ++y)
      for (long x = x0; x <= x1; ++x) visit(grid_[static_cast<std::size_t>(y * nx_ + x)]);
  }

  const std::vector<const RobotModel*>& models_;
  const std::vector<Path>& paths_;
  std::vector<std::size_t> len_;
  std::vector<char> in_;
  std::vector<geo::Aabb> goal_;
  std::vector<std::vector<Entry>> chunks_;
  geo::Aabb area_;
  double cell_ = 1.0;
  long nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::uint32_t>> grid_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t tick_ = 0;
  std::vector<Near> near_;
  std::vector<double> q_, qo_;
  PlacedBodies mine_, theirs_;
};

// The operators, chosen by how much they saved per unit of work lately.
enum Op { kShortcut, kLnsRandom, kLnsAgent, kLnsPoint, kOps };

class Refiner {
 public:
  Refiner(const Scenario& scenario, const CollisionWorld& world, const std::vector<const RobotModel*>& models,
          std::vector<Path>& paths, const RefineSettings& settings, const Deadline& deadline)
      : scenario_(scenario), world_(world), models_(models), paths_(paths), settings_(settings),
        budget_(deadline.capped(settings.seconds)), poll_(budget_, kWorkPerClockRead),
        occ_(models, paths, world.workspace()), rng_(splitSeed(settings.seed, 0x4ef1)) {
    for (std::size_t r = 0; r < paths_.size(); ++r) {
      const Path& p = paths_[r];
      lb_.push_back(p.empty() ? 0 : static_cast<std::size_t>(models_[r]->stepsBetween(p.at(0), p.back())));
    }
  }

  RefineReport run();

 private:
  std::size_t cost(std::size_t r) const { return paths_[r].empty() ? 0 : paths_[r].size() - 1; }
  std::size_t sumOfCosts() const {
    std::size_t s = 0;
    for (std::size_t r = 0; r < paths_.size(); ++r) s += cost(r);
    return s;
  }
  std::size_t makespan() const {
    std::size_t m = 0;
    for (std::size_t r = 0; r < paths_.size(); ++r) m = std::max(m, cost(r));
    return m;
  }
  bool outOfBudget() { return poll_.seenExpired() || budget_.expired(); }
  bool stop() {
    if (settings_.max_iterations > 0 && report_.iterations >= settings_.max_iterations) return true;
    return outOfBudget();
  }
  void improved() {
    soc_ = sumOfCosts();
    makespan_ = makespan();
    report_.history.push_back({clock_.seconds(), static_cast<double>(soc_), static_cast<double>(makespan_)});
    report_.final_s = clock_.seconds();
  }

  // One try at shortening robot r's path by a straight motion over a
  // stretch of it; whether it was kept.
  bool shortcut(std::size_t r);
  // The new path for robot r from a straight motion over steps [t0, t1]
  // followed by `waits` waits, the rest moved earlier; checked and kept
  // when clear. Whether it was kept.
  bool tryShortcut(std::size_t r, std::size_t t0, std::size_t t1, std::size_t waits);
  // One large-neighbourhood step of the given kind; whether it was kept.
  bool lns(Op kind, std::size_t size);
  std::vector<std::size_t> neighbourhood(Op kind, std::size_t size);
  std::size_t pickByDelay();

  const Scenario& scenario_;
  const CollisionWorld& world_;
  const std::vector<const RobotModel*>& models_;
  std::vector<Path>& paths_;
  RefineSettings settings_;
  Deadline budget_;
  DeadlinePoll poll_;
  Occupancy occ_;
  std::mt19937_64 rng_;
  std::vector<std::size_t> lb_;
  std::size_t soc_ = 0, makespan_ = 0;
  Stopwatch clock_;
  RefineReport report_;
  std::unique_ptr<RoadmapSet> roadmaps_;
  std::vector<double> q_;
};

std::size_t Refiner::pickByDelay() {
  std::size_t total = 0;
  for (std::size_t r = 0; r < paths_.size(); ++r) total += cost(r) - std::min(cost(r), lb_[r]);
  if (total == 0) return paths_.size();
  std::size_t x = uniformIndex(rng_, total);
  for (std::size_t r = 0; r < paths_.size(); ++r) {
    const std::size_t d = cost(r) - std::min(cost(r), lb_[r]);
    if (x < d) return r;
    x -= d;
  }
  return paths_.size();
}

bool Refiner::shortcut(std::size_t r) {
  const std::size_t len = cost(r);
  if (len < 2) return false;
  ++report_.shortcut_tries;
  // Stretches of every length, log-uniformly (short ones straighten a
  // bend, long ones cut a detour); a quarter of them end at the goal.
  const double span_f = std::exp(uniform(rng_, std::log(2.0), std::log(static_cast<double>(len) + 1.0)));
  const std::size_t span = std::clamp<std::size_t>(static_cast<std::size_t>(span_f), 2, len);
  const bool to_goal = uniformIndex(rng_, 4) == 0;
  const std::size_t t0 = to_goal ? len - span : uniformIndex(rng_, len - span + 1);
  const std::size_t t1 = t0 + span;
  const Path& p = paths_[r];
  const RobotModel& m = *models_[r];
  const std::size_t n = static_cast<std::size_t>(m.stepsBetween(p.at(t0), p.at(t1)));
  if (n >= span) return false;
  // The motion against the obstacles: the instants motionValid checks are
  // those of the n steps made below.
  poll_.expired((n + 1) * static_cast<std::size_t>(m.dim()));
  if (n > 0 && !world_.motionValid(m, p.at(t0), p.at(t1))) return false;
  if (tryShortcut(r, t0, t1, 0)) return true;
  // Moved earlier the rest may meet someone: a few waits first may not.
  const std::size_t gain = span - n;
  if (gain >= 2 && !outOfBudget()) return tryShortcut(r, t0, t1, 1 + uniformIndex(rng_, gain - 1));
  return false;
}

bool Refiner::tryShortcut(std::size_t r, std::size_t t0, std::size_t t1, std::size_t waits) {
  const Path& p = paths_[r];
  const RobotModel& m = *models_[r];
  const std::size_t len = p.size() - 1;
  const std::size_t n = static_cast<std::size_t>(m.stepsBetween(p.at(t0), p.at(t1)));
  Path cand(m.dim());
  cand.reserve(len + 1);
  for (std::size_t t = 0; t <= t0; ++t) cand.push(p.at(t));
  q_.resize(static_cast<std::size_t>(m.dim()));
  for (std::size_t k = 1; k < n; ++k) {
    m.interpolate(p.at(t0), p.at(t1), static_cast<double>(k) / static_cast<double>(n), q_.data());
    cand.push(q_.data());
  }
  if (n > 0) cand.push(p.at(t1));
  for (std::size_t w = 0; w < waits; ++w) cand.push(cand.back());
  for (std::size_t t = t1 + 1; t <= len; ++t) cand.push(p.at(t));
  cand.dropTrailingWaits();
  if (cand.size() >= p.size()) return false;
  // Up to instant 2 t0 nothing changed; from the old arrival on it stands
  // at its goal either way.
  if (occ_.clear(r, cand, 2 * t0 + 1, 2 * len, poll_) != Check::Clear) return false;
  occ_.remove(r);
  paths_[r] = std::move(cand);
  occ_.insert(r);
  return true;
}

std::vector<std::size_t> Refiner::neighbourhood(Op kind, std::size_t size) {
  const std::size_t n = paths_.size();
  const std::size_t k = std::min(size, n);
  std::vector<std::size_t> out;
  auto add = [&](std::size_t r) {
    if (out.size() < k && std::find(out.begin(), out.end(), r) == out.end()) out.push_back(r);
  };
  if (kind == kLnsRandom || n <= k) {
    std::vector<std::size_t> all(n);
    std::iota(all.begin(), all.end(), std::size_t{0});
    std::shuffle(all.begin(), all.end(), rng_);
    // A robot with some delay first: one without any cannot gain.
    const std::size_t seed_robot = pickByDelay();
    if (seed_robot < n) add(seed_robot);
    for (std::size_t r : all) add(r);
    return out;
  }
  if (kind == kLnsAgent) {
    // A delayed robot and the robots that were near it along its way (in
    // MAPF-LNS, the agents that block its shortest path).
    const std::size_t a = pickByDelay();
    if (a >= n) return out;
    add(a);
    std::vector<std::size_t> near;
    const RobotModel& m = *models_[a];
    const std::size_t len = cost(a);
    for (std::size_t c = 0; c * kChunkSteps <= len; ++c)
      occ_.robotsNear(a, c, boundsOverSteps(m, paths_[a], c * kChunkSteps, (c + 1) * kChunkSteps), near);
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    std::shuffle(near.begin(), near.end(), rng_);
    for (std::size_t r : near) add(r);
    return out;
  }
  // kLnsPoint: the robots that pass nearest a place where some delayed
  // robot was (in MAPF-LNS, those through one intersection).
  const std::size_t a = pickByDelay();
  if (a >= n) return out;
  const RobotModel& m = *models_[a];
  const geo::Vec2 at = m.boundingCenter(paths_[a].at(uniformIndex(rng_, cost(a) + 1)));
  std::vector<std::pair<double, std::size_t>> dist;
  for (std::size_t r = 0; r < n; ++r) {
    const RobotModel& mr = *models_[r];
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < paths_[r].size(); t += 4) {
      const geo::Vec2 c = mr.boundingCenter(paths_[r].at(t));
      best = std::min(best, std::hypot(c.x - at.x, c.y - at.y) - mr.boundingRadius());
    }
    dist.push_back({best, r});
  }
  poll_.expired(n + paths_.size() / 8);
  std::sort(dist.begin(), dist.end());
  add(a);
  for (const auto& [d, r] : dist) add(r);
  return out;
}

bool Refiner::lns(Op kind, std::size_t size) {
  std::vector<std::size_t> group = neighbourhood(kind, size);
  if (group.empty()) return false;
  ++report_.lns_tries;
  if (!roadmaps_)
    roadmaps_ = std::make_unique<RoadmapSet>(world_, models_, settings_.roadmap_samples, settings_.roadmap_neighbors,
                                             settings_.roadmap_seed, budget_);
  if (settings_.roadmap_cache && roadmaps_->built() == 0) roadmaps_->useCache(*settings_.roadmap_cache, scenario_);
  // The group replanned in a random order against everyone else's paths,
  // each robot arriving within the plan's makespan and a margin, and able
  // to stay at its goal from then on (the decoupled solver's hold).
  std::shuffle(group.begin(), group.end(), rng_);
  // A mobile robot searches around its present way (a margin of a
  // quarter of the workspace, four of its radii at least): the search
  // and the robots it has to avoid stay few.
  Subproblem sub;
  const geo::Aabb& ws = world_.workspace();
  const double margin = 0.25 * std::max(ws.hi.x - ws.lo.x, ws.hi.y - ws.lo.y);
  for (std::size_t r : group) {
    const RobotModel& m = *models_[r];
    sub.robots.push_back(static_cast<int>(r));
    sub.starts.emplace_back(paths_[r].at(0), paths_[r].at(0) + m.dim());
    sub.goals.emplace_back(paths_[r].back(), paths_[r].back() + m.dim());
    ConfigBox box;
    m.samplingBounds(ws, box.lo, box.hi);
    geo::Aabb way = boundsOverSteps(m, paths_[r], 0, cost(r));
    if (m.isMobile()) {
      way = way.inflated(std::max(margin, 3.0 * m.boundingRadius()));
      box.lo[0] = std::max(box.lo[0], way.lo.x);
      box.lo[1] = std::max(box.lo[1], way.lo.y);
      box.hi[0] = std::min(box.hi[0], way.hi.x);
      box.hi[1] = std::min(box.hi[1], way.hi.y);
    }
    sub.workspace_region.expand(way);
    sub.region.push_back(std::move(box));
  }
  sub.t_start = 0;
  sub.t_end = makespan_;
  sub.whole_problem = true;
  DecoupledSettings ds;
  ds.time_budget_s = 1.0;
  ds.max_expansions = 200000;
  ds.expansions_per_horizon_step = 0;
  ds.max_orders = 1;
  ds.horizon_windows = 1.0;
  ds.horizon_steps = 100;
  DecoupledSolver solver(ds);
  SolverContext ctx{world_, models_, *roadmaps_, paths_, sub, budget_, splitSeed(settings_.seed, 0x1a5 + report_.lns_tries)};
  SolverOutcome out = solver.solve(ctx);
  if (!out.solution) {
    ++report_.lns_failed;
    return false;
  }
  std::vector<Path> fresh = std::move(out.solution->paths);
  // Checked as the contract checks them before they count: every step
  // within the resolution and clear of the obstacles.
  for (std::size_t i = 0; i < group.size(); ++i) {
    Path& p = fresh[i];
    p.dropTrailingWaits();
    const RobotModel& m = *models_[group[i]];
    poll_.expired(p.size() * static_cast<std::size_t>(m.dim()));
    for (std::size_t t = 0; t + 1 < p.size(); ++t)
      if (m.stepsBetween(p.at(t), p.at(t + 1)) > 1 || !world_.motionValid(m, p.at(t), p.at(t + 1))) {
        ++report_.lns_failed;
        return false;
      }
  }
  std::vector<Path> old;
  std::size_t old_soc = 0;
  for (std::size_t r : group) {
    old.push_back(paths_[r]);
    old_soc += cost(r);
    occ_.remove(r);
  }
  for (std::size_t i = 0; i < group.size(); ++i) paths_[group[i]] = std::move(fresh[i]);
  for (std::size_t r : group) occ_.insert(r);
  auto restore = [&] {
    for (std::size_t r : group) occ_.remove(r);
    for (std::size_t i = 0; i < group.size(); ++i) paths_[group[i]] = std::move(old[i]);
    for (std::size_t r : group) occ_.insert(r);
  };
  // And clear of every other robot at every step and midpoint.
  std::size_t horizon = 0;
  for (std::size_t r = 0; r < paths_.size(); ++r) horizon = std::max(horizon, cost(r));
  for (std::size_t r : group)
    if (occ_.clear(r, paths_[r], 0, 2 * horizon, poll_) != Check::Clear) {
      if (!poll_.seenExpired()) ++report_.lns_failed;
      restore();
      return false;
    }
  // A roadmap's path bends at its vertices: straightened before it is
  // compared with the old one.
  for (std::size_t r : group)
    for (int k = 0; k < 24 && !poll_.seenExpired(); ++k) shortcut(r);
  std::size_t new_soc = 0;
  for (std::size_t r : group) new_soc += cost(r);
  const std::size_t new_makespan = makespan();
  if (new_makespan > makespan_ || new_soc > old_soc || (new_soc == old_soc && new_makespan == makespan_)) {
    restore();
    return false;
  }
  return true;
}

RefineReport Refiner::run() {
  soc_ = sumOfCosts();
  makespan_ = makespan();
  report_.first_sum_of_costs = report_.final_sum_of_costs = soc_;
  report_.first_makespan = report_.final_makespan = makespan_;
  for (std::size_t b : lb_) report_.lower_bound += b;
  // How much each operator saved per unit of work lately (an untried one
  // is tried first); a sixth of the choices are at random, so that one
  // that saved nothing for a while is tried again.
  std::array<double, kOps> score;
  score.fill(std::numeric_limits<double>::infinity());
  std::array<bool, kOps> on{settings_.shortcuts, settings_.lns, settings_.lns, settings_.lns};
  if (paths_.size() < 2) on[kLnsAgent] = on[kLnsPoint] = false;
  // Neighbourhoods of 2, 4 or 8 robots (at most settings.neighbourhood),
  // chosen the same way: a larger one finds more, a smaller one is cheaper.
  std::vector<std::size_t> sizes;
  for (std::size_t k = 2; k <= std::max<std::size_t>(2, settings_.neighbourhood); k *= 2)
    sizes.push_back(std::min(k, settings_.neighbourhood));
  std::vector<double> size_score(sizes.size(), std::numeric_limits<double>::infinity());
  auto choose = [&](const auto& scores, const std::vector<std::size_t>& among) {
    std::size_t pick = among[uniformIndex(rng_, among.size())];
    if (uniformIndex(rng_, 6) != 0)
      for (std::size_t o : among)
        if (scores[o] > scores[pick]) pick = o;
    return pick;
  };
  auto update = [](double& s, double value) { s = std::isinf(s) ? value : 0.8 * s + 0.2 * value; };
  std::vector<std::size_t> ops, size_index(sizes.size());
  std::iota(size_index.begin(), size_index.end(), std::size_t{0});
  for (std::size_t o = 0; o < kOps; ++o)
    if (on[o]) ops.push_back(o);
  while (!ops.empty() && !stop() && soc_ > report_.lower_bound) {
    const std::size_t op = choose(score, ops);
    ++report_.iterations;
    const std::uint64_t work0 = t_work_done;
    const std::size_t before = soc_, makespan_before = makespan_;
    std::size_t si = 0;
    bool kept = false;
    if (op == kShortcut) {
      const std::size_t r = pickByDelay();
      if (r >= paths_.size()) break;
      kept = shortcut(r);
      if (kept) ++report_.shortcut_improvements;
    } else {
      si = choose(size_score, size_index);
      kept = lns(static_cast<Op>(op), sizes[si]);
      if (kept) ++report_.lns_improvements;
    }
    if (kept) improved();
    const double work = static_cast<double>(t_work_done - work0) + 1.0;
    const double gain = static_cast<double>(before) - static_cast<double>(soc_) +
                        0.5 * (static_cast<double>(makespan_before) - static_cast<double>(makespan_));
    update(score[op], gain / work);
    if (op != kShortcut) update(size_score[si], gain / work);
  }
  report_.final_sum_of_costs = soc_;
  report_.final_makespan = makespan_;
  report_.seconds_spent = clock_.seconds();
  return report_;
}

}  // namespace

RefineReport refinePlan(const Scenario& scenario, const CollisionWorld& world,
                        const std::vector<const RobotModel*>& models, std::vector<Path>& paths,
                        const RefineSettings& settings, const Deadline& deadline) {
  for (Path& p : paths) p.dropTrailingWaits();
  Refiner refiner(scenario, world, models, paths, settings, deadline);
  return refiner.run();
}

}  // namespace earc
