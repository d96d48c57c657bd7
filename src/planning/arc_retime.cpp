// ARC's local solutions retimed inside their window before the splice
// (retimeLocalSolution, declared in arc.hpp).
#include <algorithm>

#include "earc/planning/arc.hpp"
#include "earc/planning/compact.hpp"

namespace earc {

std::int64_t retimeLocalSolution(const Subproblem& sub, LocalSolution& local,
                                 const std::vector<const RobotModel*>& models, const std::vector<Path>& paths,
                                 const CollisionWorld& world, const Deadline& deadline) {
  // A coupled answer moves its robots in lockstep, each held back by the
  // slowest of a composite motion, and a decoupled one has waits for
  // robots that may have passed already. The window's own instants are a
  // small plan: its robots are retimed in it as compactPlan retimes a
  // whole plan, each keeping its route and arriving no later, against the
  // group's paths and the outside robots' window steps, which stay as they
  // are. Each robot then waits at its window goal until the window's end,
  // so the splice is as valid as the answer was.
  const std::size_t len = local.length();
  if (len < 3) return 0;
  std::vector<const RobotModel*> window_models;
  std::vector<Path> window_paths;
  std::vector<std::size_t> which;
  std::vector<char> in_group(paths.size(), 0);
  geo::Aabb group_box;
  for (std::size_t i = 0; i < sub.robots.size(); ++i) {
    const auto r = static_cast<std::size_t>(sub.robots[i]);
    in_group[r] = 1;
    const RobotModel& m = *models[r];
    group_box.expand(pathReach(m, local.paths[i], 0, len));
    if (m.isMobile()) which.push_back(window_paths.size());
    window_models.push_back(&m);
    Path p = local.paths[i];
    p.dropTrailingWaits();
    window_paths.push_back(std::move(p));
  }
  if (which.empty()) return 0;
  for (std::size_t r = 0; r < paths.size(); ++r) {
    if (in_group[r] || paths[r].empty()) continue;
    Path p = paths[r].slice(sub.t_start, sub.t_start + len);
    if (p.empty()) p.push(paths[r].back());
    if (!pathReach(*models[r], p).overlaps(group_box)) continue;
    window_models.push_back(models[r]);
    window_paths.push_back(std::move(p));
  }
  const CompactReport rep = compactRobots(window_models, window_paths, which, &world, deadline, 2);
  if (rep.steps_saved <= 0) return 0;
  for (std::size_t i = 0; i < sub.robots.size(); ++i) {
    Path p = std::move(window_paths[i]);
    while (p.size() < len) p.push(p.back());
    local.paths[i] = std::move(p);
  }
  return rep.steps_saved;
}

}  // namespace earc
