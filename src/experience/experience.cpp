#include "earc/experience/experience.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "earc/experience/keys.hpp"
#include "earc/geometry/shapes.hpp"
#include "earc/scene/robot_signature.hpp"
#include "earc/util/format.hpp"

namespace earc::exp {

namespace {

// How far a stored key may be from the key of its paths' endpoints.
constexpr double kKeyTolerance = 1e-6;

std::size_t countParts(const std::string& s, char sep) {
  std::size_t n = 1;
  for (char ch : s) n += ch == sep;
  return n;
}

// A piece of a row quoted in a message: a hostile file's signature may be
// megabytes long, the message stays one readable line.
std::string quoted(std::string_view s) {
  constexpr std::size_t kShown = 60;
  return "\"" + std::string(s.substr(0, kShown)) + (s.size() > kShown ? "...\"" : "\"");
}

// What a geometry signature says about its robot that a row must agree with.
struct SignedRobot {
  RobotKind kind;
  int dim;
  std::vector<std::pair<double, double>> joint_limits;  // arms
};

// The robots a '|'-joined signature names, or (problem) why it names none.
struct SignedRobots {
  std::vector<SignedRobot> robots;
  std::string problem;
};

// Reading a signature builds robot models, which costs more than decoding
// the row; rows come class by class, so the last one read is remembered.
// The reference holds until the next call on this thread.
const SignedRobots& readSignature(const std::string& signature, const std::vector<std::string_view>& parts) {
  thread_local std::string known;
  thread_local bool read_once = false;
  thread_local SignedRobots last;
  if (read_once && signature == known) return last;
  SignedRobots read;
  for (std::size_t r = 0; r < parts.size() && read.problem.empty(); ++r) {
    auto spec = robotFromSignature(parts[r]);
    if (spec)
      read.robots.push_back({spec->kind, spec->dim(), spec->joint_limits});
    else
      read.problem = "robot " + std::to_string(r) + ": " + quoted(parts[r]) +
                     " is not a geometry signature earc writes";
  }
  known = signature;
  read_once = true;
  last = std::move(read);
  return last;
}


// How far past a joint limit a stored joint may lie: the checker's 1e-6
// (RobotModel::withinLimits), and the signature's limits are rounded to 6
// significant digits (pi is 3.14159 there), 5e-6 of the limit at most.
double jointLimitSlack(double limit) { return geo::kContactTolerance + 1e-5 * std::abs(limit); }

// A base class string is well formed when it is what baseClassString
// prints for some transform: three numbers with three decimals, the angle
// in (-pi, pi] at that precision.
bool wellFormedBaseClass(const std::string& s) {
  double dx, dy, dt;
  char tail;
  if (std::sscanf(s.c_str(), "dx=%lf,dy=%lf,dth=%lf%c", &dx, &dy, &dt, &tail) != 3) return false;
  if (!std::isfinite(dx) || !std::isfinite(dy) || !std::isfinite(dt)) return false;
  const double pi_rounded = std::round(std::numbers::pi / kBaseClassQuantum) * kBaseClassQuantum;
  if (dt <= -pi_rounded + 0.5 * kBaseClassQuantum || dt > pi_rounded + 0.5 * kBaseClassQuantum) return false;
  char buf[96];
  std::snprintf(buf, sizeof buf, "dx=%.3f,dy=%.3f,dth=%.3f", dx, dy, dt);
  return s == buf && s.find("-0.000") == std::string::npos;
}

}  // namespace

std::vector<std::string_view> signatureParts(const std::string& signature) {
  std::vector<std::string_view> parts;
  for (std::size_t at = 0;;) {
    const std::size_t end = signature.find('|', at);
    parts.push_back(std::string_view(signature).substr(at, end - at));
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return parts;
}

const char* sourceName(Source s) {
  switch (s) {
    case Source::Build: return "build";
    case Source::Planner: return "planner";
    case Source::Import: return "import";
  }
  return "?";
}

std::optional<Source> sourceFromName(std::string_view name) {
  for (Source s : {Source::Build, Source::Planner, Source::Import})
    if (name == sourceName(s)) return s;
  return std::nullopt;
}

const char* kindName(RobotKind k) { return k == RobotKind::Mobile ? "mobile" : "manipulator"; }

std::optional<RobotKind> kindFromName(std::string_view name) {
  if (name == "mobile") return RobotKind::Mobile;
  if (name == "manipulator") return RobotKind::Manipulator;
  return std::nullopt;
}

std::string ExperienceClass::label() const {
  std::string s = std::string(kindName(kind)) + " x" + std::to_string(robot_count);
  if (!base_class.empty()) s += " " + base_class;
  return s + " " + signature;
}

double pathCost(const std::vector<Path>& paths) {
  double c = 0;
  for (const Path& p : paths) c += p.empty() ? 0.0 : static_cast<double>(p.size() - 1);
  return c;
}

std::optional<std::string> signatureProblem(const ExperienceClass& c, const std::vector<Path>& paths) {
  const std::size_t count = c.signature.empty() ? 0 : countParts(c.signature, '|');
  if (count != static_cast<std::size_t>(c.robot_count))
    return "names " + std::to_string(count) + " robots, expected " + std::to_string(c.robot_count);
  const std::vector<std::string_view> parts = signatureParts(c.signature);
  const SignedRobots& read = readSignature(c.signature, parts);
  if (!read.problem.empty()) return read.problem;
  const std::vector<SignedRobot>& robots = read.robots;
  for (std::size_t r = 0; r < parts.size(); ++r) {
    if (robots[r].kind != c.kind)
      return "robot " + std::to_string(r) + ": " + quoted(parts[r]) + " is " +
             (robots[r].kind == RobotKind::Mobile ? "a mobile robot" : "an arm") + ", in a " + kindName(c.kind) + " class";
    if (r < paths.size() && paths[r].dim() != robots[r].dim)
      return "robot " + std::to_string(r) + ": " + quoted(parts[r]) + " has " + std::to_string(robots[r].dim) +
             " coordinates, its path " + std::to_string(paths[r].dim());
  }
  return std::nullopt;
}

// kMaxStoredPosition: a subproblem is a conflict's neighbourhood, a few
// units across from the builder, and a scenario at the default resolution
// is at most 5e5 units across (1e7 steps of 0.05). Arm joints get the
// checker's slack and the signature's rounding.
std::optional<std::string> stateProblem(const ExperienceClass& c, const std::vector<Path>& paths) {
  auto at = [](std::size_t r, std::size_t t) {
    return "paths[" + std::to_string(r) + "][" + std::to_string(t) + "]: ";
  };
  if (c.kind == RobotKind::Mobile) {
    for (std::size_t r = 0; r < paths.size(); ++r) {
      const Path& p = paths[r];
      if (p.dim() < 2) continue;
      for (std::size_t t = 0; t < p.size(); ++t)
        for (int i : {0, 1})
          if (!(std::abs(p.at(t)[i]) <= kMaxStoredPosition))
            return at(r, t) + (i == 0 ? "x " : "y ") + formatNumber(p.at(t)[i]) + " is beyond +-" +
                   formatNumber(kMaxStoredPosition) + " of its subproblem's centre";
    }
    return std::nullopt;
  }
  const std::vector<std::string_view> parts = signatureParts(c.signature);
  const SignedRobots& read = readSignature(c.signature, parts);
  if (!read.problem.empty()) return std::nullopt;  // signatureProblem's to say
  for (std::size_t r = 0; r < paths.size() && r < read.robots.size(); ++r) {
    const Path& p = paths[r];
    const auto& limits = read.robots[r].joint_limits;
    if (limits.size() != static_cast<std::size_t>(p.dim())) continue;  // signatureProblem's too
    for (std::size_t t = 0; t < p.size(); ++t)
      for (std::size_t j = 0; j < limits.size(); ++j) {
        const auto [lo, hi] = limits[j];
        const double q = p.at(t)[j];
        if (!(q >= lo - jointLimitSlack(lo) && q <= hi + jointLimitSlack(hi)))
          return at(r, t) + "joint " + std::to_string(j) + " " + formatNumber(q) + " is outside its limits " +
                 formatNumber(lo) + "/" + formatNumber(hi);
      }
  }
  return std::nullopt;
}

// kMaxUseCount is 2^40, a million uses a second for twelve days.
std::optional<std::string> findProblem(const Experience& e) {
  const ExperienceClass& c = e.cls;
  if (c.robot_count < 1 || c.robot_count > 64) return "robot_count " + std::to_string(c.robot_count) + " outside 1..64";
  if (e.paths.size() != static_cast<std::size_t>(c.robot_count))
    return std::to_string(e.paths.size()) + " paths for robot_count " + std::to_string(c.robot_count);
  const int dim = e.paths.front().dim();
  const std::size_t steps = e.paths.front().size();
  for (std::size_t r = 0; r < e.paths.size(); ++r) {
    const Path& p = e.paths[r];
    if (p.dim() != dim || p.size() != steps || p.empty())
      return "path " + std::to_string(r) + " differs in dimension or length from path 0 (or is empty)";
    for (double v : p.raw())
      if (!std::isfinite(v)) return "path " + std::to_string(r) + " has a non-finite coordinate";
  }
  if (c.kind == RobotKind::Mobile) {
    if (dim != 3) return "mobile paths must have 3 coordinates, not " + std::to_string(dim);
    if (!c.base_class.empty()) return "mobile class with a base class \"" + c.base_class + "\"";
  } else {
    if (c.robot_count != 2) return "manipulator classes hold pairs, not " + std::to_string(c.robot_count) + " arms";
    if (!wellFormedBaseClass(c.base_class)) return "malformed base class \"" + c.base_class + "\"";
  }
  if (auto problem = signatureProblem(c, e.paths)) return "signature: " + *problem;
  if (auto problem = stateProblem(c, e.paths)) return *problem;
  const int kd = keyDimension(c.kind, c.robot_count, dim);
  if (e.key.size() != static_cast<std::size_t>(kd))
    return "key has " + std::to_string(e.key.size()) + " values, the class needs " + std::to_string(kd);
  const std::vector<double> expected = keyOfCanonicalPaths(c.kind, e.paths);
  for (std::size_t i = 0; i < e.key.size(); ++i) {
    if (!std::isfinite(e.key[i])) return "key value " + std::to_string(i) + " is not finite";
    if (std::abs(e.key[i] - expected[i]) > kKeyTolerance)
      return "key value " + std::to_string(i) + " disagrees with the paths' start/goal";
  }
  if (!std::isfinite(e.cost) || std::abs(e.cost - pathCost(e.paths)) > 1e-9) {
    // %.17g: exact and short; std::to_string writes 1e308 in 309 digits.
    char buf[96];
    std::snprintf(buf, sizeof buf, "cost %.17g is not the paths' length in steps %.17g", e.cost, pathCost(e.paths));
    return buf;
  }
  if (!std::isfinite(e.solve_time_s) || e.solve_time_s < 0) return "solve_time_s is negative or not finite";
  // A session number counts a file's planning sessions: an import that
  // keeps it also raises the file's count to it, which must stay a count.
  if (e.created_session < 0 || e.created_session > kMaxSession)
    return "created_session " + std::to_string(e.created_session) + " is not a session number (0.." +
           std::to_string(kMaxSession) + ")";
  if (e.retrieved < 0 || e.succeeded < 0 || e.succeeded > e.retrieved || e.retrieved > kMaxUseCount)
    return "usage counters out of range (retrieved " + std::to_string(e.retrieved) + ", succeeded " +
           std::to_string(e.succeeded) + "; 0 <= succeeded <= retrieved <= " + std::to_string(kMaxUseCount) + ")";
  if (e.created_at < 0) return "created_at is negative";
  if (e.created_at > kMaxCreatedAt)
    return "created_at " + std::to_string(e.created_at) + " is after the year 9999";
  // A build's name, shown on one line by inspect: short, printable ASCII.
  if (e.made_by.size() > kMaxMadeBy) return "made_by longer than " + std::to_string(kMaxMadeBy) + " characters";
  if (std::any_of(e.made_by.begin(), e.made_by.end(), [](char ch) { return ch < 0x20 || ch > 0x7e; }))
    return "made_by has a character that is not printable ASCII";
  return std::nullopt;
}

}  // namespace earc::exp
