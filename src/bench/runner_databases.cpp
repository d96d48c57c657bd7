// The databases a run plans with: where its E-ARC and Lightning databases
// are, and building them when missing.

#include "runner_impl.hpp"

namespace earc::bench {

namespace runner {

std::int64_t fileSize(const std::string& path) {
  std::error_code ec;
  auto n = fs::file_size(path, ec);
  return ec ? -1 : static_cast<std::int64_t>(n);
}

std::string workDir(const RunOptions& o) { return o.work_dir.empty() ? o.results + ".work" : o.work_dir; }

std::string hex16(std::uint64_t v) {
  char hex[20];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(v));
  return hex;
}

std::string earcBuildKey(const ScenarioFile& f) {
  nlohmann::json robots = scenarioWorldJson(f.scenario)["robots"];
  for (auto& r : robots) r.erase("name");
  if (f.family == "arms") return robots.dump();
  std::set<std::string> shapes;
  for (const auto& r : robots) shapes.insert(r.dump());
  std::string key;
  for (const std::string& one : shapes) key += one;
  return key;
}

std::string unbuildableReason(const ScenarioFile& f) {
  std::vector<RobotSpec> arms;
  for (const RobotSpec& r : f.scenario.robots)
    if (r.kind == RobotKind::Manipulator) arms.push_back(r);
  if (arms.size() < 2 || !exp::armPairClasses(arms, f.scenario.resolution).empty()) return "";
  return exp::noArmPairClassReason(arms);
}

// The files of a family that its E-ARC database is built from, one
// `earc-db build --scenario` each: the first of each build key, in the
// order given. An arm layout with no pair the database can hold has
// nothing to build, and its E-ARC trials plan as ARC (the run warns why).
std::vector<const ScenarioFile*> earcBuildFiles(const std::vector<ScenarioFile>& files, const std::string& family) {
  std::vector<const ScenarioFile*> out;
  std::set<std::string> keys;
  for (const ScenarioFile& f : files)
    if (f.family == family && keys.insert(earcBuildKey(f)).second && unbuildableReason(f).empty())
      out.push_back(&f);
  return out;
}

// The E-ARC database of a family: the one given, or one the run builds in
// its work directory, named by what its rows come of, as a Lightning
// database is: WORK/earc-FAMILY[-pCOUNT]-sSEED[-learn].sqlite, COUNT as
// --earc-db-count gives it (none: earc-db's default), SEED the run's, and
// -learn when trials add to it; for scenario files
// WORK/earc-files-FAMILY-ROBOTS-..., ROBOTS a hash of the robot geometries
// (and arm layouts) it is built for. So a run takes a database only where
// it would have built the same one: another --seed, count or --learn, a
// run into another results file sharing the work directory, files of
// other robots, each build their own.
std::string earcDbPath(const RunOptions& o, const std::vector<ScenarioFile>& files, const std::string& family) {
  const std::string& given = family == "arms" ? o.db_arms : o.db_mobile;
  if (!given.empty()) return given;
  std::string name = (files.empty() ? "earc-" : "earc-files-") + family;
  if (!files.empty()) {
    // Of the builds' keys, not the files: in any order, and whichever
    // file of a key stands for it, the builds are the same.
    std::set<std::string> keys;
    for (const ScenarioFile* f : earcBuildFiles(files, family)) keys.insert(earcBuildKey(*f));
    std::string all;
    for (const std::string& key : keys) all += key + "\n";
    name += "-" + hex16(fnv1a64(all));
  }
  if (o.earc_db_count) name += "-p" + std::to_string(*o.earc_db_count);
  name += "-s" + std::to_string(o.seed);
  if (o.learn) name += "-learn";
  return workDir(o) + "/" + name + ".sqlite";
}


// An existing E-ARC database, opened read-only as the trials' `earc-plan
// --no-learn` opens it. One that cannot be read (a foreign file, a newer
// schema version) is bad input: every earc trial would fail on it, and be
// recorded, and be skipped when resumed.
EarcDbFacts earcDbFacts(const RunOptions& o, const std::vector<ScenarioFile>& files, const std::string& family) {
  const std::string path = earcDbPath(o, files, family);
  const bool given = !(family == "arms" ? o.db_arms : o.db_mobile).empty();
  const std::string option = given ? "--db-" + family : "";
  if (fs::is_directory(path)) throw InputError(path, option, "a directory, not an E-ARC database");
  try {
    exp::StoreOptions so;
    so.read_only = true;
    so.new_session = false;
    exp::ExperienceStore store(path, so);
    EarcDbFacts f;
    f.entries = static_cast<std::int64_t>(store.size());
    f.history = store.readHistoryLines(std::numeric_limits<int>::max()).lines;  // either engine
    return f;
  } catch (const std::exception& e) {
    throw InputError(path, option, "not a usable E-ARC database: " + reasonAbout(e, path) +
                                       (given ? "" : " (remove it to have it built again)"));
  }
}

std::optional<std::int64_t> earcDbState(const EarcDbFacts& f) {
  if (f.history.empty()) return std::nullopt;
  return f.history.back().token;
}


std::set<std::string> runFamilies(const RunOptions& o, const std::vector<ScenarioFile>& files) {
  std::set<std::string> out;
  for (const ScenarioFile& f : files) out.insert(f.family);
  for (const std::string& name : files.empty() ? o.suites : std::vector<std::string>{})
    out.insert(suiteByName(name).family);
  return out;
}

int Runner::lightningProblems(int robots) const {
  return o_.lightning_problems.value_or(o_.lightning_problems_per_robot * robots);
}

// A suite's per robot count; a scenario file's per world (files that
// differ only in starts and goals share it). The name also says how it
// grows: from how many problems, each under what limit, of which seed,
// and whether trials add to it (--learn). A database is used only by
// runs that would grow it so, never found again by a run with other
// settings or another seed (a resumed file from before schema 7,
// another --results sharing the --lightning-dir) and taken as theirs.
std::string Runner::lightningDb(const Cell& c) const {
  std::string name = c.file ? std::string(kFilesSuite) : c.suite->name;
  name += "-" + std::to_string(c.robots);
  if (c.file) name += "-" + hex16(c.file->world);
  name += "-p" + std::to_string(lightningProblems(c.robots)) + "-t" +
          exactNumber(o_.lightning_problem_time_limit_s) + "-s" + std::to_string(o_.seed);
  if (o_.learn) name += "-learn";
  return lightning_dir_ + "/" + name + ".lightning";
}

void Runner::buildFailed(const std::string& path, const ChildOutcome& out, const std::string& stem,
                        std::string_view method) {
  // Stopped by Ctrl-C (or SIGTERM): the run says it was interrupted.
  if (cli::stopFlag().load()) return;
  std::cerr << "earc-bench: building " << path << " failed (" << exitDescription(out)
            << "): " << lastLine(stem + ".err") << "; its " << method << " trials will fail\n";
}

// A Lightning database is built (in a child, timed) just before the
// first trial that needs it, so that trials --cutoff skips never pay for
// one (at 32 robots that is minutes of planning problems it cannot
// solve). One build at a time; other workers wait for theirs.
void Runner::ensureLightningDb(const Cell& c) {
  std::lock_guard lock(lightning_mutex_);
  if (cli::stopFlag().load()) return;
  const int robots = c.robots;
  const std::string path = lightningDb(c);
  if (fs::exists(path)) return;
  fs::create_directories(lightning_dir_);
  const int problems = lightningProblems(robots);
  log_ << "building Lightning database " << path << " from " << problems << " problems\n";
  log_.flush();
  std::vector<std::string> argv = {bench_, "lightning-db"};
  if (c.file) {
    argv.insert(argv.end(), {"--scenario", scenarioFile(c)});
  } else {
    argv.insert(argv.end(), {"--suite", c.suite->name, "--robots", std::to_string(robots)});
  }
  argv.insert(argv.end(), {"--count", std::to_string(problems), "--seed", std::to_string(o_.seed),
                           "--problem-time-limit", exactNumber(o_.lightning_problem_time_limit_s), "-o", path,
                           "--results", o_.results});
  const std::string stem = work_ + "/logs/lightning-db-" + fs::path(path).stem().string();
  ChildSpec spec;
  spec.argv = argv;
  spec.stdout_path = stem + ".out";
  spec.stderr_path = stem + ".err";
  spec.wall_limit_s =
      problems * (o_.lightning_problem_time_limit_s + wallMargin(o_.lightning_problem_time_limit_s)) + 60.0;
  spec.memory_limit_mb = o_.memory_limit_mb;
  ChildOutcome out = runChild(spec, &cli::stopFlag());
  if (out.exit_code != 0) {
    buildFailed(path, out, stem, "Lightning");
    return;
  }
  // What the minutes bought: entries, and how many problems it solved
  // (none, for robots too many for it: its trials then plan from scratch).
  log_ << "  " << lastLine(stem + ".out") << "\n";
  log_.flush();
}

void Runner::prepareDatabases(const std::vector<Cell>& cells) {
  std::set<std::string> families;
  for (const Cell& c : cells)
    if (c.method == "earc") families.insert(c.family());
  for (const std::string& family : families) {
    if (cli::stopFlag().load()) return;
    const std::string path = earcDb(family);
    std::optional<double> construction;
    if (!exp::isPostgresLocation(path) && !fs::exists(path)) {
      construction = buildEarcDb(family, path);
      if (!construction) continue;
    }
    warnNoClassFits(family, path);
    if (!construction && db_.hasDatabase("earc", path)) continue;
    DatabaseRecord d;
    d.method = "earc";
    d.suite = files_.empty() ? family : kFilesSuite;
    d.robots = 0;
    d.path = path;
    d.construction_time_s = construction;
    d.size_bytes = exp::isPostgresLocation(path)
                       ? 0
                       : fileSize(path) + std::max<std::int64_t>(0, fileSize(exp::databaseFile(path) + "-wal"));
    if (construction) {
      d.seed = o_.seed;
      if (o_.earc_db_count) d.problems = *o_.earc_db_count;
    }
    // One built here is new: opened now, for the first time.
    const auto checked = existing_.find(family);
    const EarcDbFacts facts =
        construction || checked == existing_.end() ? earcDbFacts(o_, files_, family) : checked->second;
    d.entries = facts.entries;
    earc_states_[family] = earcDbState(facts);
    db_.addDatabase(d);
  }
}

// A database given for scenario files (--db-mobile, --db-arms) may hold
// nothing for their robots: E-ARC then plans as ARC, which a table would
// not show. Said once per robot geometry (and arm layout), as earc-plan
// says it.
void Runner::warnNoClassFits(const std::string& family, const std::string& path) {
  if (files_.empty()) return;
  std::optional<exp::ExperienceStore> store;
  try {
    exp::StoreOptions so;
    so.read_only = true;
    so.new_session = false;
    store.emplace(path, so);
  } catch (const std::exception&) {
    return;  // the trials say what is wrong with it
  }
  std::set<std::string> said;
  for (const ScenarioFile& f : files_)
    if (f.family == family && said.insert(earcBuildKey(f)).second) {
      std::string w = unbuildableReason(f);
      if (!w.empty())
        w += ": an E-ARC database holds nothing for these arms, and E-ARC plans as ARC does";
      else
        w = exp::noClassFitsWarning(*store, f.scenario, path);
      if (!w.empty()) std::cerr << "earc-bench: warning: " << printableText(f.path + ": " + w, 4096) << "\n";
    }
}

// Runs `earc-db build` for one family; its wall time is the construction
// time (nullopt when it failed: the earc trials then fail with
// earc-plan's own message about the database).
// Scenario files: one build per robot geometry (and arm layout) among
// the family's files, into the one database; the construction time is
// their sum.
std::optional<double> Runner::buildEarcDb(const std::string& family, const std::string& path) {
  const std::string program = o_.earc_db_program.empty() ? executableDir() + "/earc-db" : o_.earc_db_program;
  std::vector<std::pair<std::string, std::string>> builds;  // (how, log stem)
  if (files_.empty()) {
    builds.push_back({"--kind=" + family, work_ + "/logs/earc-db-" + family});
  } else {
    // Not an arm layout with no pair the database can hold
    // (warnNoClassFits says why): failing its build would take the
    // other files' rows and E-ARC trials with it.
    for (const ScenarioFile* f : earcBuildFiles(files_, family))
      builds.push_back({"--scenario=" + scenarioFile(*f),
                        work_ + "/logs/earc-db-" + family + "-" + std::to_string(builds.size())});
    // Every layout unbuildable: an empty database, which E-ARC opens.
    if (builds.empty()) exp::ExperienceStore created(path);
  }
  double construction = 0;
  for (const auto& [how, stem] : builds) {
    if (cli::stopFlag().load()) break;
    log_ << "building E-ARC database " << path << " (earc-db build " << how << ")\n";
    log_.flush();
    ChildSpec spec;
    spec.argv = {program, "build", "--db", path, how, "--seed", std::to_string(o_.seed)};
    if (o_.earc_db_count) {
      spec.argv.push_back("--count");
      spec.argv.push_back(std::to_string(*o_.earc_db_count));
    }
    spec.stdout_path = stem + ".out";
    spec.stderr_path = stem + ".err";
    spec.wall_limit_s = kEarcDbWallLimitS;
    spec.memory_limit_mb = o_.memory_limit_mb;
    ChildOutcome out = runChild(spec, &cli::stopFlag());
    if (out.exit_code != 0) {
      buildFailed(path, out, stem, "earc");
      // A half-built database must not pass for a built one: the file
      // (a link's target: the link was given) and its -wal and -shm.
      exp::removeDatabaseFiles(exp::databaseFile(path));
      return std::nullopt;
    }
    construction += out.wall_s;
  }
  return construction;
}

}  // namespace runner

}  // namespace earc::bench
