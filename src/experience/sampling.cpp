#include "earc/experience/sampling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "earc/util/random.hpp"

namespace earc::exp {

// The defaults are fitted to the subproblems ARC makes at 32 robots with
// obstacles: some robots of a 2-robot subproblem hardly move, and in 3- and
// 4-robot ones the robots pass beside their common centre, not through it.
// Drawn so, the database's keys lie nearer the subproblems planning meets
// (figures in docs/performance-log.md).
Query sampleMobileQuery(int robots, std::mt19937_64& rng, const QuerySampling& s) {
  Query q;
  constexpr double pi = std::numbers::pi;
  // A point uniform in the disc of radius r about the origin.
  auto inDisc = [&](double r) {
    const double d = r * std::sqrt(uniform(rng, 0, 1)), a = uniform(rng, -pi, pi);
    return std::array<double, 2>{d * std::cos(a), d * std::sin(a)};
  };
  const double spread = 1 + s.spread_per_robot * std::max(0, robots - 3);
  for (int i = 0; i < robots; ++i) {
    const double heading = uniform(rng, -pi, pi);
    if (uniform(rng, 0, 1) < s.rest_probability) {
      const auto p = inDisc(s.rest_radius * spread);
      q.starts.push_back({p[0], p[1], heading});
      q.goals.push_back(q.starts.back());
      continue;
    }
    const auto p = inDisc(s.pass_offset * spread);
    const double dir = uniform(rng, -pi, pi);
    const double before = uniform(rng, s.min_travel, s.max_travel * spread);
    const double after = uniform(rng, s.min_travel, s.max_travel * spread);
    const double turn = uniform(rng, -s.max_heading_change, s.max_heading_change);
    q.starts.push_back({p[0] - before * std::cos(dir), p[1] - before * std::sin(dir), heading});
    q.goals.push_back({p[0] + after * std::cos(dir), p[1] + after * std::sin(dir), geo::wrapAngle(heading + turn)});
  }
  return q;
}

// Uniform joints almost never bring two arms of the generated layouts
// together; these draws often do, so the database holds the close
// encounters planning meets (docs/performance-log.md).
Query sampleArmQuery(const RobotModel& a, const RobotModel& b, std::mt19937_64& rng, const QuerySampling& s) {
  Query q;
  const RobotModel* arms[2] = {&a, &b};
  for (int k = 0; k < 2; ++k) {
    const RobotSpec& me = arms[k]->spec();
    const geo::Vec2 to = arms[1 - k]->spec().base_position - me.base_position;
    const double toward = std::atan2(to.y, to.x) - me.base_angle;
    std::vector<double> lo, hi;
    arms[k]->samplingBounds(geo::Aabb{}, lo, hi);
    std::vector<double> start(lo.size()), goal(lo.size());
    for (std::size_t j = 0; j < lo.size(); ++j) {
      const double v = j == 0 ? geo::wrapAngle(toward + uniform(rng, -s.arm_toward_spread, s.arm_toward_spread))
                              : uniform(rng, -s.arm_joint_spread, s.arm_joint_spread);
      start[j] = std::clamp(v, lo[j], hi[j]);
      goal[j] = std::clamp(start[j] + uniform(rng, -s.max_joint_step, s.max_joint_step), lo[j], hi[j]);
    }
    q.starts.push_back(std::move(start));
    q.goals.push_back(std::move(goal));
  }
  return q;
}

Experience straightLineExperience(std::span<const RobotTraits> robots, const Query& query, int steps, Source source) {
  const Canonical c = canonicalize(robots, query.starts, query.goals);
  std::vector<Path> paths;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const auto& s = query.starts[r];
    const auto& g = query.goals[r];
    Path p(static_cast<int>(s.size()));
    std::vector<double> q(s.size());
    for (int t = 0; t < steps; ++t) {
      // Exactly the start at t = 0 and exactly the goal at the end.
      const double f = steps == 1 ? 0.0 : static_cast<double>(t) / (steps - 1);
      for (std::size_t d = 0; d < s.size(); ++d) q[d] = t == steps - 1 ? g[d] : s[d] + f * (g[d] - s[d]);
      p.push(q);
    }
    paths.push_back(std::move(p));
  }
  Experience e = canonicalExperience(c, paths);
  e.source = source;
  return e;
}

}  // namespace earc::exp
