// ARC's jams handed to the crowd solver (ArcRun::handOverJam).
#include <algorithm>

#include "arc_run.hpp"
#include "earc/util/random.hpp"

namespace earc {

// The rules (constants in arc_run.hpp). A jam: ARC's local solvers failed
// on a conflict's subproblem through kJamLevel window levels, or since the last jam kJamConflictsPerRobot
// conflicts a robot came and went, kJamCappedGroups conflicts' groups
// grew to the merge cap, or a thirty-second of the robots' count of
// conflicts (at least kJamMinRecurrences) involved the last jam's robots.
// Its robots, the last jam's and those whose paths pass nearest are
// planned together by the crowd solver from their starts to their goals,
// the others left out; what their new paths meet is resolved as any
// conflict. The first jam takes at least a quarter of the robots, each
// later one kJamGrowth times the last one's, so a crowd that keeps
// jamming is planned whole after a few. In a fleet whose first jam would
// be half of it or more, only a conflict that failed every level is one.

std::size_t ArcRun::firstJamSize(std::size_t conflict_robots) const {
  return std::min(std::max({kFirstJam, 4 * conflict_robots, paths_.size() / 4}), paths_.size());
}

std::optional<bool> ArcRun::handOverJam(const Conflict& c, const std::vector<int>& robots) {
  Stopwatch sw;
  jam_size_ = jam_size_ == 0 ? firstJamSize(robots.size()) : std::min(jam_size_ * kJamGrowth, paths_.size());
  std::vector<int> group = jamGroup(paths_, robots, jam_group_, c.place, jam_size_);
  std::vector<std::vector<double>> starts, goals;
  for (int r : group) {
    starts.push_back(scenario_.robots[static_cast<std::size_t>(r)].start);
    goals.push_back(scenario_.robots[static_cast<std::size_t>(r)].goal);
  }
  // A jam may take as long as the plan has taken so far: the crowd
  // solver answers a jam it can solve in well under that, and one stuck
  // on a lattice that does not suit these robots (a dense few box robots)
  // must not take ARC's time.
  const Deadline budget = deadline_.capped(std::max(kJamMinBudgetS, soFar()));
  // Each jam's plan is polished as part of the first plan. A jam of every
  // robot is the whole plan: with --refine it is shortened on the crowd
  // solver's roadmap, as --method lacam does, and that time is
  // refinement's (plan.cpp's refineResult reads stats.lacam).
  CrowdOptions options;
  options.polish = true;
  if (group.size() == paths_.size()) options.refine_s = settings_.post.refine_s;
  options.refine_deadline = &deadline_;
  CrowdOutcome out = planCrowd(world_, models_, group, starts, goals, budget,
                               splitSeed(settings_.seed, 5000 + static_cast<std::uint64_t>(handovers_.size())),
                               options);
  const double lattice_s = out.stats.lattice_refine ? out.stats.lattice_refine->s.value_or(0.0) : 0.0;
  if (out.paths && lattice_s > 0) {
    whole_crowd_ = out.stats;
    lattice_s_ += lattice_s;
  }
  const double jam_s = sw.seconds() - lattice_s;
  crowd_s_ += jam_s;
  nlohmann::json ev = {{"type", "jam"}, {"conflict", conflicts_ - 1}, {"robots", group.size()},
                       {"solved", out.paths.has_value()}, {"time_s", jam_s}};
  if (!out.why.empty()) ev["detail"] = out.why;
  handovers_.push_back({static_cast<std::int64_t>(group.size()), out.paths.has_value(), jam_s});
  traceEvent(ev);
  if (!out.paths) {
    if (deadline_.expired()) return false;
    crowd_ok_ = false;  // the lattice cannot serve these robots: ARC goes on alone
    return std::nullopt;
  }
  for (std::size_t i = 0; i < group.size(); ++i) paths_[static_cast<std::size_t>(group[i])] = std::move((*out.paths)[i]);
  std::erase_if(spans_, [&](const ResolvedSpan& s) {
    for (int r : s.robots)
      if (std::binary_search(group.begin(), group.end(), r)) return true;
    return false;
  });
  jam_group_ = std::move(group);
  conflicts_at_handover_ = conflicts_;
  capped_since_handover_ = 0;
  jam_conflicts_since_handover_ = 0;
  last_t_start_ = 0;
  return true;
}

}  // namespace earc
