// E-ARC's database solver (the paper's Algorithm 2) and planEarc.
#include "earc/methods/database_solver.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string_view>

#include "earc/experience/keys.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/retrieval.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/planning/methods.hpp"
#include "earc/util/format.hpp"
#include "earc/util/random.hpp"

namespace earc {

namespace {

// Random shortcut attempts on a retrieved (or repaired) solution joined to
// the subproblem's start and goal.
constexpr int kConnectShortcuts = 100;
// For arms, after the ends are shortcut (shortcutEnds). 100 attempts alone
// were about 40% of a 16-arm database hit's time; on 60 scenarios the end
// shortcuts and 30 attempts gave about the same median makespan (122
// against 121.5) and sum of costs (1193 against 1196.5), and E-ARC's time
// fell by 7% (paired). For mobile robots the same measured no faster
// (paired 0.96 [0.89, 1.00] at 32 with obstacles) and its sums of costs
// went 2.5% up on one set of 60 scenarios and 4% down on another: left
// as it was.
constexpr int kArmShortcuts = 30;

// Why a query failed when no candidate was both valid and clear.
constexpr std::string_view kNoneToRepair = "none to repair";

// Valid candidates that ran into robots outside the subproblem before the
// query gives up: the region is busy with other robots at this time, and
// more candidates, or a repaired one, run into them too (measured on 20
// plans of 32 mobile robots with obstacles: of 82 repairs tried after 3
// or more such candidates, 4 came out clear; stopping there cut the time
// of the queries that fail by 40%). The decoupled solver, which plans
// around those robots, takes over.
constexpr int kCrowdedGiveUp = 3;
constexpr std::string_view kBusy = "region busy with other robots";

// A candidate that ends where this subproblem does (a stored answer to the
// same subproblem elsewhere, equal up to the rounding of the translation)
// takes its start and goal as they are: a join across a rounding error
// would cost a whole step (stepsBetween rounds up), and an answer that
// passes the robots outside closely runs into them a step late.
bool sameUpToRounding(const CompositeState& a, const CompositeState& b) {
  for (std::size_t r = 0; r < a.size(); ++r)
    for (std::size_t j = 0; j < a[r].size(); ++j)
      if (std::abs(a[r][j] - b[r][j]) > 1e-9) return false;
  return true;
}

// Keys hold positions, not headings, so a retrieved mobile robot's path
// may start facing anywhere: turn the whole path by one angle so that it
// starts at the subproblem's start heading (its steps keep their turns;
// the turned candidate is validated like any other). Without this, joins
// spend up to pi / rotation-resolution steps turning on the spot.
void alignHeadings(const std::vector<const RobotModel*>& robots, const Subproblem& sub, std::vector<Path>& paths) {
  for (std::size_t r = 0; r < robots.size(); ++r) {
    if (!robots[r]->isMobile() || paths[r].empty()) continue;
    const double turn = geo::wrapAngle(sub.starts[r][2] - paths[r].at(0)[2]);
    for (std::size_t t = 0; t < paths[r].size(); ++t) {
      double* q = paths[r].mutableAt(t);
      q[2] = geo::wrapAngle(q[2] + turn);
    }
  }
}

bool allArms(const std::vector<const RobotModel*>& robots) {
  return std::none_of(robots.begin(), robots.end(), [](const RobotModel* m) { return m->isMobile(); });
}

}  // namespace

std::string withoutNumbers(std::string_view text) {
  std::string out;
  auto digit = [&](std::size_t j) { return j < text.size() && std::isdigit(static_cast<unsigned char>(text[j])); };
  for (std::size_t i = 0; i < text.size(); ++i) {
    // A decimal point inside a number ("1.05") is part of it.
    const bool in_number = digit(i) || (text[i] == '.' && i > 0 && digit(i - 1) && digit(i + 1));
    if (!in_number)
      out += text[i];
    else if (out.empty() || out.back() != 'N')
      out += 'N';
  }
  return out;
}

SolverOutcome DatabaseSolver::solve(SolverContext& ctx) {
  SolverOutcome out = query(ctx);
  if (settings_.shadow_decoupled) shadow(ctx, out);
  return out;
}

void DatabaseSolver::shadow(SolverContext& ctx, const SolverOutcome& db) {
  Stopwatch sw;
  const SolverOutcome dec = DecoupledSolver().solve(ctx);
  const double seconds = sw.seconds();
  Shadow& s = shadow_;
  ++s.queries;
  s.database += db.solution.has_value();
  s.decoupled += dec.solution.has_value();
  if (db.solution && dec.solution) {
    ++s.both;
    s.decoupled_s_both.push_back(seconds);
    s.extra_steps_both.push_back(static_cast<long>(db.solution->length()) - static_cast<long>(dec.solution->length()));
  }
  if (!db.solution && !dec.solution) {
    // Why the database failed (the query's tally), numbers taken out so
    // that reasons add up across subproblems.
    const Tally& t = tally_;
    std::string general;
    if (t.why.empty())
      general = "no class of this size";
    else if (t.why == kNoneToRepair)
      general = static_cast<std::size_t>(t.ends_blocked) == t.candidates ? "every candidate blocked at its ends"
                                                                          : "every candidate blocked or crowded";
    else
      general = withoutNumbers(t.why);
    ++s.database_failed_where_decoupled_failed[general];
  }
}

SolverOutcome DatabaseSolver::query(SolverContext& ctx) {
  const Subproblem& sub = ctx.sub;
  std::vector<const RobotModel*> robots;
  for (int r : sub.robots) robots.push_back(ctx.models[static_cast<std::size_t>(r)]);
  tally_ = {};
  if (robots.size() < 2 || robots.size() > kMaxRobots) return {std::nullopt, name(), -1};
  // A stored candidate that no step count joins or follows at these
  // robots' resolution (NoStepCountError: a damaged or made-up row, or one
  // far outside this workspace at a fine resolution) is passed over like
  // an invalid one, and the query goes on with the others: one bad row
  // must not fail every plan that retrieves it.
  std::vector<std::int64_t> unusable;
  auto passOver = [&](std::int64_t id) {
    recordUse(id, false);
    ++tally_.unusable;
    ++unusable_;
  };
  Stopwatch retrieval;
  auto candidates = exp::retrieveCandidates(store_, robots, sub.starts, sub.goals, settings_.k, 0, &unusable);
  retrieval_s_ += retrieval.seconds();
  ++queries_;
  for (std::int64_t id : unusable) passOver(id);
  if (candidates.empty() && unusable.empty()) {
    tally_.why = "no entries of this class";
    return {std::nullopt, name(), -1, 0.0, tally_.why};
  }
  // What became of the candidates, for the trace.
  tally_.candidates = candidates.size() + unusable.size();
  auto failed = [&](std::string_view why) {
    const Tally& t = tally_;
    tally_.why = why;
    return SolverOutcome{std::nullopt, name(), -1, 0.0,
                         std::to_string(t.candidates) + " candidates: " + std::to_string(t.ends_blocked) +
                             " ends blocked, " + std::to_string(t.invalid) + " invalid, " + std::to_string(t.crowded) +
                             " crowded" + (t.unusable ? ", " + std::to_string(t.unusable) + " unusable" : "") + "; " +
                             t.why};
  };
  // An answer may come out far longer than the subproblem needs: at 16
  // arms one in five joined answers took 3.7 to 9 times the steps of the
  // slowest arm's straight motion, where the decoupled solver's answers
  // to the same subproblems took at most 3.1 (--db-max-stretch).
  std::size_t longest = std::numeric_limits<std::size_t>::max();
  int straight = 1;
  if (settings_.max_stretch > 0) {
    for (std::size_t r = 0; r < robots.size(); ++r)
      straight = std::max(straight, robots[r]->stepsBetween(sub.starts[r].data(), sub.goals[r].data()));
    const double bound = settings_.max_stretch * straight;
    if (bound < 1e15) longest = static_cast<std::size_t>(bound);
  }
  auto tooLong = [&](const LocalSolution& sol) {
    const std::size_t steps = sol.length() - 1;  // it holds a state per instant
    if (steps <= longest) return false;
    tally_.too_long = steps;
    ++too_long_;
    return true;
  };
  auto refusedTooLong = [&](std::string_view what) {
    return failed(std::string(what) + " " + std::to_string(tally_.too_long) + " steps, more than " +
                  formatNumber("%g", settings_.max_stretch) + " x " + std::to_string(straight));
  };
  // Try the k nearest in order of how long they would make the local
  // solution (their own steps plus the joins to this start and goal), so
  // the first valid one is also the shortest: a longer local solution
  // delays every later step of these robots and makes new conflicts.
  std::vector<std::size_t> joined;
  constexpr std::size_t kUnjoinable = std::numeric_limits<std::size_t>::max();
  auto joinedLength = [&](exp::Candidate& cand) {
    alignHeadings(robots, sub, cand.paths);
    const auto& p = cand.paths;
    int in = 0, out = 0;
    try {
      for (std::size_t r = 0; r < robots.size(); ++r) {
        in = std::max(in, robots[r]->stepsBetween(sub.starts[r].data(), p[r].at(0)));
        out = std::max(out, robots[r]->stepsBetween(p[r].at(p[r].size() - 1), sub.goals[r].data()));
      }
    } catch (const NoStepCountError&) {
      passOver(cand.id);  // sorted last, and never tried
      return kUnjoinable;
    }
    return p.front().size() + static_cast<std::size_t>(in) + static_cast<std::size_t>(out);
  };
  CompositeChecker checker(ctx.world, robots);
  // The robots outside the subproblem, as the decoupled solver sees them: a
  // stored solution knows nothing of them, and one that runs into them
  // only trades this conflict for the next. Collected when the first
  // candidate gets that far: most queries end before.
  const std::size_t window = sub.t_end - sub.t_start;
  std::optional<std::vector<MovingObstacle>> others;
  // Time-stamped paths of the subproblem's robots from its start, clear of
  // the robots outside.
  auto clearOfOthers = [&](const std::vector<Path>& paths) {
    if (!others) others = nearbyRobots(ctx, 4 * window + 100);
    for (std::size_t r = 0; r < robots.size(); ++r)
      if (!clearOfMoving(*robots[r], paths[r], *others)) return false;
    return true;
  };
  // Shortcutting changes when the robots are where, which the other
  // robots may not allow: then the candidate as stored is tried.
  auto joinClear = [&](const std::vector<Path>& middle) -> std::optional<LocalSolution> {
    for (bool shortcut : {true, false}) {
      LocalSolution sol = connect(checker, ctx, robots, middle, shortcut);
      if (clearOfOthers(sol.paths)) return sol;
    }
    return std::nullopt;
  };

  struct Repairable {
    std::size_t index;
    std::vector<StepRun> runs;
  };
  std::optional<Repairable> best;
  std::optional<SolverOutcome> found;
  // Tries candidates[first..] in order of their joined length.
  auto tryFrom = [&](std::size_t first) {
    for (std::size_t i = joined.size(); i < candidates.size(); ++i) joined.push_back(joinedLength(candidates[i]));
    std::vector<std::size_t> order;
    for (std::size_t i = first; i < candidates.size(); ++i) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return joined[a] < joined[b]; });
    for (std::size_t i : order) {
      if (found || ctx.deadline.expired()) break;
      if (joined[i] == kUnjoinable) continue;  // passed over when measured
      const auto& c = candidates[i];
      try {
        // A candidate is only usable when the subproblem's start and goal
        // connect to its ends without collision.
        if (!checker.motionValid(sub.starts, stateAt(c.paths, 0)) ||
            !checker.motionValid(stateAt(c.paths, c.paths.front().size() - 1), sub.goals)) {
          recordUse(c.id, false);
          ++tally_.ends_blocked;
          continue;
        }
        auto runs = invalidRuns(checker, c.paths);
        if (runs.empty()) {
          auto sol = joinClear(c.paths);
          if (!sol) {
            recordUse(c.id, false);
            ++crowded_;
            if (++tally_.crowded >= kCrowdedGiveUp) break;
            continue;
          }
          if (tooLong(*sol)) {
            recordUse(c.id, false);
            break;
          }
          found = SolverOutcome{std::move(*sol), "database", c.id};
          recordUse(c.id, true);
          ++hits_;
          break;
        }
        recordUse(c.id, false);
        ++tally_.invalid;
        if (!best || runs.size() < best->runs.size()) best = Repairable{i, std::move(runs)};
      } catch (const NoStepCountError&) {
        // Its ends join, but a shortcut across it has no step count.
        passOver(c.id);
      }
    }
  };
  tryFrom(0);
  // Every one of the k nearest blocked at its ends. An arm pair's key
  // holds only the joints nearest the bases (kArmKeyJoints), so the
  // nearest keys need not be the nearest states: the next ones, ordered
  // by joined length like the first, often hold one that connects. (At
  // 16 arms, 60 scenarios: hits 104 of 121 subproblems against 92. Mobile
  // keys hold whole positions: there the next candidates are blocked
  // too, and reading them made E-ARC slower.)
  if (!found && allArms(robots) && settings_.widen_k > settings_.k && tally_.candidates >= settings_.k &&
      static_cast<std::size_t>(tally_.ends_blocked + tally_.unusable) == tally_.candidates) {
    const std::size_t tried = candidates.size();
    std::vector<std::int64_t> more_unusable;
    auto seen = [&](std::int64_t id) {
      return std::any_of(candidates.begin(), candidates.end(), [&](const exp::Candidate& u) { return u.id == id; }) ||
             std::find(unusable.begin(), unusable.end(), id) != unusable.end();
    };
    for (auto& c : exp::retrieveCandidates(store_, robots, sub.starts, sub.goals, settings_.widen_k, settings_.k,
                                           &more_unusable))
      if (!seen(c.id)) candidates.push_back(std::move(c));
    for (std::int64_t id : more_unusable)
      if (!seen(id)) {
        unusable.push_back(id);
        passOver(id);
      }
    tally_.candidates = candidates.size() + unusable.size();
    tryFrom(tried);
  }
  if (found) return std::move(*found);
  // A candidate refused as too long does not stop a repair of one tried
  // before it (shorter when joined): the repaired answer is bounded too.
  if (tally_.too_long && !best) return refusedTooLong("answer");
  if (tally_.crowded >= kCrowdedGiveUp) return failed(kBusy);
  if (!best) return failed(kNoneToRepair);
  if (best->runs.size() > static_cast<std::size_t>(settings_.max_invalid_segments))
    return failed("fewest invalid runs " + std::to_string(best->runs.size()) + ", too many to repair");

  // Repair: replan each invalid run between the valid states around it in
  // the composite space, inside the subproblem's region.
  const auto& c = candidates[best->index];
  {
    // A repair keeps the candidate's steps before its first invalid run:
    // when, joined to this start, they already run into the robots
    // outside, so would nearly every repaired answer. (At 32 mobile
    // robots with obstacles a third of the failed queries repaired an
    // answer only to find it crowded, 0.25 s in 20 plans; with this check
    // the same plans used 75 repaired answers, against 76.) Joined to the
    // start as connect() joins the candidate as stored.
    const CompositeState first = stateAt(c.paths, 0);
    std::vector<Path> head = sameUpToRounding(first, sub.starts) ? timeStampComposite(robots, {sub.starts}).paths
                                                                 : timeStampComposite(robots, {sub.starts, first}).paths;
    for (std::size_t r = 0; r < robots.size(); ++r)
      for (std::size_t t = 1; t <= best->runs.front().first; ++t) head[r].push(c.paths[r].at(t));
    if (!clearOfOthers(head)) {
      recordUse(c.id, false);
      ++crowded_;
      return failed("crowded before repair");
    }
  }
  RunRepair fix = repairRuns(ctx.world, robots, c.paths, best->runs, sub.region, settings_.repair_time_s,
                             ctx.deadline, ctx.seed);
  if (!fix.paths) {
    if (!fix.out_of_time) recordUse(c.id, false);
    return failed(fix.why);
  }
  const std::vector<Path>& repaired = *fix.paths;
  std::optional<LocalSolution> sol;
  try {
    sol = joinClear(repaired);
  } catch (const NoStepCountError&) {
    passOver(c.id);
    return failed("repaired but unusable");
  }
  if (!sol) {
    recordUse(c.id, false);
    ++crowded_;
    return failed("repaired but crowded");
  }
  if (tooLong(*sol)) {
    recordUse(c.id, false);
    return refusedTooLong("repaired answer");
  }
  ++repairs_;
  recordUse(c.id, true);
  return {std::move(*sol), "repair", c.id};
}

