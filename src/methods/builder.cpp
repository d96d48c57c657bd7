#include "earc/methods/builder.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "earc/collision/collision_world.hpp"
#include "earc/experience/keys.hpp"
#include "earc/gen/generators.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/util/random.hpp"

namespace earc::exp {

namespace {

// Query draws per problem before it is given up as "no query".
constexpr int kQueryAttempts = 200;
// Solved problems inserted per transaction: few transactions, and rows
// become visible to other processes while the build runs.
constexpr std::size_t kInsertBatch = 32;

using Clock = std::chrono::steady_clock;

enum class Outcome { Solved, Unsolved, NoQuery };

struct ProblemResult {
  Outcome outcome = Outcome::NoQuery;
  Experience experience;
};

// One problem's robots, world and query, ready for solveCoupled.
struct Problem {
  Scenario scenario;
  std::vector<std::shared_ptr<const RobotModel>> models;
  CoupledQuery query;
};

std::vector<const RobotModel*> raw(const std::vector<std::shared_ptr<const RobotModel>>& models) {
  std::vector<const RobotModel*> out;
  for (const auto& m : models) out.push_back(m.get());
  return out;
}

RobotSpec defaultMobileRobot() {
  const gen::MobileFootprint f;
  RobotSpec s;
  s.name = "m";
  s.kind = RobotKind::Mobile;
  s.shape = f.shape;
  s.box_size = f.box_size;
  s.radius = f.radius;
  return s;
}

std::vector<RobotSpec> defaultArms() {
  gen::ArmSettings a;
  a.robots = 4;
  return gen::generateArms(a).robots;
}

// The index u in [0, 1) falls on when [0, 1) is cut in proportion to shares.
std::size_t pickByShares(const std::vector<double>& shares, double u) {
  double total = 0;
  for (double w : shares) total += w;
  double acc = 0;
  for (std::size_t i = 0; i < shares.size(); ++i) {
    acc += shares[i] / total;
    if (u < acc) return i;
  }
  return shares.size() - 1;
}

int robotsForMix(const std::vector<double>& mix, double u) { return static_cast<int>(pickByShares(mix, u)) + 2; }

bool conflicting(const CollisionWorld& world, const std::vector<const RobotModel*>& robots, const Query& q) {
  const CompositeChecker checker(world, robots);
  return checker.stateValid(q.starts) && checker.stateValid(q.goals) && !checker.motionValid(q.starts, q.goals);
}

// The bounding radius of the default mobile footprint (the generators'
// 0.6 x 0.4 box: 0.36056), for which QuerySampling's distances were
// chosen; rounded up, so that the default builds exactly as before
// whatever rounding the model's radius carries.
constexpr double kTunedBoundingRadius = 0.3606;

// Mobile: a workspace just around the query, no obstacles.
std::optional<Problem> mobileProblem(const BuildSettings& s, std::vector<RobotSpec> group, std::mt19937_64& rng) {
  Problem p;
  p.scenario.resolution = s.resolution;
  const int n = static_cast<int>(group.size());
  p.scenario.robots = std::move(group);
  p.models = makeRobotModels(p.scenario);
  const auto robots = raw(p.models);
  double radius = 0;
  for (const auto& m : p.models) radius = std::max(radius, m->boundingRadius());
  const double pad = radius + s.region_margin;
  // The start and goal distances were chosen for the default footprint
  // (the 0.6 x 0.4 box); a larger robot meets others farther from the
  // conflict point, and at those distances its starts would overlap.
  // Scaled with the footprint's bounding radius.
  QuerySampling sampling = s.sampling;
  // At most 8 times: paths then run to hundreds of steps at the default
  // resolution, and a footprint beyond it finds no query, as before.
  const double scale = std::clamp(radius / kTunedBoundingRadius, 1.0, 8.0);
  for (double* d : {&sampling.rest_radius, &sampling.pass_offset, &sampling.min_travel, &sampling.max_travel}) *d *= scale;
  for (int attempt = 0; attempt < kQueryAttempts; ++attempt) {
    Query q = sampleMobileQuery(n, rng, sampling);
    geo::Aabb box;
    for (const auto* v : {&q.starts, &q.goals})
      for (const auto& c : *v) box.expand({{c[0], c[1]}, {c[0], c[1]}});
    p.scenario.workspace = box.inflated(pad);
    const CollisionWorld world(p.scenario);
    if (!conflicting(world, robots, q)) continue;
    p.query = {robots, q.starts, q.goals, {}};  // region: the whole (reduced) workspace
    return p;
  }
  return std::nullopt;
}

// Arms: the pair's bases, a workspace around both reaches, a joint box
// around the query.
std::optional<Problem> armProblem(const BuildSettings& s, const RobotSpec& a, const RobotSpec& b, std::mt19937_64& rng) {
  Problem p;
  p.scenario.resolution = s.resolution;
  p.scenario.robots = {a, b};
  p.models = makeRobotModels(p.scenario);
  const auto robots = raw(p.models);
  geo::Aabb ws;
  for (const auto& m : p.models) {
    const geo::Vec2 c = m->spec().base_position;
    ws.expand(geo::Aabb{c, c}.inflated(m->boundingRadius() + 1.0));
  }
  p.scenario.workspace = ws;
  const CollisionWorld world(p.scenario);
  for (int attempt = 0; attempt < kQueryAttempts; ++attempt) {
    Query q = sampleArmQuery(*robots[0], *robots[1], rng, s.sampling);
    if (!conflicting(world, robots, q)) continue;
    std::vector<ConfigBox> region(2);
    for (std::size_t r = 0; r < 2; ++r) {
      std::vector<double> lo, hi;
      robots[r]->samplingBounds(ws, lo, hi);
      for (std::size_t j = 0; j < lo.size(); ++j) {
        region[r].lo.push_back(std::max(lo[j], std::min(q.starts[r][j], q.goals[r][j]) - s.joint_margin));
        region[r].hi.push_back(std::min(hi[j], std::max(q.starts[r][j], q.goals[r][j]) + s.joint_margin));
      }
    }
    p.query = {robots, q.starts, q.goals, region};
    return p;
  }
  return std::nullopt;
}

ProblemResult solveProblem(const BuildSettings& s, const std::vector<std::pair<int, int>>& arm_pairs,
                           std::size_t index) {
  std::mt19937_64 rng(splitSeed(s.seed, index));
  std::optional<Problem> problem;
  if (s.kind == RobotKind::Mobile) {
    const int n = robotsForMix(s.mobile_mix, uniform(rng, 0.0, 1.0));
    std::vector<RobotSpec> group;
    // One footprint draws nothing: its databases stay as they were.
    for (int r = 0; r < n; ++r)
      group.push_back(s.mobile_robots.size() == 1
                          ? s.mobile_robots.front()
                          : s.mobile_robots[pickByShares(s.mobile_shares, uniform(rng, 0.0, 1.0))]);
    problem = mobileProblem(s, std::move(group), rng);
  } else {
    const auto [a, b] = arm_pairs[index % arm_pairs.size()];
    problem = armProblem(s, s.arms[static_cast<std::size_t>(a)], s.arms[static_cast<std::size_t>(b)], rng);
  }
  ProblemResult result;
  if (!problem) return result;
  const CollisionWorld world(problem->scenario);
  CoupledSettings cs;
  cs.time_limit_s = s.time_per_problem_s;
  cs.within = Deadline().withWorkBudgets(s.work_budgets);
  cs.polish = true;
  const auto t0 = Clock::now();
  auto solution = solveCoupled(world, problem->query, cs, splitSeed(s.seed ^ 0xb01dULL, index));
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!solution) {
    result.outcome = Outcome::Unsolved;
    return result;
  }
  result.outcome = Outcome::Solved;
  result.experience =
      canonicalExperience(canonicalize(problem->query.robots, problem->query.starts, problem->query.goals),
                          solution->paths);
  result.experience.source = Source::Build;
  result.experience.solve_time_s = seconds;
  return result;
}

BuildSettings withDefaults(BuildSettings s) {
  if (s.count <= 0) s.count = s.kind == RobotKind::Mobile ? kDefaultMobileProblems : kDefaultArmProblems;
  if (s.threads < 1) throw std::invalid_argument("build: threads must be at least 1");
  if (s.time_per_problem_s <= 0) throw std::invalid_argument("build: time per problem must be positive");
  if (s.kind == RobotKind::Mobile) {
    if (s.mobile_robots.empty()) s.mobile_robots.push_back(defaultMobileRobot());
    for (const RobotSpec& r : s.mobile_robots)
      if (r.kind != RobotKind::Mobile) throw std::invalid_argument("build: mobile footprints must be mobile robots");
    if (s.mobile_mix.empty() || std::any_of(s.mobile_mix.begin(), s.mobile_mix.end(), [](double w) { return w < 0; }))
      throw std::invalid_argument("build: the robot-count mix needs non-negative shares");
    if (s.mobile_shares.empty()) s.mobile_shares.assign(s.mobile_robots.size(), 1.0);
    if (s.mobile_shares.size() != s.mobile_robots.size() ||
        std::any_of(s.mobile_shares.begin(), s.mobile_shares.end(), [](double w) { return !(w > 0); }))
      throw std::invalid_argument("build: one positive share per mobile footprint");
  } else {
    if (s.arms.empty()) s.arms = defaultArms();
  }
  return s;
}

}  // namespace

