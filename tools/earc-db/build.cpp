// earc-db build --db FILE [--kind mobile|arms] [--count N] [--scenario FILE]
// [--shape box|disc --size LxW --radius R] [--seed S] [--threads T]
// [--time-per-problem S] [--report FILE]: fills a database with solved
// random subproblems (paper, "Database Construction"); see
// earc/methods/builder.hpp. SIGINT/SIGTERM keep what was built, exit 130/143.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <set>

#include "earc/cli/stop_signals.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/experience/keys.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/io/json_io.hpp"
#include "earc/methods/builder.hpp"
#include "earc/validate/scenario_check.hpp"

namespace {

struct BuildOptions {
  std::string db;
  std::string kind;  // "" : the --scenario's robots say, else mobile
  int count = 0;
  std::string scenario;
  std::string shape;
  std::string size;
  double radius = 0.0;
  std::uint64_t seed = 1;
  int threads = 2;
  double time_per_problem = 0.5;
  bool deterministic = false;
  double dedupe = 1e-3;
  std::string report;
  bool quiet = false;
};

// --report FILE: after every committed insert transaction, one line with
// the ids it stored (space-separated), appended and fsync'd before the
// build goes on, so that a reader knows what survives if the build is
// killed at any moment after it (tests/cli/serve_crash.sh).
class CommitLog {
 public:
  explicit CommitLog(const std::string& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw earc::InputError(path, "--report", std::string("cannot open: ") + std::strerror(errno));
  }
  ~CommitLog() { ::close(fd_); }
  CommitLog(const CommitLog&) = delete;
  CommitLog& operator=(const CommitLog&) = delete;
  void committed(const std::vector<std::int64_t>& ids) {
    if (ids.empty()) return;
    std::string line;
    for (std::int64_t id : ids) line += (line.empty() ? "" : " ") + std::to_string(id);
    line += "\n";
    // One write of the whole line, so that a kill leaves no half line.
    if (::write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size()) || ::fsync(fd_) != 0)
      throw std::runtime_error(path_ + ": cannot write the commit report: " + std::strerror(errno));
  }

 private:
  std::string path_;
  int fd_ = -1;
};

// "0.6x0.4" -> (0.6, 0.4).
earc::geo::Vec2 parseSize(const std::string& text) {
  double l = 0, w = 0;
  char x = 0, tail = 0;
  if (std::sscanf(text.c_str(), "%lf%c%lf%c", &l, &x, &w, &tail) != 3 || (x != 'x' && x != 'X') || !(l > 0) ||
      !(w > 0) || !std::isfinite(l) || !std::isfinite(w))
    throw earc::InputError("", "--size", "expected LENGTHxWIDTH with positive numbers, e.g. 0.6x0.4");
  return {l, w};
}

// The footprints to build for: the scenario's distinct mobile robots (each
// problem's robots drawn in proportion to their numbers there), or the one
// given by --shape/--size/--radius, or the builder's default.
void setMobileRobots(const BuildOptions& opt, const earc::Scenario* scenario, earc::exp::BuildSettings& s,
                     earc::InputWarnings& warnings) {
  std::vector<earc::RobotSpec>& out = s.mobile_robots;
  // --size sizes the default box; --radius needs --shape disc, as in
  // earc-scenario. A footprint option that would be ignored is a mistake.
  const std::string shape = !opt.shape.empty() ? opt.shape : !opt.size.empty() || opt.radius != 0.0 ? "box" : "";
  if (shape == "disc" && !opt.size.empty()) throw earc::InputError("", "--size", "is for --shape box");
  if (shape == "box" && opt.radius != 0.0) throw earc::InputError("", "--radius", "is for --shape disc");
  const earc::exp::Footprints fleet = scenario ? earc::exp::scenarioFootprints(*scenario) : earc::exp::Footprints{};
  if (scenario && shape.empty()) {
    if (fleet.robots.empty()) throw earc::InputError(opt.scenario, "$.robots", "no mobile robot to build for");
    out = fleet.robots;
    s.mobile_shares = fleet.counts;
    return;
  }
  if (shape.empty()) return;  // builder default
  earc::RobotSpec r;
  r.kind = earc::RobotKind::Mobile;
  if (shape == "disc") {
    if (!(opt.radius > 0)) throw earc::InputError("", "--radius", "a disc needs a positive radius");
    r.shape = earc::MobileShape::Disc;
    r.radius = opt.radius;
  } else {
    r.shape = earc::MobileShape::Box;
    r.box_size = parseSize(opt.size.empty() ? "0.6x0.4" : opt.size);
  }
  out.push_back(r);
  // The scenario then gives only its resolution: a database for another
  // footprint than its robots' answers none of them. Said now, not when a
  // plan finds its class empty.
  const std::string given = earc::makeRobotModel(r, s.resolution)->geometrySignature();
  if (!fleet.signatures.empty() &&
      std::find(fleet.signatures.begin(), fleet.signatures.end(), given) == fleet.signatures.end())
    warnings.push_back({opt.scenario, "",
                        "none of its mobile robots has the footprint given (" + given +
                            "); built for that footprint, this database will not answer them"});
}

