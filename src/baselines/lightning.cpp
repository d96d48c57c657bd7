// Lightning over the composite space of all robots (see lightning.hpp).
#include "earc/baselines/lightning.hpp"

#include <ompl/base/PlannerData.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/tools/lightning/Lightning.h>
#include <ompl/tools/lightning/LightningDB.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <set>
#include <sys/mman.h>
#include <unistd.h>

#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/planning/methods.hpp"
#include "earc/planning/ompl_composite.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/hash.hpp"
#include "earc/util/random.hpp"
#include "earc/validate/validator.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace earc {

namespace {

// Sampler streams (splitSeed of the planner seed) of the planners Lightning
// runs: each draws from its own, whichever thread runs it.
constexpr std::uint64_t kScratchStream = 1;
constexpr std::uint64_t kRepairStream = 2;
// Stream of the seed given to OMPL's global generator (its path simplifiers).
constexpr std::uint64_t kOmplGlobalStream = 3;
// Stream of our replanning of what OMPL's simplifier left invalid.
constexpr std::uint64_t kRepairPathStream = 4;

// RRT-Connect whose samplers draw from a stream of ours: one stream per
// solve() call, numbered in call order, so that the repair planner (one
// solve per repaired stretch) does not replay the same samples.
class StreamedRRTConnect : public og::RRTConnect {
 public:
  StreamedRRTConnect(const ob::SpaceInformationPtr& si, std::uint64_t stream) : og::RRTConnect(si), stream_(stream) {}
  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& ptc) override {
    SeededPlanningStream seeded(splitSeed(stream_, solves_++));
    return og::RRTConnect::solve(ptc);
  }

 private:
  std::uint64_t stream_;
  std::uint64_t solves_ = 0;
};

}  // namespace

// OMPL's Lightning database with the two edits it lacks: adding paths
// that are already PlannerData (from another file) and taking paths out
// again (planning without learning). Outside the anonymous namespace
// because LightningDatabase::Impl holds one (GCC's -Wsubobject-linkage
// fires on that in a unity build).
class EditableLightningDB : public ot::LightningDB {
 public:
  using ot::LightningDB::LightningDB;
  void addLoaded(const ob::PlannerDataPtr& path) { nn_->add(path); }
  // Removes every path not in `keep`; returns how many went.
  std::size_t keepOnly(const std::set<const ob::PlannerData*>& keep) {
    std::vector<ob::PlannerDataPtr> all;
    nn_->list(all);
    std::size_t removed = 0;
    for (const auto& p : all)
      if (!keep.count(p.get()) && nn_->remove(p)) ++removed;
    numUnsavedPaths_ = std::max(0, numUnsavedPaths_ - static_cast<int>(removed));
    return removed;
  }
  std::set<const ob::PlannerData*> snapshot() const {
    std::vector<ob::PlannerDataPtr> all;
    nn_->list(all);
    std::set<const ob::PlannerData*> ids;
    for (const auto& p : all) ids.insert(p.get());
    return ids;
  }
};

namespace {

// OMPL's Lightning with its experience database swapped for one we keep
// across problems (the protected member is the only way in).
class SharedDbLightning : public ot::Lightning {
 public:
  SharedDbLightning(const ob::SpaceInformationPtr& si, const ot::LightningDBPtr& db) : ot::Lightning(si) {
    experienceDB_ = db;
    getLightningRetrieveRepairPlanner().setLightningDB(db);
  }
};

// The robots of a scenario as models, in the scenario's order.
CompositeState starts(const Scenario& s) {
  CompositeState q;
  for (const auto& r : s.robots) q.push_back(r.start);
  return q;
}

CompositeState goals(const Scenario& s) {
  CompositeState q;
  for (const auto& r : s.robots) q.push_back(r.goal);
  return q;
}

// Kinds and count of robots, the part of a scenario the state space (and so
// a database file) depends on: "4 robots: mobile x4".
std::string spaceDescription(const Scenario& s) {
  int mobile = 0, arms = 0;
  for (const auto& r : s.robots) (r.kind == RobotKind::Mobile ? mobile : arms)++;
  std::string d = std::to_string(s.robots.size()) + " robots (";
  if (mobile) d += std::to_string(mobile) + " mobile";
  if (mobile && arms) d += ", ";
  if (arms) d += std::to_string(arms) + " arms";
  return d + ")";
}

bool sameSpace(const Scenario& a, const Scenario& b) {
  if (a.robots.size() != b.robots.size()) return false;
  for (std::size_t r = 0; r < a.robots.size(); ++r)
    if (a.robots[r].kind != b.robots[r].kind || a.robots[r].dim() != b.robots[r].dim()) return false;
  return true;
}

}  // namespace