void DatabaseSolver::recordUse(std::int64_t id, bool success) {
  // Usage counters change the file: not when asked to leave it as it is.
  if (settings_.learn) store_.recordUse(id, success);
}

LocalSolution DatabaseSolver::connect(const CompositeChecker& checker, const SolverContext& ctx,
                                      const std::vector<const RobotModel*>& robots,
                                      const std::vector<Path>& middle, bool shortcut) const {
  const Subproblem& sub = ctx.sub;
  const std::size_t last = middle.front().size() - 1;
  std::vector<CompositeState> waypoints;
  for (std::size_t t = 0; t <= last; ++t) waypoints.push_back(stateAt(middle, t));
  const bool joined_start = !sameUpToRounding(waypoints.front(), sub.starts);
  const bool joined_goal = !sameUpToRounding(waypoints.back(), sub.goals);
  if (joined_start)
    waypoints.insert(waypoints.begin(), sub.starts);
  else
    waypoints.front() = sub.starts;
  if (joined_goal)
    waypoints.push_back(sub.goals);
  else
    waypoints.back() = sub.goals;
  // A stored solution answered a nearby query, not this one: joined to
  // this start and goal it can double back, and every extra step shifts
  // the rest of the robots' paths in time and breeds new conflicts. Every
  // shortcut is a checked straight composite motion, so the result stays
  // as valid as the candidate was.
  std::mt19937_64 rng(splitSeed(ctx.seed, 0xdb));
  const bool arms = allArms(robots);
  if (shortcut && arms) {
    shortcutEnds(checker, waypoints);
    shortcutComposite(checker, waypoints, kArmShortcuts, rng, ctx.deadline);
  } else if (shortcut) {
    shortcutComposite(checker, waypoints, kConnectShortcuts, rng, ctx.deadline);
  }
  LocalSolution out;
  if (shortcut) {
    out = timeStampComposite(robots, waypoints);
  } else {
    // The candidate's own steps as stored, joined at its ends. Time-stamped
    // as waypoints, its states would lose the steps on which every robot
    // waits (stepsBetween two equal states is 0): a decoupled answer's
    // robots may wait together for the robots outside to pass.
    const auto first = static_cast<std::ptrdiff_t>(joined_start);  // the candidate's first state in waypoints
    out = timeStampComposite(robots, {waypoints.begin(), waypoints.begin() + first + 1});
    for (std::size_t t = 1; t <= last; ++t)
      for (std::size_t r = 0; r < robots.size(); ++r)
        out.paths[r].push(waypoints[static_cast<std::size_t>(first) + t][r].data());
    if (joined_goal) {
      const LocalSolution tail = timeStampComposite(robots, {waypoints[waypoints.size() - 2], waypoints.back()});
      for (std::size_t t = 1; t < tail.length(); ++t)
        for (std::size_t r = 0; r < robots.size(); ++r) out.paths[r].push(tail.paths[r].at(t));
    }
  }
  // An answer for two arms comes out long: the stored pair's ends are far
  // from this start and goal in ten joint dimensions, and the composite
  // shortcut moves both arms together, so one arm's detour holds up the
  // other (median 68 steps for a window of 18 at 16 arms). Retiming each
  // arm on its own, 100 attempts, made them 22% shorter (53 steps). A
  // mobile robot's answer is closer to its window (40 steps for 23 at 32
  // robots with obstacles); there retiming cost about 10% of E-ARC's
  // planning time and saved about 1% of the steps.
  if (shortcut && arms) retimeShortcut(checker, out.paths, settings_.retime_iterations, rng, ctx.deadline);
  // Hold at the goals through the window, as the other solvers do (the
  // retimed paths end at different steps).
  std::size_t len = sub.t_end - sub.t_start + 1;
  for (const auto& p : out.paths) len = std::max(len, p.size());
  for (auto& p : out.paths)
    while (p.size() < len) p.push(p.back());
  return out;
}

