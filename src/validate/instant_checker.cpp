// The contract's rules at one instant, with check_solution.py's reporting:
// one violation per (kind, robot[, obstacle | other robot]), carrying the
// worst overlap or excess among the robot's body parts.
#include <algorithm>
#include <cstdio>

#include "earc/collision/collision_world.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/format.hpp"
#include "earc/validate/validator.hpp"

namespace earc {
namespace {

// " (link 3)"-style naming of an arm's body part; nothing for a mobile robot.
std::string linkSuffix(const RobotModel& m, std::size_t part, const char* before, const char* after) {
  if (m.isMobile()) return "";
  return before + std::to_string(part + 1) + after;
}

const char* obstacleKind(const Obstacle& o) { return o.type == Obstacle::Type::Box ? "box" : "circle"; }

// Per-thread buffers: validating a long solution calls checkGeometry for
// every instant.
struct Scratch {
  std::vector<std::vector<geo::Body>> parts;  // per robot of the call
  std::vector<geo::Aabb> bounds;              // of one robot's parts
  std::vector<int> touched;
  struct Hit {
    int obstacle;
    std::size_t part;
    double sd;
  };
  std::vector<Hit> hits;
  struct Disc {
    double lo, hi;
    geo::Vec2 c;
    double r;
    std::size_t pos;
  };
  std::vector<Disc> discs;
  std::vector<std::size_t> order;  // the discs' order by lo at the last call
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
};

// Sorts discs by lo. They come in the order of the thread's last instant,
// where most robots were where they are now or one step away: insertion
// sort does that in about linear time; a list far from sorted (a new block
// of instants) goes to std::sort once the moves pass a few per disc.
void sortByLo(std::vector<Scratch::Disc>& discs) {
  std::size_t budget = 8 * discs.size() + 64;
  for (std::size_t i = 1; i < discs.size(); ++i) {
    const Scratch::Disc d = discs[i];
    std::size_t j = i;
    for (; j > 0 && discs[j - 1].lo > d.lo && budget > 0; --j, --budget) discs[j] = discs[j - 1];
    discs[j] = d;
    if (budget == 0) {
      std::sort(discs.begin(), discs.end(), [](const Scratch::Disc& a, const Scratch::Disc& b) { return a.lo < b.lo; });
      return;
    }
  }
}

}  // namespace

struct InstantChecker::Impl {
  explicit Impl(const Scenario& s) : world(s), models(makeRobotModels(s)) {}
  CollisionWorld world;
  std::vector<std::shared_ptr<const RobotModel>> models;
};

InstantChecker::InstantChecker(const Scenario& scenario)
    : scenario_(scenario), impl_(std::make_unique<Impl>(scenario)) {}

InstantChecker::~InstantChecker() = default;

void InstantChecker::checkJointLimits(int robot, const double* q, double t, std::vector<Violation>& out) const {
  const RobotSpec& spec = scenario_.robots[static_cast<std::size_t>(robot)];
  if (spec.kind != RobotKind::Manipulator) return;
  for (std::size_t j = 0; j < spec.joint_limits.size(); ++j) {
    const auto [lo, hi] = spec.joint_limits[j];
    if (q[j] < lo - geo::kContactTolerance || q[j] > hi + geo::kContactTolerance)
      out.push_back({Violation::Type::JointLimit, t, {robot},
                     spec.name + " joint " + std::to_string(j + 1) + " = " + formatNumber(q[j]) +
                         " outside its limits [" + formatNumber(lo) + ", " + formatNumber(hi) + "]",
                     -1, static_cast<int>(j), q[j]});
  }
}

// robots[i] (scenario indices, ascending) is at configuration q[i].
// Appends, with time t: per robot one Workspace, one Obstacle per touched
// obstacle and one SelfCollision violation; then one RobotRobot per
// touching pair (robots ascending).
void InstantChecker::checkGeometry(std::span<const int> robots, std::span<const double* const> q, double t,
                                   std::vector<Violation>& out, std::span<const char> clean) const {
  thread_local Scratch s;
  const std::size_t n = robots.size();
  auto model = [&](std::size_t pos) -> const RobotModel& { return *impl_->models[static_cast<std::size_t>(robots[pos])]; };
  auto name = [&](std::size_t pos) -> const std::string& { return scenario_.robots[static_cast<std::size_t>(robots[pos])].name; };
  if (s.parts.size() < n) s.parts.resize(n);
  // A robot known clean has no parts to check alone: the checks below
  // find nothing in an empty list.
  for (std::size_t pos = 0; pos < n; ++pos) {
    if (pos < clean.size() && clean[pos])
      s.parts[pos].clear();
    else
      model(pos).bodies(q[pos], s.parts[pos]);
  }

  // Workspace: the part sticking out most.
  for (std::size_t pos = 0; pos < n; ++pos) {
    const auto& parts = s.parts[pos];
    double worst = -1.0;
    std::size_t worst_part = 0;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const double e = geo::excessOutside(parts[i], impl_->world.workspace());
      if (e > worst) worst = e, worst_part = i;
    }
    if (worst > geo::kContactTolerance)
      out.push_back({Violation::Type::Workspace, t, {robots[pos]},
                     name(pos) + linkSuffix(model(pos), worst_part, " (link ", ")") +
                         " is outside the workspace by " + formatNumber(worst),
                     -1, -1, worst});
  }

