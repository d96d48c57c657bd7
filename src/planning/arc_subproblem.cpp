// ARC's subproblem around a conflict: its robots, time window and region
// at a given expansion level (createSubproblem, declared in arc.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "earc/planning/arc.hpp"

namespace earc {

namespace {

bool goalsApart(const std::vector<int>& robots, const std::vector<const RobotModel*>& models,
                const std::vector<Path>& paths, std::size_t t) {
  for (std::size_t i = 0; i < robots.size(); ++i)
    for (std::size_t j = i + 1; j < robots.size(); ++j) {
      auto a = static_cast<std::size_t>(robots[i]);
      auto b = static_cast<std::size_t>(robots[j]);
      if (robotsTouch(*models[a], paths[a].at(t), *models[b], paths[b].at(t))) return false;
    }
  return true;
}

}  // namespace

Subproblem createSubproblem(const Conflict& conflict, const std::vector<int>& robots, int level,
                            const std::vector<const RobotModel*>& models, const std::vector<Path>& paths,
                            const CollisionWorld& world, const PlannerSettings& settings) {
  Subproblem sub;
  sub.robots = robots;
  std::sort(sub.robots.begin(), sub.robots.end());
  sub.expansions = level;
  std::size_t horizon = 0;  // last step of the longest path among the robots
  for (int r : sub.robots) horizon = std::max(horizon, paths[static_cast<std::size_t>(r)].size() - 1);
  const std::size_t w = static_cast<std::size_t>(settings.arc.initial_window) << std::min(level, 30);
  const auto tc = static_cast<std::size_t>(std::floor(conflict.t));
  sub.t_start = tc > w ? tc - w : 0;
  sub.t_end = std::min(horizon, static_cast<std::size_t>(std::ceil(conflict.t)) + w);
  // Local goals that touch each other make the subproblem unsolvable: move
  // the end of the window forward until they are apart (at the latest the
  // robots' final goals, which a valid scenario keeps apart).
  while (sub.t_end < horizon && !goalsApart(sub.robots, models, paths, sub.t_end)) ++sub.t_end;
  const bool last_level = level >= settings.arc.max_expansions;
  sub.whole_problem = sub.t_start == 0 && sub.t_end >= horizon && last_level;
  const bool saturated = sub.t_start == 0 && sub.t_end >= horizon && !last_level;
  bool regions_full = true;

  for (int r : sub.robots) {
    const RobotModel& m = *models[static_cast<std::size_t>(r)];
    const Path& p = paths[static_cast<std::size_t>(r)];
    const double* s = p.at(sub.t_start);
    const double* g = p.at(sub.t_end);
    sub.starts.emplace_back(s, s + m.dim());
    sub.goals.emplace_back(g, g + m.dim());
    ConfigBox full;
    m.samplingBounds(world.workspace(), full.lo, full.hi);
    ConfigBox box;
    if (sub.whole_problem) {
      box = full;
    } else {
      box.lo.assign(static_cast<std::size_t>(m.dim()), 1e300);
      box.hi.assign(static_cast<std::size_t>(m.dim()), -1e300);
      for (std::size_t t = sub.t_start; t <= sub.t_end; ++t) {
        const double* q = p.at(t);
        for (int j = 0; j < m.dim(); ++j) {
          box.lo[static_cast<std::size_t>(j)] = std::min(box.lo[static_cast<std::size_t>(j)], q[j]);
          box.hi[static_cast<std::size_t>(j)] = std::max(box.hi[static_cast<std::size_t>(j)], q[j]);
        }
      }
      const double grow = 1.0 + level;
      for (int j = 0; j < m.dim(); ++j) {
        auto ju = static_cast<std::size_t>(j);
        if (m.isMobile() && j == 2) {  // headings stay free
          box.lo[ju] = -std::numbers::pi;
          box.hi[ju] = std::numbers::pi;
          continue;
        }
        const double margin = (m.isMobile() ? settings.arc.region_margin : settings.arc.joint_margin) * grow;
        box.lo[ju] = std::max(full.lo[ju], box.lo[ju] - margin);
        box.hi[ju] = std::min(full.hi[ju], box.hi[ju] + margin);
      }
    }
    // The footprint of the region in the plane: where the robot's body can be.
    geo::Aabb foot;
    if (m.isMobile()) {
      foot = geo::Aabb{{box.lo[0], box.lo[1]}, {box.hi[0], box.hi[1]}}.inflated(m.boundingRadius());
    } else {
      geo::Vec2 c = m.boundingCenter(s);
      foot = geo::Aabb{c, c}.inflated(m.boundingRadius());
    }
    sub.workspace_region.expand(foot);
    sub.region.push_back(std::move(box));
    regions_full = regions_full && sub.region.back() == full;
  }
  // A window grown to span the robots' whole paths, with regions that
  // cover everything, is the whole problem before the last level: say so,
  // and ARC goes straight on to larger budgets instead of retrying the
  // same subproblem level by level. So is one whose regions together
  // already span the workspace: the levels left would only widen the
  // region of a robot whose path keeps to one part of it, a margin a
  // level, each at the same budget.
  if (saturated && (regions_full || sub.workspace_region.inflated(1e-9).contains(world.workspace()))) sub.whole_problem = true;
  return sub;
}

}  // namespace earc
