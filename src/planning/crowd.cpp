#include "earc/planning/crowd.hpp"

#include <algorithm>
#include <cmath>

#include "earc/planning/lacam.hpp"
#include "earc/planning/lattice_lns.hpp"
#include "earc/util/random.hpp"

namespace earc {

// Each configuration step is per_step time steps of straight motion; headings
// turn from start to goal heading while a robot is on lattice vertices or
// edges, pausing everyone where a robot needs more time to turn.
std::optional<std::vector<Path>> crowdPaths(const CrowdRoadmap& rm, std::vector<std::vector<int>> configs,
                                            int per_step, const std::vector<std::vector<double>>& starts,
                                            const std::vector<std::vector<double>>& goals) {
  const int n = rm.robotCount();
  auto onLattice = [&](int i, std::size_t t) {
    return rm.owner(configs[t][static_cast<std::size_t>(i)]) < 0 &&
           rm.owner(configs[t + 1][static_cast<std::size_t>(i)]) < 0;
  };
  // A robot turns only inside its bounding disc's lattice: where its steps
  // there leave too few time steps to turn, everyone waits a few steps
  // while it turns on its first lattice vertex (a repeated configuration
  // is conflict-free).
  std::vector<double> turn(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    turn[k] = geo::angleDiff(starts[k][2], goals[k][2]);
    const double rate = rm.model(i).resolution().rotation;
    const auto need = static_cast<long long>(std::ceil(std::abs(turn[k]) / rate - 1e-9));
    // Turned before it first reaches its own goal side (where the
    // roadmap's conflicts take it at its goal heading).
    auto goalSide = [&](int v) { return rm.owner(v) == i && !rm.startSide(v); };
    long long have = 0;
    for (std::size_t t = 0; t + 1 < configs.size() && !goalSide(configs[t][k]); ++t)
      if (onLattice(i, t)) have += per_step;
    if (have >= need) continue;
    std::size_t t0 = 0;
    while (t0 < configs.size() && rm.owner(configs[t0][k]) >= 0) ++t0;
    if (t0 == configs.size()) return std::nullopt;
    const auto pause = static_cast<std::size_t>((need - have + per_step - 1) / per_step);
    const std::vector<int> hold = configs[t0];
    configs.insert(configs.begin() + static_cast<std::ptrdiff_t>(t0), pause, hold);
  }
  std::vector<Path> paths;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double rate = rm.model(i).resolution().rotation;
    Path p(3);
    p.reserve((configs.size() - 1) * static_cast<std::size_t>(per_step) + 1);
    p.push(starts[k]);
    double heading = starts[k][2], left = std::abs(turn[k]);
    const double sign = turn[k] < 0 ? -1.0 : 1.0;
    for (std::size_t t = 0; t + 1 < configs.size(); ++t) {
      const geo::Vec2 a = rm.position(configs[t][k]), b = rm.position(configs[t + 1][k]);
      const bool lattice = onLattice(i, t);
      for (int s = 1; s <= per_step; ++s) {
        const double f = static_cast<double>(s) / per_step;
        if (lattice && left > 0) {
          const double d = std::min(rate, left);
          heading += sign * d;
          left -= d;
        }
        const double q[3] = {a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, heading};
        p.push(q);
      }
    }
    // The ends exactly as the scenario gives them (the lattice's positions
    // agree to rounding).
    double* last = p.mutableAt(p.size() - 1);
    std::copy(goals[k].begin(), goals[k].end(), last);
    double* first = p.mutableAt(0);
    std::copy(starts[k].begin(), starts[k].end(), first);
    paths.push_back(std::move(p));
  }
  return paths;
}

// On a grid map's cells a plan's steps follow the cells' axes, as the
// bound does: refinePlan's shortcuts off the axes find next to nothing
// there (a fraction of a percent), and the time is better spent on the
// roadmap. On other lattices they cut corners the roadmap cannot.
static double latticeRefineShare(bool grid_lattice) { return grid_lattice ? 0.95 : 0.8; }

