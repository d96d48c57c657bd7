// One query of E-ARC's database solver (the paper's Algorithm 2): retrieve
// the nearest stored answers, try them in order, widen the search for
// arms, repair the best invalid one; and joining an answer to the
// subproblem's start and goal.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string_view>

#include "earc/experience/retrieval.hpp"
#include "earc/methods/database_solver.hpp"
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
// For arms, after the ends are shortcut (shortcutEnds): fewer attempts
// gave plans as short in less time (docs/performance-log.md). Mobile
// robots keep kConnectShortcuts.
constexpr int kArmShortcuts = 30;

// Why a query failed when no candidate was both valid and clear.
constexpr std::string_view kNoneToRepair = "none to repair";

// Valid candidates that ran into robots outside the subproblem before the
// query gives up: the region is busy with other robots at this time, and
// more candidates, or a repaired one, nearly always run into them too.
// The decoupled solver, which plans around those robots, takes over.
constexpr int kCrowdedGiveUp = 3;
constexpr std::string_view kBusy = "region busy with other robots";

// A candidate's joined length when no step count joins it: sorted last,
// never tried.
constexpr std::size_t kUnjoinable = std::numeric_limits<std::size_t>::max();

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

// The state of one query: the subproblem's robots, the candidates
// retrieved, what became of them, and the best one to repair. The counts
// go to the solver's tally_ and counters as they happen.
struct DatabaseSolver::QueryState {
  struct Repairable {
    std::size_t index;
    std::vector<StepRun> runs;
  };

  QueryState(DatabaseSolver& solver, SolverContext& context, std::vector<const RobotModel*> subproblem_robots)
      : db(solver), ctx(context), sub(context.sub), robots(std::move(subproblem_robots)), checker(ctx.world, robots) {}

  bool retrieve();
  void boundLength();
  void tryFrom(std::size_t first);
  bool tryCandidate(std::size_t i);
  bool worthWidening() const;
  void widen();
  SolverOutcome repair();
  bool headClear(const exp::Candidate& c);

  void passOver(std::int64_t id);
  SolverOutcome failed(std::string_view why);
  bool tooLong(const LocalSolution& sol);
  SolverOutcome refusedTooLong(std::string_view what);
  std::size_t joinedLength(exp::Candidate& cand);
  bool clearOfOthers(const std::vector<Path>& paths);
  std::optional<LocalSolution> joinClear(const std::vector<Path>& middle);

  DatabaseSolver& db;
  SolverContext& ctx;
  const Subproblem& sub;
  const std::vector<const RobotModel*> robots;
  const CompositeChecker checker;
  std::vector<exp::Candidate> candidates;
  std::vector<std::int64_t> unusable;  // ids of rows passed over when retrieved
  std::vector<std::size_t> joined;     // candidates' joined lengths, as measured
  std::size_t longest = std::numeric_limits<std::size_t>::max();  // steps an answer may take
  int straight = 1;  // the slowest robot's steps straight from start to goal (with max_stretch)
  // The robots outside the subproblem, collected when first needed.
  std::optional<std::vector<MovingObstacle>> others;
  std::optional<Repairable> best;
  std::optional<SolverOutcome> found;
};

SolverOutcome DatabaseSolver::query(SolverContext& ctx) {
  std::vector<const RobotModel*> robots;
  for (int r : ctx.sub.robots) robots.push_back(ctx.models[static_cast<std::size_t>(r)]);
  tally_ = {};
  if (robots.size() < 2 || robots.size() > kMaxRobots) return {std::nullopt, name(), -1};
  QueryState q(*this, ctx, std::move(robots));
  if (!q.retrieve()) {
    tally_.why = "no entries of this class";
    return {std::nullopt, name(), -1, 0.0, tally_.why};
  }
  q.boundLength();
  q.tryFrom(0);
  if (!q.found && q.worthWidening()) q.widen();
  if (q.found) return std::move(*q.found);
  // A candidate refused as too long does not stop a repair of one tried
  // before it (shorter when joined): the repaired answer is bounded too.
  if (tally_.too_long && !q.best) return q.refusedTooLong("answer");
  if (tally_.crowded >= kCrowdedGiveUp) return q.failed(kBusy);
  if (!q.best) return q.failed(kNoneToRepair);
  if (q.best->runs.size() > static_cast<std::size_t>(settings_.max_invalid_segments))
    return q.failed("fewest invalid runs " + std::to_string(q.best->runs.size()) + ", too many to repair");
  return q.repair();
}