  // Obstacles: one violation per touched obstacle, at its deepest part.
  for (std::size_t pos = 0; pos < n; ++pos) {
    const auto& parts = s.parts[pos];
    s.hits.clear();
    for (std::size_t i = 0; i < parts.size(); ++i) {
      s.touched.clear();
      impl_->world.touchedObstacles(parts[i], s.touched);
      for (int o : s.touched)
        s.hits.push_back({o, i, geo::signedDistance(parts[i], impl_->world.obstacle(static_cast<std::size_t>(o)))});
    }
    std::sort(s.hits.begin(), s.hits.end(), [](const Scratch::Hit& a, const Scratch::Hit& b) {
      return a.obstacle != b.obstacle ? a.obstacle < b.obstacle : a.sd < b.sd;
    });
    for (std::size_t h = 0; h < s.hits.size(); ++h) {
      if (h > 0 && s.hits[h].obstacle == s.hits[h - 1].obstacle) continue;
      const auto& hit = s.hits[h];
      out.push_back({Violation::Type::Obstacle, t, {robots[pos]},
                     name(pos) + linkSuffix(model(pos), hit.part, " link ", "") + " overlaps obstacle #" +
                         std::to_string(hit.obstacle) + " (" +
                         obstacleKind(scenario_.obstacles[static_cast<std::size_t>(hit.obstacle)]) + ") by " +
                         formatNumber(-hit.sd),
                     hit.obstacle, -1, -hit.sd});
    }
  }

  // Self-collision: links that share a joint never count.
  // The parts' bounds are made once: an arm of a thousand links has half
  // a million pairs, and making them per pair was most of its validation.
  for (std::size_t pos = 0; pos < n; ++pos) {
    const auto& parts = s.parts[pos];
    double worst = 0.0;
    std::size_t wa = 0, wb = 0;
    s.bounds.resize(parts.size());
    for (std::size_t i = 0; i < parts.size(); ++i) s.bounds[i] = geo::bounds(parts[i]);
    for (std::size_t i = 0; i + 2 < parts.size(); ++i)
      for (std::size_t j = i + 2; j < parts.size(); ++j)
        if (s.bounds[i].overlaps(s.bounds[j]) && geo::touches(parts[i], parts[j])) {
          const double overlap = -geo::signedDistance(parts[i], parts[j]);
          if (overlap > worst) worst = overlap, wa = i, wb = j;
        }
    if (worst > 0.0)
      out.push_back({Violation::Type::SelfCollision, t, {robots[pos]},
                     name(pos) + " links " + std::to_string(wa + 1) + " and " + std::to_string(wb + 1) +
                         " overlap by " + formatNumber(worst) + " (self-collision)",
                     -1, -1, worst});
  }

  // Robot-robot: sort and sweep the bounding discs along x, then the exact test.
  if (s.order.size() != n) {
    s.order.resize(n);
    for (std::size_t pos = 0; pos < n; ++pos) s.order[pos] = pos;
  }
  s.discs.clear();
  for (const std::size_t pos : s.order) {
    const geo::Vec2 c = model(pos).boundingCenter(q[pos]);
    const double r = model(pos).boundingRadius();
    s.discs.push_back({c.x - r, c.x + r, c, r, pos});
  }
  sortByLo(s.discs);
  for (std::size_t i = 0; i < n; ++i) s.order[i] = s.discs[i].pos;
  s.pairs.clear();
  for (std::size_t i = 0; i < s.discs.size(); ++i)
    for (std::size_t j = i + 1; j < s.discs.size() && s.discs[j].lo <= s.discs[i].hi; ++j) {
      const auto& a = s.discs[i];
      const auto& b = s.discs[j];
      // Squared: discs this close to meeting touch by no more than rounding,
      // which robotsTouch's tolerance does not count.
      const geo::Vec2 d = a.c - b.c;
      if (geo::dot(d, d) > (a.r + b.r) * (a.r + b.r)) continue;
      const std::size_t pa = std::min(a.pos, b.pos), pb = std::max(a.pos, b.pos);
      if (robotsTouch(model(pa), q[pa], model(pb), q[pb])) s.pairs.emplace_back(pa, pb);
    }
  std::sort(s.pairs.begin(), s.pairs.end());
  for (auto [pa, pb] : s.pairs) {
    const double overlap = -robotDistance(model(pa), q[pa], model(pb), q[pb]);
    out.push_back({Violation::Type::RobotRobot, t, {robots[pa], robots[pb]},
                   name(pa) + " overlaps " + name(pb) + " by " + formatNumber(overlap), -1, -1, overlap});
  }
}

}  // namespace earc