namespace {

// Calls fn(i, j, traits of i, traits of j) for each pair of arms i < j whose
// reach discs overlap by kMinReachOverlap or more. Less overlap is no real
// conflict worth storing: two arms of reach 2.55 at 5 units (the generated
// layout's diagonal neighbours) touch only fully stretched towards each
// other, and 1 in 10,000 query draws conflicts.
template <typename Fn>
void forEachReachingArmPair(const std::vector<RobotSpec>& arms, const Resolution& resolution, Fn fn) {
  std::vector<std::shared_ptr<const RobotModel>> models;
  for (const RobotSpec& a : arms) {
    if (a.kind != RobotKind::Manipulator) throw std::invalid_argument("build: the arm layout has a mobile robot");
    models.push_back(makeRobotModel(a, resolution));
  }
  for (std::size_t i = 0; i < models.size(); ++i)
    for (std::size_t j = i + 1; j < models.size(); ++j) {
      const double gap = geo::norm(arms[i].base_position - arms[j].base_position);
      if (gap > models[i]->boundingRadius() + models[j]->boundingRadius() - kMinReachOverlap) continue;
      fn(i, j, traitsOf(*models[i]), traitsOf(*models[j]));
    }
}

// "'a'", or "arm 2" for an arm without a name.
std::string armName(const std::vector<RobotSpec>& arms, std::size_t i) {
  return arms[i].name.empty() ? "arm " + std::to_string(i) : "'" + arms[i].name + "'";
}

}  // namespace