std::string DatabaseSolver::Tally::general() const {
  if (why.empty()) return "no class of this size";
  if (why == kNoneToRepair)
    return static_cast<std::size_t>(ends_blocked) == candidates ? "every candidate blocked at its ends"
                                                                : "every candidate blocked or crowded";
  return withoutNumbers(why);
}

// The k nearest; false when the store holds none of this class.
bool DatabaseSolver::QueryState::retrieve() {
  Stopwatch retrieval;
  candidates = exp::retrieveCandidates(db.store_, robots, sub.starts, sub.goals, db.settings_.k, 0, &unusable);
  db.retrieval_s_ += retrieval.seconds();
  ++db.queries_;
  for (std::int64_t id : unusable) passOver(id);
  if (candidates.empty() && unusable.empty()) return false;
  // What became of the candidates, for the trace.
  db.tally_.candidates = candidates.size() + unusable.size();
  return true;
}

// An answer may come out far longer than the subproblem needs, longer
// than the decoupled solver's answer to the same subproblem would be:
// at most max_stretch times the slowest robot's straight motion.
void DatabaseSolver::QueryState::boundLength() {
  if (db.settings_.max_stretch <= 0) return;
  for (std::size_t r = 0; r < robots.size(); ++r)
    straight = std::max(straight, robots[r]->stepsBetween(sub.starts[r].data(), sub.goals[r].data()));
  const double bound = db.settings_.max_stretch * straight;
  if (bound < 1e15) longest = static_cast<std::size_t>(bound);
}

// A stored candidate that no step count joins or follows at these robots'
// resolution (NoStepCountError: a damaged or made-up row, or one far
// outside this workspace at a fine resolution) is passed over like an
// invalid one, and the query goes on with the others: one bad row must
// not fail every plan that retrieves it.
void DatabaseSolver::QueryState::passOver(std::int64_t id) {
  db.recordUse(id, false);
  ++db.tally_.unusable;
  ++db.unusable_;
}

SolverOutcome DatabaseSolver::QueryState::failed(std::string_view why) {
  Tally& t = db.tally_;
  t.why = why;
  return SolverOutcome{std::nullopt, db.name(), -1, 0.0,
                       std::to_string(t.candidates) + " candidates: " + std::to_string(t.ends_blocked) +
                           " ends blocked, " + std::to_string(t.invalid) + " invalid, " + std::to_string(t.crowded) +
                           " crowded" + (t.unusable ? ", " + std::to_string(t.unusable) + " unusable" : "") + "; " +
                           t.why};
}

bool DatabaseSolver::QueryState::tooLong(const LocalSolution& sol) {
  const std::size_t steps = sol.length() - 1;  // it holds a state per instant
  if (steps <= longest) return false;
  db.tally_.too_long = steps;
  ++db.too_long_;
  return true;
}

SolverOutcome DatabaseSolver::QueryState::refusedTooLong(std::string_view what) {
  return failed(std::string(what) + " " + std::to_string(db.tally_.too_long) + " steps, more than " +
                formatNumber("%g", db.settings_.max_stretch) + " x " + std::to_string(straight));
}