struct LightningDatabase::Impl {
  Scenario prototype;
  RobotModels robots;
  CollisionWorld world;
  CompositeChecker checker;
  OmplComposite composite;
  std::shared_ptr<EditableLightningDB> db;

  explicit Impl(const Scenario& s)
      : prototype(s),
        robots(s),
        world(s),
        checker(world, robots.raw),
        composite(checker, compositeBounds(world, robots.raw, {}, {starts(s), goals(s)})),
        db(std::make_shared<EditableLightningDB>(composite.space())) {}
};

LightningDatabase::LightningDatabase(const Scenario& prototype) : impl_(std::make_unique<Impl>(prototype)) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
}

LightningDatabase::~LightningDatabase() = default;

// OMPL's loader trusts its file: a damaged one can crash it. So every file
// we write ends with a line of our own after OMPL's data, naming the state
// space and carrying a checksum of everything before it, and a file is
// handed to OMPL only when that line is there and agrees.
namespace {
// v2: one flat OMPL space for all robots (v1 had a compound of per-robot
// spaces, whose files OMPL's loader cannot read into a v2 space).
constexpr int kFormat = 2;
constexpr std::string_view kTrailerPrefix = "earc-lightning v";
const std::string kTrailerTag = std::string(kTrailerPrefix) + std::to_string(kFormat) + " fnv1a64=";

std::string trailer(std::string_view body, const std::string& space) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64(body)));
  return "\n" + kTrailerTag + hex + " space=" + space + "\n";
}
}  // namespace

void LightningDatabase::load(const std::string& path) {
  const std::string space = spaceDescription(impl_->prototype);
  const std::string rebuild = " (build one with earc-bench lightning-db)";
  const std::string refusal = "not a Lightning database of " + space + rebuild;
  const std::string bytes = readTextFile(path);
  // The likeliest wrong file: E-ARC's experience database, given to
  // --method lightning with the same --db option.
  if (bytes.starts_with(std::string_view("SQLite format 3\0", 16)))
    throw InputError(path, "", "an SQLite file (an E-ARC experience database?), not a Lightning database" + rebuild);
  const std::size_t at = bytes.rfind("\n" + kTrailerTag);
  if (at == std::string::npos || bytes.back() != '\n') {
    const std::size_t other = bytes.rfind("\n" + std::string(kTrailerPrefix));
    if (other != std::string::npos && bytes.back() == '\n') {
      const std::size_t from = other + 1 + kTrailerPrefix.size();
      const std::string version = bytes.substr(from, bytes.find(' ', from) - from);
      throw InputError(path, "", "Lightning database format v" + version + ", this earc reads v" +
                                     std::to_string(kFormat) + rebuild);
    }
    throw InputError(path, "", "no earc checksum line at the end: cut short, or not written by earc" + rebuild);
  }
  if (bytes.compare(at, std::string::npos, trailer(std::string_view(bytes).substr(0, at), space)) != 0) {
    const std::string line = bytes.substr(at + 1, bytes.size() - at - 2);
    if (line.find(" space=" + space) == std::string::npos) throw InputError(path, "", refusal);
    throw InputError(path, "", "damaged: its checksum does not match its contents" + rebuild);
  }
  // OMPL reads a path count, then the paths. Check that every path it
  // hands back has states.
  double declared = -1;
  {
    std::istringstream in(bytes.substr(0, at));
    in >> declared;
    if (!in || declared < 0 || declared != static_cast<double>(static_cast<std::size_t>(declared)))
      throw InputError(path, "", refusal);
  }
  // OMPL reads only from a named file. Hand it the bytes just checked, in
  // an anonymous in-memory file, not `path` again: the file could change
  // in between (another process saving it), and would be read twice.
  const int fd = ::memfd_create("earc-lightning", MFD_CLOEXEC);
  if (fd < 0) throw std::runtime_error(path + ": cannot load the Lightning database (memfd_create failed)");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  writeAll(fd, std::string_view(bytes).substr(0, at), path + " (in memory)");
  ot::LightningDB fresh(impl_->composite.space());
  if (!fresh.load("/proc/self/fd/" + std::to_string(fd))) throw InputError(path, "", refusal);
  std::vector<ob::PlannerDataPtr> paths;
  fresh.getAllPlannerDatas(paths);
  if (paths.size() != static_cast<std::size_t>(declared)) throw InputError(path, "", refusal);
  for (const auto& p : paths)
    if (p->numVertices() < 2) throw InputError(path, "", refusal);
  // The paths keep their own SpaceInformation (shared), so they outlive
  // the loader.
  for (const auto& p : paths) impl_->db->addLoaded(p);
}

