#include "earc/planning/refine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <random>

#include "earc/planning/compact.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/path_bound.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/planning/solver.hpp"
#include "earc/util/random.hpp"
#include "refine_index.hpp"
#include "refine_retime.hpp"

namespace earc {

namespace {

using refine::boundsOverSteps;
using refine::Check;
using refine::kChunkSteps;
using refine::Occupancy;

// The operators, chosen by how much they saved per unit of work lately.
enum Op { kShortcut, kLnsRandom, kLnsAgent, kLnsPoint, kOps };

class Refiner {
 public:
  Refiner(const Scenario& scenario, const CollisionWorld& world, const std::vector<const RobotModel*>& models,
          std::vector<Path>& paths, const RefineSettings& settings, const Deadline& deadline)
      : scenario_(scenario), world_(world), models_(models), paths_(paths), settings_(settings),
        budget_(deadline.capped(settings.seconds)), poll_(budget_, kWorkPerClockRead),
        occ_(models, paths, world.workspace()), rng_(splitSeed(settings.seed, 0x4ef1)),
        lb_(ownPathLowerBounds(scenario, models)) {
    for (std::size_t b : straightLineBounds(scenario, models)) report_.straight_line_bound += b;
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
  // Robot r's states strictly after step t0 of a straight motion from its
  // state at t0 to its state at t1, at full speed, appended to out.
  // The new path for robot r from a straight motion over steps [t0, t1],
  // the rest moved earlier; checked and kept when clear. Whether it was kept.
  bool tryShortcut(std::size_t r, std::size_t t0, std::size_t t1);
  // The stretch [t0, t1] made straight and the rest of robot r's route
  // timed anew (waiting where needed); whether it was kept.
  bool retimeShortcut(std::size_t r, std::size_t t0, std::size_t t1);
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
  const auto [t0, t1] = drawStretch(rng_, len);
  const std::size_t span = t1 - t0;
  const Path& p = paths_[r];
  const RobotModel& m = *models_[r];
  const std::size_t n = static_cast<std::size_t>(m.stepsBetween(p.at(t0), p.at(t1)));
  if (n >= span) return false;
  // The motion against the obstacles: the instants motionValid checks are
  // those of the n steps made below.
  poll_.expired((n + 1) * static_cast<std::size_t>(m.dim()));
  if (n > 0 && !world_.motionValid(m, p.at(t0), p.at(t1))) return false;
  if (tryShortcut(r, t0, t1)) return true;
  // Moved earlier the rest may meet someone: the earliest timing along
  // the shortened route, waiting where someone is in the way.
  return !outOfBudget() && retimeShortcut(r, t0, t1);
}

bool Refiner::retimeShortcut(std::size_t r, std::size_t t0, std::size_t t1) {
  const Path& p = paths_[r];
  const RobotModel& m = *models_[r];
  const std::size_t len = p.size() - 1;
  // The route: the straight motion, then the old path without its waits.
  Path route(m.dim());
  route.push(p.at(t0));
  appendStraightMotion(m, p.at(t0), p.at(t1), route);
  for (std::size_t t = t1 + 1; t <= len; ++t)
    if (m.stepsBetween(p.at(t), route.back()) > 0) route.push(p.at(t));
  // Each position tried at a few steps on average.
  std::optional<Path> cand =
      refine::retimeAlong(occ_, m, r, p, t0, route, len, makespan_, poll_, 8 * route.size() + 64);
  if (!cand || cand->size() >= p.size()) return false;
  if (occ_.clear(r, *cand, 2 * t0 + 1, 2 * std::max(len, makespan_), poll_) != Check::Clear) return false;
  occ_.remove(r);
  paths_[r] = std::move(*cand);
  occ_.insert(r);
  return true;
}

bool Refiner::tryShortcut(std::size_t r, std::size_t t0, std::size_t t1) {
  const Path& p = paths_[r];
  const RobotModel& m = *models_[r];
  const std::size_t len = p.size() - 1;
  Path cand(m.dim());
  cand.reserve(len + 1);
  for (std::size_t t = 0; t <= t0; ++t) cand.push(p.at(t));
  appendStraightMotion(m, p.at(t0), p.at(t1), cand);
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
  // One priority order, and a search cut short: one that succeeds seldom
  // needs many expansions, and one that cannot succeed would otherwise
  // explore every (vertex, step) pair within the horizon.
  DecoupledSettings ds;
  ds.time_budget_s = 0.5;
  ds.max_expansions = 30000;
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
  // First the waits nothing needs, each robot retimed along its route
  // (compactPlan): a shortcut moves the rest of a path earlier as one
  // piece, which in a plan of many robots seldom stays clear of them all.
  if (settings_.shortcuts && !stop()) {
    const CompactReport compacted = compactPlan(models_, paths_, &world_, budget_);
    report_.retimed_steps = static_cast<std::size_t>(std::max<std::int64_t>(0, compacted.steps_saved));
    if (compacted.robots_retimed > 0) {
      for (std::size_t r = 0; r < paths_.size(); ++r) {
        occ_.remove(r);
        occ_.insert(r);
      }
      improved();
    }
  }
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
  // Equal yields (none has saved anything yet) go to the cheaper choice:
  // a failing neighbourhood may cost a hundred failing shortcuts.
  std::array<double, kOps> op_work{};
  std::vector<double> size_work(sizes.size(), 0.0);
  auto choose = [&](const auto& scores, const auto& works, const std::vector<std::size_t>& among) {
    std::size_t pick = among[uniformIndex(rng_, among.size())];
    if (uniformIndex(rng_, 6) != 0)
      for (std::size_t o : among)
        if (scores[o] > scores[pick] || (scores[o] == scores[pick] && works[o] < works[pick])) pick = o;
    return pick;
  };
  auto update = [](double& s, double value) { s = std::isinf(s) ? value : 0.8 * s + 0.2 * value; };
  std::vector<std::size_t> ops, size_index(sizes.size());
  std::iota(size_index.begin(), size_index.end(), std::size_t{0});
  for (std::size_t o = 0; o < kOps; ++o)
    if (on[o]) ops.push_back(o);
  while (!ops.empty() && !stop() && soc_ > report_.lower_bound) {
    const std::size_t op = choose(score, op_work, ops);
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
      si = choose(size_score, size_work, size_index);
      kept = lns(static_cast<Op>(op), sizes[si]);
      if (kept) ++report_.lns_improvements;
    }
    if (kept) improved();
    const double work = static_cast<double>(t_work_done - work0) + 1.0;
    const double gain = static_cast<double>(before) - static_cast<double>(soc_) +
                        0.5 * (static_cast<double>(makespan_before) - static_cast<double>(makespan_));
    update(score[op], gain / work);
    op_work[op] = op_work[op] == 0.0 ? work : 0.8 * op_work[op] + 0.2 * work;
    if (op != kShortcut) {
      update(size_score[si], gain / work);
      size_work[si] = size_work[si] == 0.0 ? work : 0.8 * size_work[si] + 0.2 * work;
    }
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