// The candidate's own steps plus the joins to this start and goal, its
// headings aligned first; kUnjoinable (and passed over) when no step
// count joins it.
std::size_t DatabaseSolver::QueryState::joinedLength(exp::Candidate& cand) {
  alignHeadings(robots, sub, cand.paths);
  const auto& p = cand.paths;
  int in = 0, out = 0;
  try {
    for (std::size_t r = 0; r < robots.size(); ++r) {
      in = std::max(in, robots[r]->stepsBetween(sub.starts[r].data(), p[r].at(0)));
      out = std::max(out, robots[r]->stepsBetween(p[r].at(p[r].size() - 1), sub.goals[r].data()));
    }
  } catch (const NoStepCountError&) {
    passOver(cand.id);
    return kUnjoinable;
  }
  return p.front().size() + static_cast<std::size_t>(in) + static_cast<std::size_t>(out);
}

// Time-stamped paths of the subproblem's robots from its start, clear of
// the robots outside. Those are the robots as the decoupled solver sees
// them: a stored solution knows nothing of them, and one that runs into
// them only trades this conflict for the next. Collected when the first
// candidate gets that far: most queries end before.
bool DatabaseSolver::QueryState::clearOfOthers(const std::vector<Path>& paths) {
  const std::size_t window = sub.t_end - sub.t_start;
  if (!others) others = nearbyRobots(ctx, 4 * window + 100);
  for (std::size_t r = 0; r < robots.size(); ++r)
    if (!clearOfMoving(*robots[r], paths[r], *others)) return false;
  return true;
}

// Shortcutting changes when the robots are where, which the other robots
// may not allow: then the candidate as stored is tried.
std::optional<LocalSolution> DatabaseSolver::QueryState::joinClear(const std::vector<Path>& middle) {
  for (bool shortcut : {true, false}) {
    LocalSolution sol = db.connect(checker, ctx, robots, middle, shortcut);
    if (clearOfOthers(sol.paths)) return sol;
  }
  return std::nullopt;
}

// Tries candidates[first..] in order of how long they would make the
// local solution, so the first valid one is also the shortest: a longer
// local solution delays every later step of these robots and makes new
// conflicts.
void DatabaseSolver::QueryState::tryFrom(std::size_t first) {
  for (std::size_t i = joined.size(); i < candidates.size(); ++i) joined.push_back(joinedLength(candidates[i]));
  std::vector<std::size_t> order;
  for (std::size_t i = first; i < candidates.size(); ++i) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return joined[a] < joined[b]; });
  for (std::size_t i : order) {
    if (found || ctx.deadline.expired()) break;
    if (joined[i] == kUnjoinable) continue;  // passed over when measured
    if (tryCandidate(i)) break;
  }
}

// Candidate i: found when valid, clear and short enough, else remembered
// for repair when invalid and the best so far. True when the query should
// try no more.
bool DatabaseSolver::QueryState::tryCandidate(std::size_t i) {
  const auto& c = candidates[i];
  Tally& t = db.tally_;
  try {
    // A candidate is only usable when the subproblem's start and goal
    // connect to its ends without collision.
    if (!checker.motionValid(sub.starts, stateAt(c.paths, 0)) ||
        !checker.motionValid(stateAt(c.paths, c.paths.front().size() - 1), sub.goals)) {
      db.recordUse(c.id, false);
      ++t.ends_blocked;
      return false;
    }
    auto runs = invalidRuns(checker, c.paths);
    if (runs.empty()) {
      auto sol = joinClear(c.paths);
      if (!sol) {
        db.recordUse(c.id, false);
        ++db.crowded_;
        return ++t.crowded >= kCrowdedGiveUp;
      }
      if (tooLong(*sol)) {
        db.recordUse(c.id, false);
        return true;
      }
      found = SolverOutcome{std::move(*sol), "database", c.id};
      db.recordUse(c.id, true);
      ++db.hits_;
      return true;
    }
    db.recordUse(c.id, false);
    ++t.invalid;
    if (!best || runs.size() < best->runs.size()) best = Repairable{i, std::move(runs)};
  } catch (const NoStepCountError&) {
    // Its ends join, but a shortcut across it has no step count.
    passOver(c.id);
  }
  return false;
}