// --kind, or a footprint option (mobile), or what the scenario holds: a
// database for an arm cell's scenario is an arm database without being
// told twice.
earc::RobotKind kindToBuild(const BuildOptions& opt, const earc::Scenario* scenario) {
  const bool footprint = !opt.shape.empty() || !opt.size.empty() || opt.radius != 0.0;
  if (opt.kind == "arms" && footprint)
    throw earc::InputError("", !opt.shape.empty() ? "--shape" : !opt.size.empty() ? "--size" : "--radius",
                           "is for mobile robots, not --kind arms");
  if (!opt.kind.empty()) return opt.kind == "arms" ? earc::RobotKind::Manipulator : earc::RobotKind::Mobile;
  if (!scenario || footprint) return earc::RobotKind::Mobile;
  const auto arms = std::count_if(scenario->robots.begin(), scenario->robots.end(),
                                  [](const earc::RobotSpec& r) { return r.kind == earc::RobotKind::Manipulator; });
  if (arms > 0 && arms < static_cast<std::ptrdiff_t>(scenario->robots.size()))
    throw earc::InputError(opt.scenario, "$.robots", "holds mobile robots and arms: say which with --kind");
  return arms > 0 ? earc::RobotKind::Manipulator : earc::RobotKind::Mobile;
}