std::vector<std::pair<int, int>> armPairClasses(const std::vector<RobotSpec>& arms, const Resolution& resolution) {
  std::map<std::string, std::pair<int, int>> classes;  // label -> representative
  forEachReachingArmPair(arms, resolution, [&](std::size_t i, std::size_t j, RobotTraits ti, RobotTraits tj) {
    std::vector<RobotTraits> pair{ti, tj};
    if (!hasExperienceClass(pair)) return;
    std::vector<std::vector<double>> q{arms[i].start, arms[j].start};
    for (std::size_t r = 0; r < 2; ++r) q[r].assign(static_cast<std::size_t>(pair[r].dim), 0.0);
    const Canonical c = canonicalize(pair, q, q);
    const int a = static_cast<int>(c.order[0] == 0 ? i : j), b = static_cast<int>(c.order[0] == 0 ? j : i);
    classes.try_emplace(c.cls.label(), a, b);
  });
  std::vector<std::pair<int, int>> out;
  for (const auto& [label, pair] : classes) out.push_back(pair);
  return out;
}

std::vector<std::pair<int, int>> unequalArmPairs(const std::vector<RobotSpec>& arms, const Resolution& resolution) {
  std::vector<std::pair<int, int>> out;
  forEachReachingArmPair(arms, resolution, [&](std::size_t i, std::size_t j, RobotTraits ti, RobotTraits tj) {
    if (ti.dim != tj.dim) out.emplace_back(static_cast<int>(i), static_cast<int>(j));
  });
  return out;
}