// Every one of the k nearest blocked at its ends (or unusable), for arms.
// An arm pair's key holds only the joints nearest the bases
// (kArmKeyJoints), so the nearest keys need not be the nearest states:
// the next ones, ordered by joined length like the first, often hold one
// that connects. Mobile keys hold whole positions: there the next
// candidates are blocked too, and reading them only costs time.
bool DatabaseSolver::QueryState::worthWidening() const {
  const Tally& t = db.tally_;
  return allArms(robots) && db.settings_.widen_k > db.settings_.k && t.candidates >= db.settings_.k &&
         static_cast<std::size_t>(t.ends_blocked + t.unusable) == t.candidates;
}

// Retrieves up to widen_k, skipping the k nearest, and tries those not
// seen yet.
void DatabaseSolver::QueryState::widen() {
  const std::size_t tried = candidates.size();
  std::vector<std::int64_t> more_unusable;
  auto seen = [&](std::int64_t id) {
    return std::any_of(candidates.begin(), candidates.end(), [&](const exp::Candidate& u) { return u.id == id; }) ||
           std::find(unusable.begin(), unusable.end(), id) != unusable.end();
  };
  for (auto& c : exp::retrieveCandidates(db.store_, robots, sub.starts, sub.goals, db.settings_.widen_k,
                                         db.settings_.k, &more_unusable))
    if (!seen(c.id)) candidates.push_back(std::move(c));
  for (std::int64_t id : more_unusable)
    if (!seen(id)) {
      unusable.push_back(id);
      passOver(id);
    }
  db.tally_.candidates = candidates.size() + unusable.size();
  tryFrom(tried);
}

// A repair keeps the candidate's steps before its first invalid run: when,
// joined to this start, they already run into the robots outside, so
// would nearly every repaired answer, and the repair is skipped. Joined
// to the start as connect() joins the candidate as stored.
bool DatabaseSolver::QueryState::headClear(const exp::Candidate& c) {
  const CompositeState first = stateAt(c.paths, 0);
  std::vector<Path> head = sameUpToRounding(first, sub.starts) ? timeStampComposite(robots, {sub.starts}).paths
                                                               : timeStampComposite(robots, {sub.starts, first}).paths;
  for (std::size_t r = 0; r < robots.size(); ++r)
    for (std::size_t t = 1; t <= best->runs.front().first; ++t) head[r].push(c.paths[r].at(t));
  return clearOfOthers(head);
}

// Replans each of the best candidate's invalid runs between the valid
// states around it in the composite space, inside the subproblem's region.
SolverOutcome DatabaseSolver::QueryState::repair() {
  const auto& c = candidates[best->index];
  if (!headClear(c)) {
    db.recordUse(c.id, false);
    ++db.crowded_;
    return failed("crowded before repair");
  }
  RunRepair fix = repairRuns(ctx.world, robots, c.paths, best->runs, sub.region, db.settings_.repair_time_s,
                             ctx.deadline, ctx.seed);
  if (!fix.paths) {
    if (!fix.out_of_time) db.recordUse(c.id, false);
    return failed(fix.why);
  }
  std::optional<LocalSolution> sol;
  try {
    sol = joinClear(*fix.paths);
  } catch (const NoStepCountError&) {
    passOver(c.id);
    return failed("repaired but unusable");
  }
  if (!sol) {
    db.recordUse(c.id, false);
    ++db.crowded_;
    return failed("repaired but crowded");
  }
  if (tooLong(*sol)) {
    db.recordUse(c.id, false);
    return refusedTooLong("repaired answer");
  }
  ++db.repairs_;
  db.recordUse(c.id, true);
  return {std::move(*sol), "repair", c.id};
}

