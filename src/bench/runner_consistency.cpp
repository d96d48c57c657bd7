// A run held to its options and to the results file it adds to: the same
// planner arguments, Lightning settings, --learn, E-ARC database and files.

#include "runner_impl.hpp"

namespace earc::bench {

namespace runner {

// Every option checked before anything is created, run or recorded: a
// configuration error is not a trial failure. Returns the entries of the
// E-ARC databases that exist, which it had to open to check.
ExistingEarcDbs validateOptions(const RunOptions& o, const std::vector<ScenarioFile>& files) {
  // Single numbers were checked as the options were parsed (earc::cli's
  // validators); what is left depends on more than one option or on the
  // machine.
  if (o.memory_limit_mb > (std::numeric_limits<std::size_t>::max() >> 20))
    throw InputError("", "--memory-limit-mb", "too large");
  for (const std::string& m : o.methods)
    if (std::find(allMethods().begin(), allMethods().end(), m) == allMethods().end())
      throw InputError("", "--methods", "unknown method '" + m + "' (" + allMethodsText() + ")");
  std::vector<const Suite*> suites;
  if (!files.empty() && o.cutoff)
    throw InputError("", "--cutoff", "is for suites (robot counts that grow), not scenario files");
  // A database that was given is not the run's to build: one that is there
  // is used as it is, one that is missing is built with earc-db's default
  // count. A count beside it would be ignored for it, silently.
  if (o.earc_db_count && (!o.db_mobile.empty() || !o.db_arms.empty()))
    throw InputError("", "--earc-db-count",
                     "is for the E-ARC databases the run builds itself, and " +
                         std::string(o.db_mobile.empty() ? "--db-arms" : "--db-mobile") +
                         " names one instead (used as it is; built with earc-db's default count when missing): "
                         "give one or the other");
  std::string counts;  // "mobile: 2, 4, 8, 16, 32; arms: 2, 4, 8, 16"
  for (const std::string& name : files.empty() ? o.suites : std::vector<std::string>{}) {
    const Suite& s = suiteByName(name);
    suites.push_back(&s);
    counts += (counts.empty() ? "" : "; ") + suiteCountsText(s);
  }
  // A count no suite runs would make "nothing to run: all 0 trials are in ...".
  for (int n : files.empty() ? o.robots : std::vector<int>{})
    if (std::none_of(suites.begin(), suites.end(), [n](const Suite* s) { return suiteTakes(*s, n); }))
      throw InputError("", "--robots", "no suite of this run has " + std::to_string(n) + " robots (" + counts + ")");
  for (const auto& [method, args] : o.method_args) {
    if (std::find(allMethods().begin(), allMethods().end(), method) == allMethods().end())
      throw InputError("", "--method-arg", "unknown method '" + method + "' (" + allMethodsText() + ")");
    if (std::find(o.methods.begin(), o.methods.end(), method) == o.methods.end())
      throw InputError("", "--method-arg", "method " + method + " is not one of this run's methods (--methods)");
    requirePlannerArgs(args, "--method-arg " + method);
  }
  // E-ARC's database options where they would be ignored: no earc trials,
  // or no robots of that kind.
  const bool runs_earc = std::find(o.methods.begin(), o.methods.end(), "earc") != o.methods.end();
  const std::set<std::string> families = runFamilies(o, files);
  for (const auto& [option, given, family] :
       {std::tuple{"--earc-db-count", o.earc_db_count.has_value(), ""}, std::tuple{"--db-mobile", !o.db_mobile.empty(), "mobile"},
        std::tuple{"--db-arms", !o.db_arms.empty(), "arms"}}) {
    if (!given) continue;
    if (!runs_earc)
      throw InputError("", option, "is for method earc, which this run does not plan with (--methods)");
    if (*family && !families.count(family))
      throw InputError("", option,
                       std::string("this run plans for no ") + (family == std::string("arms") ? "arms" : "mobile robots") +
                           " (its suites or scenario files), so it would not be used");
  }
  if (!o.plan_program.empty()) requireExecutable(o.plan_program, "--plan-program");
  else requireExecutable(executableDir() + "/earc-plan", "--plan-program (default: earc-plan beside earc-bench)");
  ExistingEarcDbs existing;
  if (runs_earc)
    for (const std::string& family : families)
      if (const std::string db = earcDbPath(o, files, family); exp::isPostgresLocation(db) || fs::exists(db))
        existing[family] = earcDbFacts(o, files, family);  // a store on a server is there: used as it is
  return existing;
}


const std::vector<std::string>& Runner::argsOf(const std::string& method) const {
  static const std::vector<std::string> none;
  const auto it = o_.method_args.find(method);
  return it == o_.method_args.end() ? none : it->second;
}

std::string Runner::withArgs(const std::vector<std::string>& args) {
  return args.empty() ? " with no planner arguments" : " with " + plannerArgsText(args);
}

// A results file holds one experiment per method: table, export and
// plot group trials by method, so trials of one method run with other
// planner arguments would be pooled into one cell, and a resumed run
// would skip trials that ran with the old ones. Refused before
// anything runs; to measure one setting against another, a results
// file each, or earc-bench compare.
void Runner::requireSamePlannerArgs() const {
  for (const std::string& m : o_.methods) {
    const auto recorded = db_.plannerArgs(m);
    if (!recorded || *recorded == argsOf(m)) continue;
    throw InputError(o_.results, "--method-arg",
                     "its " + m + " trials ran" + withArgs(*recorded) + "; this run gives " + m + " " +
                         (argsOf(m).empty() ? "none" : plannerArgsText(argsOf(m))) +
                         ": a results file holds one set of planner arguments per method (give another "
                         "--results, or measure one against the other with earc-bench compare)");
  }
}

LightningSettings Runner::lightningSettings() const {
  LightningSettings l;
  l.problems = o_.lightning_problems;
  if (!l.problems) l.problems_per_robot = o_.lightning_problems_per_robot;
  l.problem_time_limit_s = o_.lightning_problem_time_limit_s;
  return l;
}

// The same for Lightning's databases: its trials grown from other
// problems, or under another limit per problem, are another experiment,
// and a resumed run would put them in the cells of the first. Files
// from before schema 7 (or without a lightning trial) have no settings
// to hold the run to.
void Runner::requireSameLightningSettings() const {
  if (!runs("lightning")) return;
  const auto recorded = db_.lightningSettings();
  if (!recorded) return;
  if (const auto d = lightningSettingDifference(*recorded, lightningSettings()))
    throw InputError(o_.results, d->option,
                     "its lightning trials ran with " + d->stored + "; this run gives " + d->given +
                         ": a results file holds one Lightning database setting (give the same, or another "
                         "--results)");
}

bool Runner::runs(const std::string& method) const {
  return std::find(o_.methods.begin(), o_.methods.end(), method) != o_.methods.end();
}

void Runner::requireSameLearn() const {
  for (const std::string& m : o_.methods) {
    const auto recorded = usesDatabase(m) ? db_.learn(m) : std::nullopt;
    if (!recorded || *recorded == o_.learn) continue;
    throw InputError(o_.results, "--learn",
                     "its " + m + " trials ran with " + learnText(*recorded) + "; this run gives " +
                         learnText(o_.learn) +
                         ": a results file holds one --learn setting per method (give the same, or another "
                         "--results)");
  }
}

std::optional<std::string> Runner::familyOf(const TrialRecord& t) const {
  if (t.suite != kFilesSuite) return suiteByName(t.suite).family;
  for (const ScenarioFile& f : files_)
    if (f.path == t.scenario_file) return f.family;
  return std::nullopt;
}

// The earc trials of one family of robots and one --seed plan with one
// E-ARC database, as they found it: a resumed run on another would put
// trials of two databases in one cell. (Another seed's is another: the
// run builds one per seed, as it draws other scenarios per seed.) "The
// same" is the same file wherever it lies now (moved or copied, given
// by another path) and changed since only by the trials' own learning
// (--learn): the token of the last line of its history, which each earc
// trial records, is still in its history, and no line after it added
// or removed rows but those. Another database, built again in its place
// (even by the same command: what it holds depends on the earc build
// too), curated or added to since, or one this run would build because
// it is gone (or because the trials ran on one named as before
// earcDbPath's names), is refused before anything runs. Files from
// before schema 8, and databases without a history (experience schema
// before 5), have none to tell by.
void Runner::requireSameEarcDb() const {
  if (!runs("earc")) return;
  const std::set<std::string> ours = families();
  std::set<std::pair<std::string, std::int64_t>> checked;
  for (const TrialRecord& t : db_.recordedTrials()) {
    if (t.method != "earc" || !t.earc_db_state || t.seed != o_.seed) continue;
    const auto family = familyOf(t);
    if (!family || !ours.count(*family) || !checked.insert({*family, *t.earc_db_state}).second) continue;
    const std::string path = earcDb(*family);
    const auto refuse = [&](const std::string& now) {
      return InputError(o_.results, "--db-" + *family,
                        "its earc trials of " + (*family == "arms" ? std::string("arms") : *family + " robots") +
                            " with --seed " + std::to_string(o_.seed) + " ran on the E-ARC database " + t.earc_db +
                            "; " + now +
                            ": a results file holds the earc trials of one E-ARC database per kind of robot and "
                            "seed, as they found it (give that one, or another --results)");
    };
    const auto facts = existing_.find(*family);
    if (facts == existing_.end()) throw refuse("this run would build a new one at " + path);
    const std::vector<exp::HistoryLine>& lines = facts->second.history;
    if (lines.empty()) continue;
    const auto then = std::find_if(lines.begin(), lines.end(),
                                   [&](const exp::HistoryLine& l) { return l.token == *t.earc_db_state; });
    if (then == lines.end()) throw refuse(path + " is another");
    std::vector<std::string> changes;
    for (auto l = then + 1; l != lines.end(); ++l)
      if ((l->rows_added || l->rows_removed) && !(o_.learn && l->operation == "learn") &&
          std::find(changes.begin(), changes.end(), l->operation) == changes.end())
        changes.push_back(l->operation);
    if (changes.empty()) continue;
    std::string what;
    for (const std::string& c : changes) what += (what.empty() ? "" : ", ") + c;
    throw refuse(path + " has changed since (" + what + ")");
  }
}

// The E-ARC databases runs built into this file (databases rows with a
// construction time, which have recorded the count since schema 1) were
// built from one --earc-db-count: a run that builds its own from another
// (by its name, another database; for another --seed too) would put
// trials of databases built from two counts in one cell, as other
// Lightning settings would. A database given (--db-mobile) is used as it
// is, and no count goes with it.
void Runner::requireSameEarcDbCount() const {
  if (!runs("earc")) return;
  const std::vector<DatabaseRecord> recorded = db_.databases();
  const auto count = [](std::optional<std::int64_t> n) {
    return n ? std::to_string(*n) + " problems" : std::string("earc-db's default count");
  };
  const std::optional<std::int64_t> given = o_.earc_db_count;
  for (const std::string& family : families()) {
    if (!(family == "arms" ? o_.db_arms : o_.db_mobile).empty()) continue;
    // Scenario files' rows are of suite files, whichever their kind: a
    // cell pools the files of one robot count, mobile or arms.
    const std::string suite = files_.empty() ? family : std::string(kFilesSuite);
    for (const DatabaseRecord& d : recorded) {
      if (d.method != "earc" || d.suite != suite || !d.construction_time_s || d.problems == given) continue;
      throw InputError(o_.results, "--earc-db-count",
                       "its E-ARC database " + d.path + " was built from " + count(d.problems) +
                           "; this run gives " + count(given) +
                           ": a results file holds the earc trials of E-ARC databases built from one count (give "
                           "the same, or another --results)");
    }
  }
}

// A scenario file's trials are numbered by the order the files were
// given in: a resumed run given other files, or the same in another
// order, would skip trials recorded for other scenarios. The hash of
// each file's scenario is recorded as its trials' scenario seed.
void Runner::requireSameFiles() const {
  if (files_.empty()) return;
  const TrialFilter f{o_.seed, o_.time_limit_s};
  for (const TrialRecord& t : f.apply(db_.recordedTrials())) {
    if (t.suite != kFilesSuite) continue;
    for (const ScenarioFile& file : files_)
      if (file.robots() == t.robots && file.trial == t.trial && file.hash != t.scenario_seed)
        throw InputError(o_.results, "",
                         "its trial " + std::string(kFilesSuite) + "-" + std::to_string(t.robots) + "-t" +
                             std::to_string(t.trial) + " (" + t.method + ") was planned on another scenario than " +
                             file.path + ", the " + ordinal(file.trial + 1) + " file of " +
                             std::to_string(t.robots) +
                             " robots given: give the files as before, or another --results");
  }
}

}  // namespace runner

}  // namespace earc::bench
