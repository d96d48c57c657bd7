// One experience: a solved subproblem stored in canonical form (keys.hpp),
// with its class, start/goal key, paths, and bookkeeping.
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "earc/scene/path.hpp"
#include "earc/scene/scenario.hpp"

namespace earc::exp {

// Where a row came from.
enum class Source { Build, Planner, Import };
const char* sourceName(Source s);                          // "build", "planner", "import"
std::optional<Source> sourceFromName(std::string_view name);
const char* kindName(RobotKind k);                         // "mobile", "manipulator"
std::optional<RobotKind> kindFromName(std::string_view name);

// What subproblems must share to share experiences: kind, robot count,
// bodies in canonical order and (arms) base transform class. All keys of a
// class have one dimension.
struct ExperienceClass {
  RobotKind kind = RobotKind::Mobile;
  int robot_count = 0;
  std::string signature;   // geometry signatures in canonical order, '|'-joined
  std::string base_class;  // manipulators: baseClassString(); mobile: empty
  auto operator<=>(const ExperienceClass&) const = default;
  bool operator==(const ExperienceClass&) const = default;
  // Short readable form: "mobile x2 mobile:disc:r=0.300000" or
  // "manipulator x2 dx=4.000,dy=0.000,dth=3.142 arm:...".
  std::string label() const;
};

struct Experience {
  std::int64_t id = 0;                // row id; 0 until stored
  ExperienceClass cls;
  std::vector<double> key;            // keyOfCanonicalPaths(cls.kind, paths)
  std::vector<Path> paths;            // canonical order and frame, all of one length
  double cost = 0.0;                  // pathCost(paths)
  Source source = Source::Build;
  std::int64_t created_at = 0;        // Unix seconds; 0: set on insert
  double solve_time_s = 0.0;
  std::int64_t retrieved = 0;         // recordUse counters
  std::int64_t succeeded = 0;
  std::int64_t created_session = 0;   // set by the store on insert
  // The earc build that solved it (earc::version(), set when it is made:
  // canonicalExperience), kept through export and import; '' not known
  // (stored before schema version 4).
  std::string made_by;
};

// The longest build name an experience may carry (Experience::made_by).
inline constexpr std::size_t kMaxMadeBy = 100;

// Sum over robots of the path length in steps (states - 1).
double pathCost(const std::vector<Path>& paths);

// The most planning sessions a file may count (a billion: a session a
// second for thirty years).
inline constexpr std::int64_t kMaxSession = 1'000'000'000;

// The most uses one experience may count (retrieved, succeeded): counters
// stop there, so that sums over a class (inspect) cannot overflow.
inline constexpr std::int64_t kMaxUseCount = std::int64_t{1} << 40;

// The latest creation time an experience may carry (created_at, Unix
// seconds): the end of the year 9999, the last a date prints for.
inline constexpr std::int64_t kMaxCreatedAt = 253'402'300'799;

// The robots' geometry signatures a class's '|'-joined signature names.
std::vector<std::string_view> signatureParts(const std::string& signature);

// What is wrong with a class's signature for these paths, or nothing: it
// must name robot_count robots ('|'-joined) by signatures earc writes
// (robotFromSignature), of the class's kind and its paths' dimension.
std::optional<std::string> signatureProblem(const ExperienceClass& c, const std::vector<Path>& paths);

// The farthest a stored mobile state's x or y may lie from its
// subproblem's centre (keys.hpp); beyond it a row is damaged or made up.
inline constexpr double kMaxStoredPosition = 1e6;

// The first state no robot of the class could take, as "paths[r][t]: ...":
// a mobile x or y beyond kMaxStoredPosition, an arm joint outside its
// signature's limits; or nothing (signatureProblem's faults included).
std::optional<std::string> stateProblem(const ExperienceClass& c, const std::vector<Path>& paths);

// What is wrong with an experience (counts, dimensions, numbers, signature,
// states, key, cost, base class), or nothing. Checked on every insert and
// every imported, verified or retrieved row.
std::optional<std::string> findProblem(const Experience& e);

}  // namespace earc::exp