void DatabaseSolver::accepted(const SolverContext& ctx, const LocalSolution& sol, const SolverOutcome& by) {
  if (!settings_.learn || by.how == "database" || by.how == "repair") return;
  Pending p;
  for (int r : ctx.sub.robots) p.robots.push_back(ctx.models[static_cast<std::size_t>(r)]);
  // A stored path holds at most kMaxBlobDim coordinates a state: an arm of
  // more joints is planned, not learned (inserting it ended the plan).
  std::vector<exp::RobotTraits> traits;
  for (const RobotModel* m : p.robots) traits.push_back(exp::traitsOf(*m));
  const bool storable =
      p.robots.size() >= 2 && p.robots.size() <= kMaxRobots &&
      std::none_of(p.robots.begin(), p.robots.end(), [](const RobotModel* m) { return m->dim() > exp::kMaxBlobDim; }) &&
      exp::hasExperienceClass(traits);
  if (!storable) {
    ++unstorable_;
    return;
  }
  // Trailing steps where every robot waits at its goal say nothing about
  // how the conflict was resolved: store the solution without them.
  std::size_t len = sol.length();
  auto still = [&](std::size_t t) {
    for (const auto& path : sol.paths)
      if (!std::equal(path.at(t), path.at(t) + path.dim(), path.at(t - 1))) return false;
    return true;
  };
  while (len > 2 && still(len - 1)) --len;
  for (const auto& path : sol.paths) p.paths.push_back(path.slice(0, len));
  p.seconds = by.seconds;
  pending_.push_back(std::move(p));
}