namespace {

// A candidate's states joined to the subproblem's start and goal: a join
// is added where an end differs from them (beyond rounding), else the end
// becomes the start or goal itself.
struct JoinedWaypoints {
  std::vector<CompositeState> states;
  bool joined_start = false;
  bool joined_goal = false;
};

JoinedWaypoints joinAtEnds(const Subproblem& sub, const std::vector<Path>& middle) {
  JoinedWaypoints w;
  const std::size_t last = middle.front().size() - 1;
  for (std::size_t t = 0; t <= last; ++t) w.states.push_back(stateAt(middle, t));
  w.joined_start = !sameUpToRounding(w.states.front(), sub.starts);
  w.joined_goal = !sameUpToRounding(w.states.back(), sub.goals);
  if (w.joined_start)
    w.states.insert(w.states.begin(), sub.starts);
  else
    w.states.front() = sub.starts;
  if (w.joined_goal)
    w.states.push_back(sub.goals);
  else
    w.states.back() = sub.goals;
  return w;
}

// The candidate's own steps as stored (`steps` of them), joined at its
// ends. Time-stamped as waypoints, its states would lose the steps on
// which every robot waits (stepsBetween two equal states is 0): a
// decoupled answer's robots may wait together for the robots outside.
LocalSolution stampAsStored(const std::vector<const RobotModel*>& robots, const JoinedWaypoints& w,
                            std::size_t steps) {
  const auto& states = w.states;
  const auto first = static_cast<std::ptrdiff_t>(w.joined_start);  // the candidate's first state in states
  LocalSolution out = timeStampComposite(robots, {states.begin(), states.begin() + first + 1});
  for (std::size_t t = 1; t <= steps; ++t)
    for (std::size_t r = 0; r < robots.size(); ++r)
      out.paths[r].push(states[static_cast<std::size_t>(first) + t][r].data());
  if (w.joined_goal) {
    const LocalSolution tail = timeStampComposite(robots, {states[states.size() - 2], states.back()});
    for (std::size_t t = 1; t < tail.length(); ++t)
      for (std::size_t r = 0; r < robots.size(); ++r) out.paths[r].push(tail.paths[r].at(t));
  }
  return out;
}

// Holds every path at its goal through the subproblem's window, as the
// other solvers do, and to the longest path's end (retimed paths end at
// different steps).
void holdAtGoals(const Subproblem& sub, std::vector<Path>& paths) {
  std::size_t len = sub.t_end - sub.t_start + 1;
  for (const auto& p : paths) len = std::max(len, p.size());
  for (auto& p : paths)
    while (p.size() < len) p.push(p.back());
}

}  // namespace

LocalSolution DatabaseSolver::connect(const CompositeChecker& checker, const SolverContext& ctx,
                                      const std::vector<const RobotModel*>& robots,
                                      const std::vector<Path>& middle, bool shortcut) const {
  JoinedWaypoints w = joinAtEnds(ctx.sub, middle);
  // A stored solution answered a nearby query, not this one: joined to
  // this start and goal it can double back, and every extra step shifts
  // the rest of the robots' paths in time and breeds new conflicts. Every
  // shortcut is a checked straight composite motion, so the result stays
  // as valid as the candidate was.
  std::mt19937_64 rng(splitSeed(ctx.seed, 0xdb));
  const bool arms = allArms(robots);
  if (shortcut && arms) {
    shortcutEnds(checker, w.states);
    shortcutComposite(checker, w.states, kArmShortcuts, rng, ctx.deadline);
  } else if (shortcut) {
    shortcutComposite(checker, w.states, kConnectShortcuts, rng, ctx.deadline);
  }
  LocalSolution out =
      shortcut ? timeStampComposite(robots, w.states) : stampAsStored(robots, w, middle.front().size() - 1);
  // Two arms' answers come out long: the stored pair's ends are far from
  // this start and goal in ten joint dimensions, and the composite
  // shortcut moves both arms together, so one arm's detour holds up the
  // other. Each arm is retimed on its own; a mobile robot's answer lies
  // closer to its window, where retiming costs more than it saves.
  if (shortcut && arms) retimeShortcut(checker, out.paths, settings_.retime_iterations, rng, ctx.deadline);
  holdAtGoals(ctx.sub, out.paths);
  return out;
}

}  // namespace earc