CrowdOutcome planCrowd(const CollisionWorld& world, const std::vector<const RobotModel*>& models,
                       const std::vector<int>& robots, const std::vector<std::vector<double>>& starts,
                       const std::vector<std::vector<double>>& goals, const Deadline& deadline, std::uint64_t seed,
                       const CrowdOptions& options) {
  CrowdOutcome out;
  Stopwatch clock;
  const CrowdRoadmap rm(world, models, robots, starts, goals);
  const double roadmap_s = clock.seconds();
  out.stats.roadmap_vertices = rm.vertexCount();
  out.stats.lattice_spacing = rm.spacing();
  out.stats.grid_lattice = rm.gridAligned();
  out.stats.bounding_radius = rm.radius();
  out.stats.roadmap_s = roadmap_s;
  const LacamResult r = solveLacam(rm, deadline, seed);
  out.stats.search_s = clock.seconds() - roadmap_s;
  out.stats.configurations = static_cast<std::int64_t>(r.nodes);
  out.stats.expansions = static_cast<std::int64_t>(r.expansions);
  out.stats.spread_meetings = r.spread_meetings;
  out.stats.restarts = static_cast<std::int64_t>(r.restarts);
  if (!r.solved) {
    out.why = r.why;
    out.timed_out = r.timed_out;
    return out;
  }
  std::vector<std::vector<int>> configs = r.configs;
  if (options.polish) {
    // One round of single robots: cheap next to the search (a robot's
    // space-time search each), and it takes out most of LaCAM's detours.
    out.stats.polish = refineOnLattice(rm, configs, deadline, splitSeed(seed, 0x9011), rm.robotCount());
  }
  out.stats.roadmap_steps = static_cast<std::int64_t>(configs.size()) - 1;
  out.stats.first_solution_s = clock.seconds();
  const double lattice_refine_s = latticeRefineShare(rm.gridAligned()) * options.refine_s;
  if (lattice_refine_s > 0) {
    // The first plan's costs, for refinement's record of cost over time.
    if (auto first = crowdPaths(rm, configs, rm.stepsPerEdge(), starts, goals)) {
      std::size_t soc = 0, makespan = 0;
      for (std::size_t i = 0; i < first->size(); ++i) {
        Path& p = (*first)[i];
        settleAtGoal(rm.model(static_cast<int>(i)), p);  // as plan() counts costs
        p.dropTrailingWaits();
        soc += p.size() - 1;
        makespan = std::max(makespan, p.size() - 1);
      }
      out.stats.first_sum_of_costs = static_cast<std::int64_t>(soc);
      out.stats.first_makespan = static_cast<std::int64_t>(makespan);
    }
    Stopwatch lns;
    const Deadline& within = options.refine_deadline ? *options.refine_deadline : deadline;
    const double work0 = workSecondsDone();
    const Deadline lattice_deadline = within.capped(lattice_refine_s);
    LatticeRefineStats stats;
    // On a grid map's cells the refinement takes diagonal steps too.
    out.paths = refineWithDiagonals(rm, configs, lattice_deadline, seed, starts, goals, stats);
    if (!out.paths) stats = refineOnLattice(rm, configs, lattice_deadline, seed);
    LatticeRefineStats& lattice = out.stats.lattice_refine.emplace(std::move(stats));
    lattice.s = lns.seconds();
    // Budgets that count work take the lattice's share as work too.
    if (within.countsWork()) lattice.work_s = workSecondsDone() - work0;
    if (out.paths) {
      out.stats.steps_per_roadmap_step = rm.stepsPerEdge();
      return out;
    }
  }
  const int per_step = rm.stepsPerEdge();
  out.stats.steps_per_roadmap_step = per_step;
  out.paths = crowdPaths(rm, std::move(configs), per_step, starts, goals);
  if (!out.paths) out.why = "a robot has to turn but never stands on a lattice vertex";
  return out;
}


std::vector<int> jamGroup(const std::vector<Path>& paths, std::vector<int> robots, const std::vector<int>& previous,
                          geo::Vec2 place, std::size_t size) {
  std::vector<char> in(paths.size(), 0);
  for (int r : robots) in[static_cast<std::size_t>(r)] = 1;
  for (int r : previous)
    if (!in[static_cast<std::size_t>(r)]) {
      in[static_cast<std::size_t>(r)] = 1;
      robots.push_back(r);
    }
  // The others by the closest their path comes to the jam, sampled every
  // few steps (a mobile robot moves little between them).
  std::vector<std::pair<double, int>> others;
  for (std::size_t r = 0; r < paths.size(); ++r) {
    if (in[r] || paths[r].empty()) continue;
    double best = 1e300;
    const std::size_t n = paths[r].size();
    for (std::size_t t = 0; t < n; t += 4) {
      const double* q = paths[r].at(t);
      best = std::min(best, geo::norm({q[0] - place.x, q[1] - place.y}));
    }
    const double* q = paths[r].back();
    best = std::min(best, geo::norm({q[0] - place.x, q[1] - place.y}));
    others.emplace_back(best, static_cast<int>(r));
  }
  std::sort(others.begin(), others.end());
  for (const auto& [d, r] : others) {
    if (robots.size() >= size) break;
    robots.push_back(r);
  }
  std::sort(robots.begin(), robots.end());
  return robots;
}

}  // namespace earc