int runBuild(const BuildOptions& opt, std::ostream& out) {
  // Ctrl-C (or SIGTERM) ends the build between problems: the rows built
  // so far are committed and kept (see the interrupted line below).
  earc::cli::StopSignals signals;
  earc::exp::BuildSettings s;
  s.stop = &signals.flag();
  s.count = opt.count;
  s.seed = opt.seed;
  s.threads = opt.threads;
  s.time_per_problem_s = opt.time_per_problem;
  s.work_budgets = opt.deterministic;
  s.near_duplicate_eps = opt.dedupe;
  // The report is appended to: as the database or the scenario it would
  // write lines into that file.
  earc::requireDistinctFiles({{"--scenario", opt.scenario}, {"--db", opt.db, true}, {"--report", opt.report}});
  earc::requireWritableOutput({"--report", opt.report});
  std::optional<earc::Scenario> scenario;
  // Warnings about the scenario (unknown keys and the like), even with -q,
  // once it is accepted as the robots to build for.
  earc::InputWarnings read_warnings;
  if (!opt.scenario.empty()) {
    scenario = earc::loadScenario(opt.scenario, &read_warnings);
    s.resolution = scenario->resolution;
  }
  s.kind = kindToBuild(opt, scenario ? &*scenario : nullptr);
  if (s.kind == earc::RobotKind::Mobile) {
    setMobileRobots(opt, scenario ? &*scenario : nullptr, s, read_warnings);
  } else if (scenario) {
    for (const auto& r : scenario->robots)
      if (r.kind == earc::RobotKind::Manipulator) s.arms.push_back(r);
    if (s.arms.size() < 2) throw earc::InputError(opt.scenario, "$.robots", "fewer than two arms to build for");
    // Said before the database is made: a refused build leaves no file.
    if (earc::exp::armPairClasses(s.arms, s.resolution).empty())
      throw earc::InputError(opt.scenario, "$.robots", earc::exp::noArmPairClassReason(s.arms));
  }
  earc::printInputWarnings(read_warnings);
  // Arms of unequal joint counts among equal ones: their pairs are left
  // out, and the summary says so.
  const std::string left_out = s.kind == earc::RobotKind::Manipulator
                                   ? earc::exp::unequalArmPairsNote(s.arms, earc::exp::unequalArmPairs(s.arms, s.resolution))
                                   : "";
  // Opened (created) only once every input has been accepted.
  std::optional<CommitLog> log;
  if (!opt.report.empty()) {
    log.emplace(opt.report);
    s.on_commit = [&log](const std::vector<std::int64_t>& ids) { log->committed(ids); };
  }
  const int count = s.count > 0 ? s.count
                                : (s.kind == earc::RobotKind::Mobile ? earc::exp::kDefaultMobileProblems
                                                                     : earc::exp::kDefaultArmProblems);
  std::error_code ec;
  const bool existed = std::filesystem::exists(opt.db, ec);
  const auto report = earc::exp::withInputErrors(opt.db, [&] {
    earc::exp::StoreOptions options;
    options.new_session = false;  // building is not a planning session
    options.full_check = true;    // never build onto a damaged file (indexes too)
    earc::exp::ExperienceStore store(opt.db, options);
    earc::Progress progress("build", static_cast<std::size_t>(count), !opt.quiet);
    return earc::exp::buildDatabase(store, s, &progress);
  });
  if (report.stopped) {
    std::cerr << "earc-db build: interrupted (" << signals.signalName() << "): kept " << report.inserted
              << " entries from the first " << report.problems << " of " << count << " problems in " << opt.db
              << "\n";
    return signals.exitCode();
  }
  // A footprint too large for the builder's small queries (starts 0.25-0.9
  // from the conflict point) places no problem at all: said, not "built 0".
  // A file this build made holds nothing then: it goes too.
  if (report.problems > 0 && report.no_query == report.problems) {
    if (!existed) earc::exp::removeDatabaseFiles(earc::exp::databaseFile(opt.db));  // a link's target, not the link
    const bool from_scenario = opt.size.empty() && opt.radius == 0.0 && !opt.scenario.empty();
    throw earc::InputError(from_scenario ? opt.scenario : "",
                           from_scenario ? "$.robots" : !opt.size.empty() ? "--size" : "--radius",
                           "none of " + std::to_string(report.problems) +
                               " problems could be made: no random query of these robots conflicts without "
                               "their starts or goals touching (too large a footprint?)");
  }
  if (opt.quiet) return 0;
  char line[256];
  std::snprintf(line, sizeof line,
                "built %s: %d entries from %d problems in %.2f s (%d solved, %d unsolved in %.2g s, %d without a "
                "conflicting query, %d near-duplicates)\n",
                opt.db.c_str(), report.inserted, report.problems, report.seconds, report.solved, report.unsolved,
                s.time_per_problem_s, report.no_query, report.duplicates);
  out << line;
  // A fleet of several footprints makes hundreds of classes: the largest
  // are listed, the rest counted (earc-db inspect lists them all).
  constexpr std::size_t kListedClasses = 12;
  std::vector<std::pair<std::string, int>> classes(report.inserted_per_class.begin(), report.inserted_per_class.end());
  if (classes.size() > kListedClasses)
    std::stable_sort(classes.begin(), classes.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  for (std::size_t i = 0; i < std::min(classes.size(), kListedClasses); ++i)
    out << "  " << classes[i].second << "  " << classes[i].first << "\n";
  if (classes.size() > kListedClasses) {
    int rest = 0;
    for (std::size_t i = kListedClasses; i < classes.size(); ++i) rest += classes[i].second;
    out << "  " << rest << " more in " << classes.size() - kListedClasses << " smaller classes (earc-db inspect lists them)\n";
  }
  if (!left_out.empty()) out << left_out << "\n";
  return 0;
}

void setupBuild(CLI::App& app) {
  auto opt = std::make_shared<BuildOptions>();
  CLI::App* sub = app.add_subcommand("build", "Fill a database with solved random subproblems");
  sub->add_option("--db", opt->db, "Experience database file (created when missing)")->check(earc::cli::kFileName)->required();
  sub->add_option("--kind", opt->kind, "Robot kind (default: the --scenario's, else mobile)")->check(CLI::IsMember({"mobile", "arms"}));
  sub->add_option("--count", opt->count,
                  "Problems to solve (default " + std::to_string(earc::exp::kDefaultMobileProblems) + " mobile, " +
                      std::to_string(earc::exp::kDefaultArmProblems) + " arms)")
      ->check(earc::cli::wholeNumberIn(1, 10000000));
  sub->add_option("--scenario", opt->scenario,
                  "Take robot geometry (mobile footprints or the arm layout) and resolution from this scenario")
      ->check(CLI::ExistingFile);
  sub->add_option("--shape", opt->shape, "Mobile footprint (default: box 0.6x0.4)")->check(CLI::IsMember({"box", "disc"}));
  sub->add_option("--size", opt->size, "Box footprint LENGTHxWIDTH (a box without --shape)");
  sub->add_option("--radius", opt->radius, "Disc footprint radius")->check(earc::cli::kFinitePositive);
  sub->add_option("--seed", opt->seed,
                  "Random seed (with --deterministic the result depends only on it; else also on whether a "
                  "problem's solver ran out of --time-per-problem)")
      ->check(earc::cli::kWholeNumber);
  sub->add_option("--threads", opt->threads, "Solver threads")->check(earc::cli::wholeNumberIn(1, 256));
  sub->add_option("--time-per-problem", opt->time_per_problem, "Solver time limit per problem (s)")
      ->check(earc::cli::kFinitePositive);
  sub->add_flag("--deterministic", opt->deterministic,
                "Count --time-per-problem in work done, not seconds: the same database from the same seed on a "
                "busy or slower machine");
  sub->add_option("--dedupe", opt->dedupe, "Skip entries this close in key space to a stored one (negative: keep all)")
      ->check(earc::cli::kFinite);
  sub->add_option("--report", opt->report,
                  "Append a line with the ids of each committed insert transaction to FILE (fsync'd)");
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success (no progress bar, no summary)");
  sub->callback([opt] { earc::cli::setExitCode(runBuild(*opt, std::cout)); });
}

}  // namespace

static earc::cli::Registrar registered_build("earc-db", "build", setupBuild);