std::string unequalArmPairsNote(const std::vector<RobotSpec>& arms, const std::vector<std::pair<int, int>>& pairs) {
  if (pairs.empty()) return "";
  const auto [a, b] = pairs.front();
  const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
  return "left out " + std::to_string(pairs.size()) + " arm pair" + (pairs.size() == 1 ? "" : "s") +
         " within reach whose joint counts differ (" + (pairs.size() == 1 ? "" : "e.g. ") + armName(arms, ia) +
         ": " + std::to_string(arms[ia].dim()) + " joints, " + armName(arms, ib) + ": " +
         std::to_string(arms[ib].dim()) + "); an arm database holds pairs of arms with equal joint counts only";
}

// The store holds pairs of arms with equal joint counts only
// (hasExperienceClass: a key and a path blob of one dimension for both).
std::string noArmPairClassReason(const std::vector<RobotSpec>& arms) {
  std::map<int, int> per_count;  // joint count -> arms with it
  std::string counts;
  for (std::size_t i = 0; i < arms.size(); ++i) {
    counts += (i ? ", " : "") + armName(arms, i) + ": " + std::to_string(arms[i].dim()) + (i ? "" : " joints");
    ++per_count[arms[i].dim()];
  }
  if (std::none_of(per_count.begin(), per_count.end(), [](const auto& c) { return c.second > 1; }))
    return "no two arms have the same number of joints (" + counts +
           "), and an arm database holds pairs of arms with equal joint counts only";
  std::ostringstream overlap;
  overlap << kMinReachOverlap;
  return "no two arms with the same number of joints can reach each other (" + counts +
         "; their reach discs must overlap by " + overlap.str() + " or more)";
}

namespace {

// The build's line in the database's history: what was asked for.
std::string buildDescription(const BuildSettings& s, std::size_t arm_pair_classes) {
  std::ostringstream out;
  out << s.count << (s.kind == RobotKind::Mobile ? " mobile problems" : " arm pair problems") << ", seed " << s.seed;
  if (s.kind == RobotKind::Mobile) {
    out << ", mix 2/3/4 robots";
    for (std::size_t i = 0; i < s.mobile_mix.size(); ++i) out << (i ? "/" : " ") << s.mobile_mix[i];
    out << ", " << s.mobile_robots.size() << " footprint" << (s.mobile_robots.size() == 1 ? "" : "s");
  } else {
    out << ", " << s.arms.size() << " arms, " << arm_pair_classes << " pair class"
        << (arm_pair_classes == 1 ? "" : "es");
  }
  out << ", " << s.time_per_problem_s << (s.work_budgets ? " s of work a problem" : " s a problem");
  // The mobile draw (QuerySampling), so that a database of an earlier
  // one, every robot crossing the conflict point, can be told apart.
  if (s.kind == RobotKind::Mobile)
    out << ", robots rest " << s.sampling.rest_probability << " or pass within " << s.sampling.pass_offset;
  return out.str();
}

}  // namespace

