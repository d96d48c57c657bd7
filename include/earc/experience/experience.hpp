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

// Experiences are only ever handed between subproblems of one class: same
// kind, same number of robots, same bodies in the same canonical order,
// and (manipulators) the same relative base transform class. All keys of a
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

// The most uses one experience may count (retrieved, succeeded): 2^40, a
// million a second for twelve days. A row's counters stop there instead
// of overflowing, and the sums over a class (inspect) stay far from
// 64-bit overflow.
inline constexpr std::int64_t kMaxUseCount = std::int64_t{1} << 40;

// The latest creation time an experience may carry (created_at, Unix
// seconds): the end of the year 9999, the last a date prints for.
inline constexpr std::int64_t kMaxCreatedAt = 253'402'300'799;

// The robots' geometry signatures a class's '|'-joined signature names.
std::vector<std::string_view> signatureParts(const std::string& signature);

// What is wrong with a class's signature for these paths, or nothing: it
// must name robot_count robots ('|'-joined), each by a geometry signature
// earc writes (robotFromSignature), of the class's kind and with its path's
// dimension.
std::optional<std::string> signatureProblem(const ExperienceClass& c, const std::vector<Path>& paths);

// The farthest a stored mobile state's x or y may lie from 0. Stored
// mobile paths are relative to their subproblem's centre (keys.hpp), and a
// subproblem is a conflict's neighbourhood: the builder's are a few units
// across, and a scenario at the default resolution is at most 5e5 units
// across (1e7 steps of 0.05). A position beyond this is a damaged or made-up
// row; retrieved, it is millions of steps from anything in the workspace.
inline constexpr double kMaxStoredPosition = 1e6;

// Which state of the paths no robot of the class could take, as
// "paths[r][t]: ...", or nothing: a mobile x or y beyond
// kMaxStoredPosition, an arm joint outside the limits its signature gives
// (with the checker's slack and the signature's rounding). Nothing for
// what signatureProblem finds.
std::optional<std::string> stateProblem(const ExperienceClass& c, const std::vector<Path>& paths);

// What is wrong with an experience, or nothing: robot count, path
// dimensions and lengths, finite numbers, signature (signatureProblem),
// states (stateProblem), key dimension and agreement with the paths'
// endpoints, cost, base class form. Used on every insert and on every
// imported, verified or retrieved row.
std::optional<std::string> findProblem(const Experience& e);

}  // namespace earc::exp