void LightningDatabase::save(const std::string& path) const {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  auto fail = [&](const std::string& why) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error(path + ": cannot write the Lightning database" + why);
  };
  if (!impl_->db->save(tmp)) fail("");
  std::string body;
  try {
    body = readTextFile(tmp);  // to checksum it; bounded like every read
  } catch (const std::exception& e) {
    fail(std::string(": ") + e.what());
  }
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::app);
    out << trailer(body, spaceDescription(impl_->prototype));
    out.flush();
    if (!out) fail("");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) fail(": " + ec.message());
}

std::size_t LightningDatabase::entries() const { return impl_->db->getExperiencesCount(); }
std::size_t LightningDatabase::states() const { return impl_->db->getStatesCount(); }

PlanResult LightningDatabase::plan(const Scenario& scenario, const PlannerSettings& settings,
                                   const LightningSettings& lightning, const PlanContext& context) {
  Stopwatch clock;
  PlanResult result;
  result.solution.scenario = scenario.name;
  if (!sameSpace(scenario, impl_->prototype))
    throw std::invalid_argument("Lightning database of " + spaceDescription(impl_->prototype) + " used for " +
                                spaceDescription(scenario));
  RobotModels robots(scenario);
  CollisionWorld world(scenario);
  // Motions checked past the limit read as invalid: OMPL's path simplifier
  // runs one round however late (PathSimplifier::simplify, atLeastOnce),
  // and on arms of thousands of links that round took tens of seconds.
  const Deadline deadline = Deadline(settings.time_limit_s - clock.seconds()).stoppedBy(context.stop);
  CompositeChecker checker(world, robots.raw, deadline);
  const CompositeState start = starts(scenario), goal = goals(scenario);
  OmplComposite composite(checker, compositeBounds(world, robots.raw, {}, {start, goal}));
  composite.setSeed(settings.seed);
  // OMPL seeds the generators of its path simplifiers from a global one;
  // reset it (OMPL complains once generators exist, but does reseed).
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(splitSeed(settings.seed, kOmplGlobalStream) % 2147483647 + 1));

  const std::size_t entries_before = impl_->db->getExperiencesCount();
  const auto known = lightning.learn ? std::set<const ob::PlannerData*>{} : impl_->db->snapshot();
  PlanStats& st = result.stats;
  LightningStats& lst = st.lightning.emplace();
  lst.lightning_db_entries = static_cast<std::int64_t>(entries_before);
  if (!checker.stateValid(start) || !checker.stateValid(goal)) {
    result.failures.insert(checker.outOfTime() ? FailureCause::TimeLimit : FailureCause::InvalidInput);
    st.planning_time_s = clock.seconds();
    return result;
  }

  const ob::SpaceInformationPtr& si = composite.spaceInformation();
  SharedDbLightning lightning_setup(si, impl_->db);
  lightning_setup.setPlannerAllocator(
      [](const ob::SpaceInformationPtr& s) { return std::make_shared<StreamedRRTConnect>(s, kScratchStream); });
  lightning_setup.setRepairPlanner(std::make_shared<StreamedRRTConnect>(si, kRepairStream));
  lightning_setup.getLightningRetrieveRepairPlanner().setNumNearestSolutions(lightning.recall_k);
  ob::ScopedState<> s0(composite.space()), s1(composite.space());
  composite.fromComposite(start, s0.get());
  composite.fromComposite(goal, s1.get());
  lightning_setup.setStartAndGoalStates(s0, s1);
  lightning_setup.setup();

  const double remaining = settings.time_limit_s - clock.seconds();
  // The time limit, or sooner on the context's stop request.
  ob::PlannerStatus status =
      remaining > 0 ? lightning_setup.solve(ob::plannerOrTerminationCondition(
                          ob::timedPlannerTerminationCondition(remaining),
                          ob::PlannerTerminationCondition([stop = context.stop] { return stopSet(stop); })))
                    : ob::PlannerStatus(ob::PlannerStatus::TIMEOUT);
  const bool exact = status == ob::PlannerStatus::EXACT_SOLUTION && lightning_setup.haveExactSolutionPath();
  if (exact) {
    const std::string winner = lightning_setup.getSolutionPlannerName();
    const bool from_recall = winner == lightning_setup.getLightningRetrieveRepairPlanner().getName();
    lst.lightning_source = from_recall ? "recall" : "scratch";
    st.db_hits = from_recall ? 1 : 0;
    const og::PathGeometric& path = lightning_setup.getSolutionPath();
    std::vector<CompositeState> waypoints(path.getStateCount());
    for (std::size_t i = 0; i < waypoints.size(); ++i) composite.toComposite(path.getState(i), waypoints[i]);
    // OMPL holds wrapped headings; put back the exact endpoints (equal
    // modulo 2 pi, so every motion is unchanged).
    waypoints.front() = start;
    waypoints.back() = goal;
    // OMPL's simplifier keeps pieces of checked motions without checking
    // them again, which our checker (at the time-stamped instants of each
    // motion) may refuse; when its own repair of such a piece fails it
    // leaves the last state it sampled, in collision, in the path. Drop
    // such states and replan what is still invalid between the valid
    // states around it, as Lightning repairs a recalled path.
    // Past the limit checks read as invalid: a path found valid was truly
    // checked, one found invalid then may not be (see below).
    std::vector<CompositeState> kept{waypoints.front()};
    for (std::size_t i = 1; i + 1 < waypoints.size(); ++i)
      if (checker.stateValid(waypoints[i])) kept.push_back(waypoints[i]);
    kept.push_back(waypoints.back());
    std::vector<Path> paths = timeStampComposite(robots.raw, kept).paths;
    const std::vector<StepRun> runs = invalidRuns(checker, paths);
    std::string refused;
    if (!runs.empty()) {
      RunRepair fix = repairRuns(world, robots.raw, paths, runs, {}, deadline.remaining(), deadline,
                                 splitSeed(settings.seed, kRepairPathStream));
      lst.lightning_repaired_runs = static_cast<std::int64_t>(runs.size());
      if (fix.paths && invalidRuns(checker, *fix.paths).empty())
        paths = std::move(*fix.paths);
      else
        refused = "Lightning's path has " + std::to_string(runs.size()) + " invalid stretch(es) (the first at step " +
                  std::to_string(runs.front().first) + "), and replanning them failed: " +
                  (fix.why.empty() ? std::string("still invalid") : fix.why);
    }
    if (refused.empty()) {
      result.solution.solved = true;
      result.solution.paths = std::move(paths);
    } else if (checker.outOfTime()) {
      result.failures.insert(FailureCause::TimeLimit);
    } else {
      result.failures.insert(FailureCause::InvalidResult);
      st.invalid_result = std::vector<std::string>{refused};
    }
  } else {
    result.failures.insert(FailureCause::TimeLimit);
  }
  st.planning_time_s = clock.seconds();
  // Lightning adds what it found to the database itself; without learning
  // take it out again.
  if (!lightning.learn) impl_->db->keepOnly(known);
  lst.lightning_db_added =
      static_cast<std::int64_t>(impl_->db->getExperiencesCount()) - static_cast<std::int64_t>(entries_before);
  return result;
}

// plan()'s Lightning: the database file of the settings, if any.
PlanResult planLightning(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context) {
  LightningSettings ls;
  ls.db_path = settings.db.lightning_file;
  ls.learn = settings.db.learn;
  return planLightning(scenario, settings, ls, context);
}

PlanResult planLightning(const Scenario& scenario, const PlannerSettings& settings,
                         const LightningSettings& lightning, const PlanContext& context) {
  LightningDatabase db(scenario);
  const bool file = !lightning.db_path.empty();
  if (file && std::filesystem::exists(lightning.db_path)) db.load(lightning.db_path);
  const std::size_t before = db.entries();
  PlanResult result = db.plan(scenario, settings, lightning, context);
  if (file && lightning.learn && lightning.save && db.entries() != before) db.save(lightning.db_path);
  return result;
}

}  // namespace earc