void DatabaseSolver::finish(PlanStats& stats) {
  Stopwatch sw;
  DatabaseStats& db = stats.db.emplace();
  // The ids of the rows inserted (each committed when learn returns), so
  // that a caller such as `earc-plan serve` can report what it stored.
  // The plan is made: a disk with no room for what it learned costs the
  // lesson, not the plan. Each row commits on its own, so those before the
  // failure stay, and SQLite rolled the failed one back. Anything else (a
  // damaged file, a lock held through every retry) is still an error.
  try {
    for (const auto& p : pending_)
      if (auto id = exp::learn(store_, p.robots, p.paths, p.seconds, exp::Source::Planner)) {
        ++db.db_learned;
        db.db_learned_ids.push_back(*id);
      }
    store_.flush();
  } catch (const exp::WriteLostError& e) {
    stats.db_learn_error = oneLine(e.what());
  }
  db.db_queries = queries_;
  stats.db_hits = hits_;
  db.db_repairs = repairs_;
  db.db_refused_crowded = crowded_;
  db.db_refused_too_long = too_long_;
  db.db_skipped_unusable = unusable_;
  db.db_learn_candidates = static_cast<std::int64_t>(pending_.size());
  db.db_learn_unstorable = unstorable_;
  db.db_learn_time_s = sw.seconds();
  // Rows of the store's cache while this plan ran (a service's concurrent
  // plans share one store and count each other's).
  const exp::ExperienceStore::RetrievalStats now = store_.retrievalStats();
  db.db_retrieval_time_s = retrieval_s_;
  db.db_row_cache_hits = static_cast<std::int64_t>(now.cache_hits - retrieval_at_start_.cache_hits);
  db.db_row_cache_misses = static_cast<std::int64_t>(now.cache_misses - retrieval_at_start_.cache_misses);
  if (settings_.shadow_decoupled) {
    const Shadow& s = shadow_;
    db.db_shadow_decoupled = nlohmann::json{{"queries", s.queries},
                                            {"database_solved", s.database},
                                            {"decoupled_solved", s.decoupled},
                                            {"both_solved", s.both},
                                            {"decoupled_seconds_where_both", s.decoupled_s_both},
                                            {"database_extra_steps_where_both", s.extra_steps_both},
                                            {"database_failed_where_decoupled_failed", s.database_failed_where_decoupled_failed}};
  }
  pending_.clear();
}

