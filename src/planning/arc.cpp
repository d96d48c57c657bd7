#include "earc/planning/arc.hpp"

#include "arc_run.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "earc/planning/compact.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/crowd.hpp"
#include "earc/util/random.hpp"

namespace earc {

// A solver's answer is spliced into the robots' paths: one path per robot
// of the subproblem, all of one length, is what makes that safe. Anything
// else is a bug in the solver, said as such rather than as a bad_alloc.
void requireWellFormed(const LocalSolution& local, const Subproblem& sub, const std::string& solver) {
  bool ok = local.paths.size() == sub.robots.size() && !local.paths.empty() && local.paths.front().size() > 0;
  for (std::size_t i = 0; ok && i < local.paths.size(); ++i)
    ok = local.paths[i].size() == local.paths.front().size() &&
         local.paths[i].dim() == static_cast<int>(sub.starts[i].size());
  if (!ok)
    throw std::logic_error("solver '" + solver + "' answered a subproblem of " + std::to_string(sub.robots.size()) +
                           " robots with " + std::to_string(local.paths.size()) + " paths of unequal or wrong shape");
}

void splice(std::vector<Path>& paths, const Subproblem& sub, const LocalSolution& local) {
  for (std::size_t i = 0; i < sub.robots.size(); ++i) {
    Path& p = paths[static_cast<std::size_t>(sub.robots[i])];
    while (p.size() < sub.t_start + 1) p.push(p.back());
    Path next = p.slice(0, sub.t_start);
    next.append(local.paths[i]);
    next.append(p, sub.t_end + 1);
    p = std::move(next);
  }
}

int mergeOverlapping(std::vector<int>& robots, const std::vector<ResolvedSpan>& spans, std::size_t t0,
                     std::size_t t1, std::size_t max_robots) {
  // One hop only: the robots of spans that share a robot with the conflict
  // itself. Following spans transitively snowballs two robots into a dozen,
  // and no solver in the hierarchy can handle that.
  const std::vector<int> core = robots;
  int added = 0;
  for (const auto& span : spans) {
    if (span.t1 < t0 || span.t0 > t1) continue;
    bool shares = std::any_of(span.robots.begin(), span.robots.end(), [&](int r) {
      return std::find(core.begin(), core.end(), r) != core.end();
    });
    if (!shares) continue;
    std::vector<int> grown = robots;
    for (int r : span.robots)
      if (std::find(grown.begin(), grown.end(), r) == grown.end()) grown.push_back(r);
    if (grown.size() > max_robots) continue;
    added += static_cast<int>(grown.size() - robots.size());
    robots = std::move(grown);
  }
  std::sort(robots.begin(), robots.end());
  return added;
}

// Past the cap an answer that undoes a resolved robot's span is accepted,
// and two groups at the cap can then undo each other for ever. The same
// conflict found again means its resolution was undone, so its group grows
// to take in the robot whose span it keeps undoing. It is keyed on the
// place, not the instant: every resolution shifts the later paths in time.
std::size_t ConflictRecurrence::capFor(const Conflict& c, std::size_t max_robots) {
  const auto cell = [](double v) { return static_cast<long long>(std::floor(v / kCell)); };
  const int before = seen_[{std::min(c.a, c.b), std::max(c.a, c.b), cell(c.place.x), cell(c.place.y)}]++;
  return max_robots + static_cast<std::size_t>(std::min(before / kRecurrencesPerRobot, kMaxExtraRobots));
}

namespace {

// Solver budgets: the solvers' own up to the last expansion level, then
// doubling with every retry of that largest subproblem.
double budgetScale(int level, int max_expansions) {
  return level <= max_expansions ? 1.0 : std::pow(2.0, std::min(level - max_expansions, 20));
}

nlohmann::json boxJson(const geo::Aabb& b) { return {{b.lo.x, b.lo.y}, {b.hi.x, b.hi.y}}; }

}  // namespace

void ArcRun::leaveOutGroupWaits(const Subproblem& sub, const LocalSolution& local) {
  // A local solution's paths share one length, so a robot that reaches its
  // window goal before the group's last step waits there, and its whole
  // later path is late by as much. Leave that wait out when the robot's
  // first conflict comes no sooner than it did with the wait. Mobile robots
  // only: for arms the checks cost more than the few steps they save.
  const std::size_t len = local.length();
  ConflictDetector detector(models_, deadline_);
  std::vector<char> focus(paths_.size(), 0);
  for (std::size_t i = 0; i < sub.robots.size(); ++i) {
    if (!models_[static_cast<std::size_t>(sub.robots[i])]->isMobile()) continue;
    Path arrived = local.paths[i];
    arrived.dropTrailingWaits();
    const std::size_t a = arrived.size() - 1;  // the step it reaches its window goal
    if (a + 1 >= len) continue;
    const auto r = static_cast<std::size_t>(sub.robots[i]);
    Path cand = paths_[r].slice(0, sub.t_start + a + 1);
    cand.append(paths_[r], sub.t_start + len);
    focus[r] = 1;
    std::vector<const Path*> view = pathPointers(paths_);
    view[r] = &cand;
    // Only the group's span again past the arrival is looked at: what comes
    // later is ARC's next conflict either way.
    const std::size_t from = sub.t_start + a;
    const std::size_t to = sub.t_start + 2 * len;
    const auto after = detector.first(view, from, to, &focus);
    bool take = !after;
    if (after && !detector.interrupted()) {
      view[r] = &paths_[r];  // with the wait: did it meet someone that soon too?
      const auto before = detector.first(view, from, static_cast<std::size_t>(std::ceil(after->t)), &focus);
      take = before && before->t <= after->t;
    }
    focus[r] = 0;
    if (detector.interrupted()) return;
    if (!take) continue;
    waits_left_out_ += static_cast<std::int64_t>(len - 1 - a);
    paths_[r] = std::move(cand);
  }
}

std::optional<int> ArcRun::conflictsWithResolved(const Subproblem& sub, const LocalSolution& local) {
  // Would this local solution collide, inside its own span, with a robot
  // whose earlier local solution covers that span? Then that robot joins.
  std::vector<Path> candidate;
  std::vector<const Path*> view = pathPointers(paths_);
  candidate.reserve(sub.robots.size());
  std::vector<char> focus(paths_.size(), 0);
  for (std::size_t i = 0; i < sub.robots.size(); ++i) {
    auto r = static_cast<std::size_t>(sub.robots[i]);
    Path p = paths_[r];
    while (p.size() < sub.t_start + 1) p.push(p.back());
    Path next = p.slice(0, sub.t_start);
    next.append(local.paths[i]);
    candidate.push_back(std::move(next));
    focus[r] = 1;
  }
  for (std::size_t i = 0; i < sub.robots.size(); ++i) view[static_cast<std::size_t>(sub.robots[i])] = &candidate[i];
  const std::size_t t1 = sub.t_start + local.length() - 1;
  // Out of time, no robot is merged: the plan's own search for conflicts
  // then stops at the deadline too, so nothing unchecked is reported solved.
  ConflictDetector detector(models_, deadline_);
  auto c = detector.first(view, sub.t_start, t1, &focus);
  if (!c) return std::nullopt;
  const int other = focus[static_cast<std::size_t>(c->a)] ? c->b : c->a;
  if (focus[static_cast<std::size_t>(other)]) return std::nullopt;
  for (const auto& span : spans_) {
    if (span.t1 < sub.t_start || span.t0 > t1) continue;
    if (std::find(span.robots.begin(), span.robots.end(), other) != span.robots.end()) return other;
  }
  return std::nullopt;
}

bool ArcRun::resolve(const Conflict& c, std::size_t max_robots) {
  std::vector<int> robots{c.a, c.b};
  const auto tc = static_cast<std::size_t>(c.t);
  int merged_here = mergeOverlapping(robots, spans_, tc, tc, max_robots);
  merged_ += merged_here;
  // Levels beyond max_expansions re-solve the last level's subproblem (the
  // whole problem, unless the paths are very long) with ever larger
  // budgets, until the deadline: giving up with time left helps no one.
  if (robots.size() >= static_cast<std::size_t>(settings_.arc.max_merged_robots)) ++capped_since_handover_;
  if (std::binary_search(jam_group_.begin(), jam_group_.end(), c.a) ||
      std::binary_search(jam_group_.begin(), jam_group_.end(), c.b))
    ++jam_conflicts_since_handover_;
  // In a fleet whose first jam would be half of it or more, a jam is
  // handed over only once ARC's own window levels have failed: replanning
  // most of a small fleet on the crowd solver's roadmap makes its plan far
  // longer than ARC's.
  const bool small_fleet = 2 * firstJamSize(robots.size()) >= paths_.size();
  const bool jammed =
      crowd_ok_ && !small_fleet &&
      (conflicts_ - conflicts_at_handover_ > kJamConflictsPerRobot * static_cast<double>(paths_.size()) ||
       capped_since_handover_ >= kJamCappedGroups ||
       jam_conflicts_since_handover_ > std::max<std::size_t>(kJamMinRecurrences, paths_.size() / 32));
  const int jam_level = small_fleet ? settings_.arc.max_expansions + 1 : kJamLevel;
  for (int level = 0, tried = 0;;) {
    if (deadline_.expired()) return false;
    if (crowd_ok_ && (jammed || level >= jam_level))
      if (auto handed = handOverJam(c, robots)) return *handed;
    // Every window tried counts, also when the plan then fails: the
    // stats say how far it went.
    if (level > tried) {
      ++expansions_;
      tried = level;
    }
    Subproblem sub = createSubproblem(c, robots, std::min(level, settings_.arc.max_expansions), models_, paths_, world_,
                                      settings_);
    if (sub.whole_problem && level < settings_.arc.max_expansions) level = settings_.arc.max_expansions;
    report(&PlanProgress::subproblem_robots, static_cast<int>(sub.robots.size()));
    report(&PlanProgress::expansions, level);
    nlohmann::json ev;
    if (settings_.trace)
      ev = {{"type", "subproblem"}, {"id", subproblem_id_}, {"conflict", conflicts_ - 1}, {"robots", sub.robots},
            {"window", {sub.t_start, sub.t_end}}, {"region", boxJson(sub.workspace_region)},
            {"expansions", level}, {"merged", merged_here}};
    if (settings_.trace && max_robots > static_cast<std::size_t>(settings_.arc.max_merged_robots))
      ev["merge_cap"] = max_robots;
    ++subproblem_id_;
    SolverContext ctx{world_, models_, *roadmaps_, paths_, sub, deadline_,
                      splitSeed(settings_.seed, static_cast<std::uint64_t>(subproblem_id_)), budgetScale(level, settings_.arc.max_expansions)};
    // Every other retry beyond the last level plans the group as if the
    // robots outside it were not there. A group can be walled in by their
    // paths, which bigger budgets do not change (48 and 64 robots on a
    // dense MovingAI map: a 4- or 5-robot group whose window spanned its
    // whole paths failed for the whole limit); the robots in its way then
    // meet its answer as later conflicts of their own and are replanned.
    ctx.ignore_others = level > settings_.arc.max_expansions && (level - settings_.arc.max_expansions) % 2 == 1;
    if (settings_.trace && ctx.ignore_others) ev["ignore_others"] = true;
    nlohmann::json attempts = nlohmann::json::array();
    bool restart = false;
    for (auto& solver : hierarchy_) {
      Stopwatch sw;
      const double built_before = roadmaps_->buildSeconds();
      SolverOutcome out = solver->solve(ctx);
      // A roadmap built on the way is kept for every later subproblem of
      // the plan: its cost is the plan's (stats.roadmap_build_s), not this
      // attempt's, which may be the first of many that use it.
      const double building = roadmaps_->buildSeconds() - built_before;
      const double secs = std::max(0.0, sw.seconds() - building);
      out.seconds = secs;
      solver_time_[solver->name()] += secs;
      const std::string how = out.how.empty() ? solver->name() : out.how;
      if (settings_.trace) {
        nlohmann::json attempt = {{"solver", how}, {"ok", out.solution.has_value()}, {"time_s", secs}};
        if (building > 0) attempt["roadmap_build_s"] = building;
        if (!out.detail.empty()) attempt["detail"] = out.detail;
        attempts.push_back(std::move(attempt));
      }
      if (!out.solution) continue;
      requireWellFormed(*out.solution, sub, how);
      if (robots.size() < max_robots) {
        if (auto other = conflictsWithResolved(sub, *out.solution)) {
          // Merge the robot rather than undo its earlier resolution, and
          // solve again at the same level with the larger group.
          robots.push_back(*other);
          std::sort(robots.begin(), robots.end());
          ++merged_here;
          ++merged_;
          ev["solved_by"] = "merged";
          restart = true;
          break;
        }
      }
      for (auto& s : hierarchy_) s->accepted(ctx, *out.solution, out);
      ++by_solver_[how];
      ++by_size_[std::to_string(sub.robots.size())];
      if (settings_.arc.restamp_coupled && how == "coupled") {
        const RestampReport rs = restampLocalSolution(sub, *out.solution, models_, paths_, world_, deadline_);
        (rs.restamped ? restamped_ : lockstep_) += 1;
        restamped_around_ += rs.around_outside ? 1 : 0;
        restamped_steps_ += rs.steps_saved;
      }
      // A decoupled answer is each robot's earliest arrival over roadmap
      // edges taken at full speed: retiming it finds nothing to save.
      if (settings_.arc.retime_windows && how != "decoupled")
        window_retimed_ += retimeLocalSolution(sub, *out.solution, models_, paths_, world_, deadline_);
      splice(paths_, sub, *out.solution);
      leaveOutGroupWaits(sub, *out.solution);
      spans_.push_back({sub.robots, sub.t_start, sub.t_start + out.solution->length() - 1});
      last_t_start_ = sub.t_start;
      if (settings_.trace) {
        ev["solved_by"] = how;
        if (out.entry >= 0) ev["entry"] = out.entry;
        ev["attempts"] = attempts;
        ev["length"] = out.solution->length();
        traceEvent(ev);
      }
      return true;
    }
    if (settings_.trace) {
      if (!restart) ev["solved_by"] = "failed";
      ev["attempts"] = attempts;
      traceEvent(ev);
    }
    if (sub.whole_problem && !restart) whole_problem_failed_ = true;
    if (!restart) ++level;
  }
}

PlanResult ArcRun::run() {
  Stopwatch clock;
  PlanResult result;
  result.solution.scenario = scenario_.name;
  roadmaps_ = std::make_unique<RoadmapSet>(world_, models_, settings_.roadmap.samples, settings_.roadmap.neighbors,
                                           splitSeed(settings_.seed, 1), deadline_);
  if (context_.roadmap_cache) roadmaps_->useCache(*context_.roadmap_cache, scenario_);
  for (std::size_t r = 0; r < models_.size(); ++r) {
    auto p = individualPath(world_, *roadmaps_, *models_[r], static_cast<int>(r), deadline_,
                            splitSeed(settings_.seed, 100 + r));
    if (!p) {
      failures_.insert(deadline_.expired() ? FailureCause::TimeLimit : FailureCause::NoIndividualPath);
      result.stats.unsolved_robot = scenario_.robots[r].name;
      break;
    }
    paths_.push_back(std::move(*p));
    report(&PlanProgress::individual_paths, static_cast<int>(paths_.size()));
  }
  const double individual_s = clock.seconds();
  crowd_ok_ = settings_.arc.crowd_fallback;
  for (const RobotModel* m : models_) crowd_ok_ = crowd_ok_ && m->isMobile();
  bool solved = false;
  if (failures_.empty()) {
    ConflictDetector detector(models_, deadline_);
    std::size_t from = 0;
    for (;;) {
      if (deadline_.expired()) {
        failures_.insert(FailureCause::TimeLimit);
        break;
      }
      auto c = detector.first(pathPointers(paths_), from);
      if (!c && detector.interrupted()) {
        failures_.insert(FailureCause::TimeLimit);
        break;
      }
      if (!c) {
        solved = true;
        break;
      }
      ++conflicts_;
      report(&PlanProgress::conflicts, conflicts_);
      report(&PlanProgress::conflict_step, static_cast<int>(c->t));
      if (context_.progress) {
        std::size_t steps = 0;
        for (const Path& p : paths_) steps = std::max(steps, p.size());
        report(&PlanProgress::steps, static_cast<int>(steps));
      }
      traceEvent({{"type", "conflict"}, {"id", conflicts_ - 1}, {"robots", {c->a, c->b}}, {"t", c->t},
                  {"place", {c->place.x, c->place.y}}, {"at_s", clock.seconds()}});
      const std::size_t cap = recurrence_.capFor(*c, static_cast<std::size_t>(settings_.arc.max_merged_robots));
      if (cap > static_cast<std::size_t>(settings_.arc.max_merged_robots)) ++cap_raised_;
      if (!resolve(*c, cap)) {
        failures_.insert(deadline_.expired() ? FailureCause::TimeLimit : FailureCause::SubproblemUnsolved);
        // Said too when the time ran out re-solving a conflict whose
        // subproblem had already grown to the whole problem and failed.
        if (whole_problem_failed_) failures_.insert(FailureCause::SubproblemUnsolved);
        break;
      }
      from = last_t_start_;
    }
  }
  result.solution.solved = solved;
  // The valid plan's mobile robots retimed along their routes: a step
  // after the loop, so it changes no conflict ARC met, and it never makes a
  // robot arrive later. For arms the checks cost more than they save. In
  // a crowd of hundreds the pass would take longer than the plan: it
  // stops at a quarter of the plan's time, each robot retimed or not.
  std::optional<CompactReport> compacted;
  Stopwatch compact_clock;
  std::vector<std::size_t> mobile;
  for (std::size_t r = 0; r < models_.size(); ++r)
    if (models_[r]->isMobile()) mobile.push_back(r);
  if (solved && settings_.arc.compact_passes > 0 && !mobile.empty()) {
    for (Path& p : paths_) p.dropTrailingWaits();
    compacted = compactRobots(models_, paths_, mobile, &world_, deadline_.capped(kCompactShare * soFar()),
                              settings_.arc.compact_passes,
                              static_cast<std::size_t>(settings_.arc.compact_states));
    // Then a few shortcuts, with a shallow search (a cut that is free is
    // found at once, one that is not fails cheaply). Bounded by their
    // count, not by a share of the time: a share would make the plan
    // depend on how fast the roadmaps came (a cache, the machine's load).
    if (settings_.arc.compact_shortcut_robots > 0 && !deadline_.expired()) {
      const CompactReport cut = shortcutRobots(
          models_, paths_, mobile, world_, deadline_,
          static_cast<std::size_t>(settings_.arc.compact_shortcut_robots), settings_.arc.compact_shortcut_tries,
          splitSeed(settings_.seed, 0x5c0ffee), kShortcutStates);
      compacted->steps_saved += cut.steps_saved;
    }
  }
  const double compact_s = compact_clock.seconds();
  if (solved) result.solution.paths = std::move(paths_);
  result.failures = failures_;
  result.stats.planning_time_s = clock.seconds() - lattice_s_;
  if (solved && whole_crowd_) result.stats.lacam = whole_crowd_;
  ArcStats& st = result.stats.arc.emplace();
  st.individual_paths_s = individual_s;
  st.conflicts = conflicts_;
  st.subproblems = subproblem_id_;
  st.subproblems_by_solver = by_solver_;
  st.subproblems_by_robots = by_size_;
  st.solver_time_s = solver_time_;
  st.window_expansions = expansions_;
  st.waits_left_out = waits_left_out_;
  if (settings_.arc.retime_windows) st.window_retimed = window_retimed_;
  if (settings_.arc.restamp_coupled) {
    st.coupled_restamped = restamped_;
    st.coupled_restamped_around = restamped_around_;
    st.coupled_lockstep = lockstep_;
    st.restamped_steps = restamped_steps_;
  }
  if (compacted) {
    st.compacted_steps = compacted->steps_saved;
    st.compacted_s = compact_s;
  }
  st.solver_budgets = settings_.work_budgets ? "work" : "seconds";
  st.robots_merged = merged_;
  st.merge_cap_raised = cap_raised_;
  st.crowd_handovers = handovers_;
  st.crowd_s = crowd_s_;
  st.roadmap_edge_checks = static_cast<std::int64_t>(roadmaps_->edgeChecks());
  st.roadmaps_built = static_cast<std::int64_t>(roadmaps_->built());
  if (context_.roadmap_cache) result.stats.roadmaps_reused = static_cast<std::int64_t>(roadmaps_->reused());
  st.roadmap_vertices = static_cast<std::int64_t>(roadmaps_->vertices());
  st.roadmap_build_s = roadmaps_->buildSeconds();
  for (auto& solver : hierarchy_) solver->finish(result.stats);
  if (settings_.trace) result.trace = {{"format", "earc.trace.v1"}, {"events", events_}};
  return result;
}

PlanResult runArc(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context,
                  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy) {
  ArcRun run(scenario, settings, context, std::move(hierarchy));
  return run.run();
}

}  // namespace earc
