// Database construction (paper, "Database Construction"): random small
// subproblems shaped like ARC's conflicts, each solved in isolation in its
// composite space with solveCoupled, stored in canonical form.
//
// Mobile robots: 2, 3 and 4 robots (mix below) around a conflict point,
// each resting near it or passing by it (QuerySampling), random headings;
// the region is a box just around the query plus a margin.
// Manipulators: 2 arms for every relative base transform class of a layout
// (pairs whose reach discs overlap by kMinReachOverlap or more), start
// joints reaching towards the other arm and goals a short joint distance
// away.
//
// Queries whose straight composite motion is already valid are redrawn:
// they are not conflicts. Deterministic per seed with any thread count:
// problem i draws from splitSeed(seed, i) and rows are inserted in index
// order (as long as the time limit is not what decides a problem).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "earc/experience/sampling.hpp"
#include "earc/experience/store.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/progress.hpp"

namespace earc::exp {

// Default problem counts: what the 2-core reference machine builds within
// the targets (mobile 10 s, arms 20 s) with 2 threads; see the report.
inline constexpr int kDefaultMobileProblems = 5000;
inline constexpr int kDefaultArmProblems = 4000;

struct BuildSettings {
  RobotKind kind = RobotKind::Mobile;
  int count = 0;  // problems; 0: kDefaultMobileProblems / kDefaultArmProblems
  // Mobile: shares of problems with 2, 3 and 4 robots (ARC: conflicts of
  // few robots are the most frequent).
  std::vector<double> mobile_mix{0.5, 0.3, 0.2};
  // Mobile footprints, distinct (default: the generators' box robot); each
  // robot of a problem draws one in proportion to mobile_shares (empty:
  // equal), so a mixed fleet gets the mixed groups its conflicts make.
  std::vector<RobotSpec> mobile_robots;
  std::vector<double> mobile_shares;  // robots of each footprint, say
  // Manipulators: the arm layout whose pair classes are built (default:
  // gen::generateArms with 4 arms: facing, neighbouring and diagonal pairs).
  std::vector<RobotSpec> arms;
  Resolution resolution;
  double region_margin = 0.5;  // units around the mobile query (beyond the footprint)
  double joint_margin = 0.6;   // radians around the arm query
  QuerySampling sampling;
  std::uint64_t seed = 1;
  int threads = 2;
  double time_per_problem_s = 0.5;
  // Count time_per_problem_s in work done, not seconds (see
  // Deadline::withWorkBudgets): the same database on a busy machine.
  bool work_budgets = false;
  double near_duplicate_eps = 1e-3;
  // Called after each insert transaction commits, with the ids it stored
  // (duplicates left out); `earc-db build --report` logs them.
  std::function<void(const std::vector<std::int64_t>& ids)> on_commit;
  // Once set (a signal handler may), no new problem starts and the rows of
  // the problems before the first not started are kept. Null: never.
  const StopFlag* stop = nullptr;
};

struct BuildReport {
  int problems = 0;          // all asked for, or those handled before a stop
  bool stopped = false;      // settings.stop ended the build early
  int solved = 0;
  int inserted = 0;
  int duplicates = 0;
  int unsolved = 0;          // solver gave up within the time limit
  int no_query = 0;          // no conflicting valid query found
  double seconds = 0.0;
  std::map<std::string, int> inserted_per_class;  // ExperienceClass::label()
};

// Arm pairs whose reach discs overlap less are left out: they meet in no
// conflict worth storing (forEachReachingArmPair in builder.cpp says why).
inline constexpr double kMinReachOverlap = 0.25;

// The relative base transform classes of an arm layout: one representative
// pair (indices into arms) per class, in canonical order.
std::vector<std::pair<int, int>> armPairClasses(const std::vector<RobotSpec>& arms, const Resolution& resolution);

// The pairs of arms (indices, i < j) that can reach each other but have
// different joint counts: armPairClasses leaves them out, as the store
// holds no class for them (hasExperienceClass).
std::vector<std::pair<int, int>> unequalArmPairs(const std::vector<RobotSpec>& arms, const Resolution& resolution);

// One line for a build's summary saying how many such pairs were left out
// and naming the first with its joint counts; "" when pairs is empty.
std::string unequalArmPairsNote(const std::vector<RobotSpec>& arms, const std::vector<std::pair<int, int>>& pairs);

// Why armPairClasses found no class in a layout, in one line naming each
// arm with its joint count (no two arms of equal joints, or none of those
// pairs can reach). Thread-safe.
std::string noArmPairClassReason(const std::vector<RobotSpec>& arms);

// Builds into the store; progress (optional) ticks once per problem.
// Throws std::invalid_argument for unusable settings.
BuildReport buildDatabase(ExperienceStore& store, const BuildSettings& settings, Progress* progress = nullptr);

// A scenario's distinct mobile footprints (by geometry signature): one robot
// of each and how many robots have it, in the order they first appear.
struct Footprints {
  std::vector<std::string> signatures;
  std::vector<RobotSpec> robots;
  std::vector<double> counts;
};
Footprints scenarioFootprints(const Scenario& scenario);

}  // namespace earc::exp
