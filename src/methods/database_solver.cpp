// E-ARC's database solver (the paper's Algorithm 2): what it learns, its
// statistics, and planEarc. Its queries are in database_query.cpp.
#include "earc/methods/database_solver.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string_view>

#include "earc/experience/keys.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/retrieval.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/methods.hpp"
#include "earc/util/format.hpp"

namespace earc {

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
  if (!db.solution && !dec.solution) ++s.database_failed_where_decoupled_failed[tally_.general()];
}

void DatabaseSolver::recordUse(std::int64_t id, bool success) {
  // Usage counters change the file: not when asked to leave it as it is.
  if (settings_.learn) store_.recordUse(id, success);
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
  db.db_warm_copy_hits = static_cast<std::int64_t>(now.warm_hits - retrieval_at_start_.warm_hits);
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
  for (auto& s : arcHierarchy(settings.arc)) hierarchy.push_back(std::move(s));
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