PlanResult planEarc(const Scenario& scenario, const PlannerSettings& settings, exp::ExperienceStore* store,
                    const PlanContext& context) {
  // The caller's mistake, not the input's: the programs refuse a missing
  // database file before planning, naming their own option.
  if (store == nullptr) throw std::invalid_argument("method earc needs an experience store (none was given)");
  DatabaseSolverSettings ds;
  ds.k = static_cast<std::size_t>(settings.db.k);
  ds.max_invalid_segments = settings.db.max_invalid_segments;
  ds.max_stretch = settings.db.max_stretch;
  ds.learn = settings.db.learn;
  ds.shadow_decoupled = settings.db.shadow_decoupled;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
  hierarchy.push_back(std::make_unique<DatabaseSolver>(*store, ds));
  for (auto& s : arcHierarchy()) hierarchy.push_back(std::move(s));
  PlanResult r = runArc(scenario, settings, context, std::move(hierarchy));
  // The hit rate: subproblems solved from the database (as retrieved or
  // repaired) over all subproblems solved.
  if (r.stats.db) r.stats.db->db_hit_rate = databaseAnswers(r.stats).hitRate();
  return r;
}

DatabaseAnswers databaseAnswers(const PlanStats& stats) {
  DatabaseAnswers a;
  if (!stats.arc) return a;
  for (const auto& [name, n] : stats.arc->subproblems_by_solver) {
    a.solved += n;
    if (name == "database") a.retrieved = n;
    if (name == "repair") a.repaired = n;
  }
  return a;
}

}  // namespace earc
