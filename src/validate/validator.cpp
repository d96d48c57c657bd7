// validateSolution: the contract's three rules, counted and ordered as
// shared/tools/check_solution.py does (see validator.hpp).
#include "earc/validate/validator.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <unordered_map>

#include "earc/util/format.hpp"

namespace earc {
namespace {

using Type = Violation::Type;

// Instants handed to a worker at a time: large enough to amortise the
// scheduling, small enough to balance two cores on short solutions.
constexpr std::size_t kInstantsPerBlock = 64;

std::string fmtState(std::span<const double> q) {
  std::string s = "[";
  for (std::size_t i = 0; i < q.size(); ++i) s += (i ? ", " : "") + formatNumber(q[i]);
  return s + "]";
}

// The checker's order of violation kinds at one instant.
enum Code { kResTranslation, kResRotation, kResJoint, kJointLimit, kWorkspace, kObstacle, kSelf, kRobot };

int codeOf(const Violation& v) {
  switch (v.type) {
    case Type::JointLimit: return kJointLimit;
    case Type::Workspace: return kWorkspace;
    case Type::Obstacle: return kObstacle;
    case Type::SelfCollision: return kSelf;
    default: return kRobot;
  }
}

// A violation at an instant k (k = 2t, or 2t + 1 for the midpoint of step
// t; resolution violations sit at their step's midpoint), sortable as the
// checker sorts: by instant, kind, robot, then obstacle / other robot / joint.
struct Record {
  std::size_t k;
  int code;
  int a;
  int b;
  Violation v;
  bool operator<(const Record& o) const {
    if (k != o.k) return k < o.k;
    if (code != o.code) return code < o.code;
    if (a != o.a) return a < o.a;
    return b < o.b;
  }
};

struct BlockResult {
  std::size_t count = 0;
  std::vector<Record> first;  // earliest, at most `keep`
};

// Which path belongs to which robot, and the structural problems of the
// solution, found as the checker's parse_solution finds them.
struct PathMap {
  std::vector<const Path*> of;  // per scenario robot, nullptr when unusable
  std::vector<Violation> issues;
};

PathMap mapPaths(const Scenario& sc, const Solution& sol) {
  const std::size_t n = sc.robots.size();
  PathMap m;
  m.of.assign(n, nullptr);
  std::vector<bool> named(n, false), seen(n, false);
  auto issue = [&](int robot, std::string detail) {
    m.issues.push_back({Type::Paths, -1, robot < 0 ? std::vector<int>{} : std::vector<int>{robot}, std::move(detail)});
    if (robot >= 0) named[static_cast<std::size_t>(robot)] = true;
  };
  if (!sol.solved) m.issues.push_back({Type::NotSolved, -1, {}, "the solution says solved=false"});
  if (!sol.scenario.empty() && !sc.name.empty() && sol.scenario != sc.name)
    m.issues.push_back({Type::ScenarioName, -1, {}, "solution is for scenario '" + sol.scenario + "', not '" + sc.name + "'"});
  if (!sol.robot_names.empty() && sol.robot_names.size() != sol.paths.size())
    throw std::invalid_argument("validateSolution: robot_names and paths differ in length");

  std::unordered_map<std::string, int> index;
  for (std::size_t i = 0; i < n; ++i) index.emplace(sc.robots[i].name, static_cast<int>(i));
  for (std::size_t pos = 0; pos < sol.paths.size(); ++pos) {
    int r;
    if (sol.robot_names.empty()) {
      if (pos >= n) {
        issue(-1, "path entry " + std::to_string(pos) + " has no robot (the scenario has " + std::to_string(n) + ")");
        continue;
      }
      r = static_cast<int>(pos);
    } else {
      auto it = index.find(sol.robot_names[pos]);
      if (it == index.end()) {
        issue(-1, "path for unknown robot '" + sol.robot_names[pos] + "'");
        continue;
      }
      r = it->second;
    }
    const RobotSpec& spec = sc.robots[static_cast<std::size_t>(r)];
    const Path& path = sol.paths[pos];
    if (!path.empty() && path.dim() != spec.dim()) {
      issue(r, "path of '" + spec.name + "' has states of " + std::to_string(path.dim()) + " numbers, expected " +
                   std::to_string(spec.dim()));
      continue;
    }
    if (seen[static_cast<std::size_t>(r)]) {
      issue(r, "more than one path for robot '" + spec.name + "'");
      continue;
    }
    seen[static_cast<std::size_t>(r)] = true;
    if (static_cast<int>(pos) != r)
      issue(r, "path of '" + spec.name + "' is entry " + std::to_string(pos) + ", scenario order puts it at " +
                   std::to_string(r));
    if (path.empty()) {
      issue(r, "path of '" + spec.name + "' has no states");
      continue;
    }
    m.of[static_cast<std::size_t>(r)] = &path;
  }
  if (sol.solved || !sol.paths.empty())
    for (std::size_t r = 0; r < n; ++r)
      if (m.of[r] == nullptr && !named[r]) issue(static_cast<int>(r), "no path for robot '" + sc.robots[r].name + "'");
  return m;
}

bool endpointMatches(const RobotSpec& spec, const double* q, const std::vector<double>& target) {
  const std::size_t d = target.size();
  for (std::size_t i = 0; i < d; ++i) {
    const bool heading = spec.kind == RobotKind::Mobile && i == 2;
    const double diff = heading ? geo::wrapAngle(q[i] - target[i]) : q[i] - target[i];
    if (!(std::abs(diff) <= geo::kContactTolerance)) return false;
  }
  return true;
}

// Resolution records of step s -> s + 1 of robot r.
void checkStep(const RobotSpec& spec, const Resolution& res, int r, const double* a, const double* b, std::size_t s,
               std::vector<Record>& out) {
  const std::size_t k = 2 * s + 1;
  // The message is made only for a violation: this runs for every step of
  // every robot.
  auto add = [&](int code, const char* quantity, double amount, double limit, int joint) {
    const std::string between = " between t=" + std::to_string(s) + " and t=" + std::to_string(s + 1) + ", resolution ";
    const std::string j = joint >= 0 ? " (joint " + std::to_string(joint + 1) + ")" : "";
    out.push_back({k, code, r, -1,
                   {Type::Resolution, static_cast<double>(s), {r},
                    spec.name + " changes " + quantity + " by " + formatNumber(amount) + j + between + formatNumber(limit), -1, joint,
                    amount}});
  };
  if (spec.kind == RobotKind::Mobile) {
    const double tr = geo::norm({b[0] - a[0], b[1] - a[1]});
    const double rot = std::abs(geo::wrapAngle(b[2] - a[2]));
    if (tr > res.translation + geo::kContactTolerance) add(kResTranslation, "translation", tr, res.translation, -1);
    if (rot > res.rotation + geo::kContactTolerance) add(kResRotation, "rotation", rot, res.rotation, -1);
  } else {
    double worst = -1.0;
    int wj = 0;
    for (int j = 0; j < spec.dim(); ++j)
      if (std::abs(b[j] - a[j]) > worst) worst = std::abs(b[j] - a[j]), wj = j;
    if (worst > res.joint + geo::kContactTolerance) add(kResJoint, "joint", worst, res.joint, wj);
  }
}

// Configuration of a robot at instant k: its state k / 2, or the midpoint
// of states k / 2 and k / 2 + 1 (heading along the shortest arc), computed
// as the checker does; a robot past its last state stays there.
void configurationAt(const RobotSpec& spec, const Path& p, std::size_t k, double* out) {
  const double* a = p.at(k / 2);
  const int d = p.dim();
  if (k % 2 == 0) {
    std::copy(a, a + d, out);
    return;
  }
  const double* b = p.at(k / 2 + 1);
  for (int i = 0; i < d; ++i) out[i] = 0.5 * (a[i] + b[i]);
  if (spec.kind == RobotKind::Mobile) out[2] = a[2] + 0.5 * geo::wrapAngle(b[2] - a[2]);
}

}  // namespace

const char* violationTypeName(Violation::Type t) {
  switch (t) {
    case Type::NotSolved: return "not-solved";
    case Type::Paths: return "paths";
    case Type::Start: return "start";
    case Type::Goal: return "goal";
    case Type::Resolution: return "resolution";
    case Type::JointLimit: return "joint-limit";
    case Type::Workspace: return "workspace";
    case Type::Obstacle: return "obstacle";
    case Type::SelfCollision: return "self-collision";
    case Type::RobotRobot: return "robot-robot";
    case Type::ScenarioName: return "scenario-name";
  }
  return "unknown";
}

// Violations are ordered as check_solution.py lists them: the problems found
// in the solution's structure (not solved, scenario name, paths) and its
// endpoints first, then everything else by instant, and at one instant
// by kind (resolution, joint limits, workspace, obstacle, self-collision,
// robot-robot), then by robot. Instants are checked on all cores.
ValidationReport validateSolution(const Scenario& sc, const Solution& sol, const ValidatorSettings& settings) {
  ValidationReport rep;
  PathMap map = mapPaths(sc, sol);
  std::vector<Violation>& issues = map.issues;

  std::vector<int> present;
  std::size_t T = 0;
  for (std::size_t r = 0; r < sc.robots.size(); ++r) {
    const Path* p = map.of[r];
    if (p == nullptr) continue;
    const RobotSpec& spec = sc.robots[r];
    const int ri = static_cast<int>(r);
    present.push_back(ri);
    const std::size_t steps = p->size() - 1;
    T = std::max(T, steps);
    rep.sum_of_costs += steps;
    if (!endpointMatches(spec, p->at(0), spec.start))
      issues.push_back({Type::Start, 0, {ri},
                        spec.name + " first state " + fmtState(p->state(0)) + " != start " + fmtState(spec.start)});
    if (!endpointMatches(spec, p->back(), spec.goal))
      issues.push_back({Type::Goal, static_cast<double>(steps), {ri},
                        spec.name + " last state " + fmtState(p->state(steps)) + " != goal " + fmtState(spec.goal)});
    for (std::size_t t = 0; t < steps; ++t) {
      const double* a = p->at(t);
      const double* b = p->at(t + 1);
      if (spec.kind == RobotKind::Mobile) {
        rep.total_distance += geo::norm({b[0] - a[0], b[1] - a[1]});
      } else {
        for (int j = 0; j < p->dim(); ++j) rep.total_distance += std::abs(b[j] - a[j]);
      }
    }
  }
  rep.makespan = T;

  // Every instant k = 0 .. 2T, in blocks, on all cores.
  const std::size_t K = present.empty() ? 0 : 2 * T + 1;
  const std::size_t blocks = (K + kInstantsPerBlock - 1) / kInstantsPerBlock;
  const std::size_t keep = settings.max_listed;
  std::vector<BlockResult> results(blocks);
  std::atomic<std::size_t> next{0};
  const InstantChecker checker(sc);

  // Where each present robot's configuration lies in a thread's buffer.
  std::vector<std::size_t> offset(present.size() + 1, 0);
  std::vector<std::size_t> position(sc.robots.size(), 0);
  for (std::size_t i = 0; i < present.size(); ++i) {
    const auto r = static_cast<std::size_t>(present[i]);
    offset[i + 1] = offset[i] + static_cast<std::size_t>(sc.robots[r].dim());
    position[r] = i;
  }
  auto checkBlocks = [&] {
    std::vector<double> qbuf, before;
    std::vector<const double*> q(present.size());
    std::vector<Violation> found;
    std::vector<Record> recs;
    // A robot standing where it stood at the instant before, which met no
    // obstacle, workspace bound or itself there, meets none now either:
    // in a crowd's plan most robots wait or have arrived at most instants.
    std::vector<char> clean(present.size(), 0), known(present.size(), 0);
    std::size_t last_k = 0;
    bool have_last = false;
    for (std::size_t blk; (blk = next.fetch_add(1)) < blocks;) {
      BlockResult& out = results[blk];
      const std::size_t k1 = std::min(K, (blk + 1) * kInstantsPerBlock);
      for (std::size_t k = blk * kInstantsPerBlock; k < k1; ++k) {
        recs.clear();
        found.clear();
        const std::size_t s = k / 2;
        qbuf.clear();
        for (int r : present) {
          const RobotSpec& spec = sc.robots[static_cast<std::size_t>(r)];
          const Path& p = *map.of[static_cast<std::size_t>(r)];
          if (k % 2 == 1 && s + 1 < p.size()) checkStep(spec, sc.resolution, r, p.at(s), p.at(s + 1), s, recs);
          if (k % 2 == 0 && s < p.size()) checker.checkJointLimits(r, p.at(s), static_cast<double>(s), found);
          qbuf.resize(qbuf.size() + static_cast<std::size_t>(spec.dim()));
        }
        const bool follows = have_last && last_k + 1 == k;
        for (std::size_t i = 0; i < present.size(); ++i) {
          const std::size_t r = static_cast<std::size_t>(present[i]);
          double* qi = qbuf.data() + offset[i];
          configurationAt(sc.robots[r], *map.of[r], k, qi);
          q[i] = qi;
          known[i] = follows && clean[i] &&
                     std::memcmp(qi, before.data() + offset[i], (offset[i + 1] - offset[i]) * sizeof(double)) == 0;
        }
        const std::size_t found_before = found.size();
        checker.checkGeometry(present, q, static_cast<double>(k) / 2.0, found, known);
        std::fill(clean.begin(), clean.end(), 1);
        for (std::size_t v = found_before; v < found.size(); ++v)
          if (found[v].type != Type::RobotRobot)
            clean[position[static_cast<std::size_t>(found[v].robots.front())]] = 0;
        before.swap(qbuf);
        last_k = k;
        have_last = true;
        for (Violation& v : found) {
          const int code = codeOf(v);
          const int b = code == kJointLimit ? v.joint : code == kObstacle ? v.obstacle
                                                      : code == kRobot    ? v.robots.back()
                                                                          : -1;
          recs.push_back({k, code, v.robots.front(), b, std::move(v)});
        }
        std::sort(recs.begin(), recs.end());
        out.count += recs.size();
        for (Record& rec : recs) {
          if (out.first.size() >= keep) break;
          out.first.push_back(std::move(rec));
        }
      }
    }
  };
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&] {
    try {
      checkBlocks();
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
      next = blocks;  // the others stop at their next block
    }
  };
  const std::size_t threads = std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()), blocks);
  std::vector<std::thread> pool;
  // A thread that cannot be started (no memory for its stack under a
  // memory limit) leaves its blocks to the others: the check still runs.
  try {
    for (std::size_t i = 1; i < threads; ++i) pool.emplace_back(worker);
  } catch (const std::system_error&) {
  }
  worker();
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);

  rep.violation_count = issues.size();
  for (auto& v : issues) {
    if (rep.violations.size() >= keep) break;
    rep.violations.push_back(std::move(v));
  }
  for (auto& blk : results) {
    rep.violation_count += blk.count;
    for (auto& rec : blk.first) {
      if (rep.violations.size() >= keep) break;
      rep.violations.push_back(std::move(rec.v));
    }
  }
  rep.valid = rep.violation_count == 0;
  return rep;
}

}  // namespace earc