BuildReport buildDatabase(ExperienceStore& store, const BuildSettings& requested, Progress* progress) {
  const BuildSettings s = withDefaults(requested);
  const auto start = Clock::now();
  std::vector<std::pair<int, int>> arm_pairs;
  if (s.kind == RobotKind::Manipulator) {
    arm_pairs = armPairClasses(s.arms, s.resolution);
    if (arm_pairs.empty()) throw std::invalid_argument("build: " + noArmPairClassReason(s.arms));
  }
  store.describeHistory("build", buildDescription(s, arm_pairs.size()));
  const std::size_t n = static_cast<std::size_t>(s.count);
  std::vector<std::optional<ProblemResult>> results(n);
  std::mutex mutex;
  std::condition_variable ready;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  // A stop request starts no new problem: those under way finish, and
  // the inserter keeps the results before the first one not started.
  auto stopping = [&] { return stop || stopSet(s.stop); };
  auto worker = [&] {
    try {
      for (std::size_t i; !stopping() && (i = next++) < n;) {
        ProblemResult r = solveProblem(s, arm_pairs, i);
        {
          std::lock_guard lock(mutex);
          results[i] = std::move(r);
        }
        ready.notify_all();
        if (progress) progress->tick();
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
      stop = true;
      ready.notify_all();
    }
    // Stopped with no result to wake the inserter: it must see the stop.
    // Locked first, so that the wake cannot fall between its check and its wait.
    { std::lock_guard lock(mutex); }
    ready.notify_all();
  };
  std::vector<std::jthread> workers;
  for (int t = 0; t < std::min<int>(s.threads, s.count); ++t) workers.emplace_back(worker);

  // Insert in index order, in batches, as results arrive.
  BuildReport report;
  report.problems = s.count;
  std::vector<Experience> batch;
  auto flushBatch = [&] {
    if (batch.empty()) return;
    auto ids = store.insertAll(batch, s.near_duplicate_eps);
    std::vector<std::int64_t> committed;
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (ids[k]) {
        committed.push_back(*ids[k]);
        ++report.inserted;
        ++report.inserted_per_class[batch[k].cls.label()];
      } else {
        ++report.duplicates;
      }
    }
    batch.clear();
    if (s.on_commit) s.on_commit(committed);
  };
  try {
    for (std::size_t i = 0; i < n; ++i) {
      ProblemResult r;
      {
        std::unique_lock lock(mutex);
        auto abandoned = [&] { return stopSet(s.stop) && i >= next.load(); };
        ready.wait(lock, [&] { return results[i].has_value() || failure || abandoned(); });
        if (failure) break;
        if (!results[i]) {
          report.stopped = true;
          report.problems = static_cast<int>(i);
          break;
        }
        r = std::move(*results[i]);
        results[i].reset();
      }
      switch (r.outcome) {
        case Outcome::Solved:
          ++report.solved;
          batch.push_back(std::move(r.experience));
          break;
        case Outcome::Unsolved: ++report.unsolved; break;
        case Outcome::NoQuery: ++report.no_query; break;
      }
      if (batch.size() >= kInsertBatch) flushBatch();
    }
    flushBatch();
  } catch (...) {
    stop = true;
    throw;  // jthreads join on the way out
  }
  workers.clear();
  if (failure) std::rethrow_exception(failure);
  if (progress) progress->finish();
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

Footprints scenarioFootprints(const Scenario& scenario) {
  Footprints f;
  for (const auto& r : scenario.robots) {
    if (r.kind != RobotKind::Mobile) continue;
    const std::string sig = makeRobotModel(r, scenario.resolution)->geometrySignature();
    const auto at = std::find(f.signatures.begin(), f.signatures.end(), sig);
    if (at != f.signatures.end()) {
      f.counts[static_cast<std::size_t>(at - f.signatures.begin())] += 1;
      continue;
    }
    f.signatures.push_back(sig);
    f.robots.push_back(r);
    f.counts.push_back(1);
  }
  return f;
}

}  // namespace earc::exp
