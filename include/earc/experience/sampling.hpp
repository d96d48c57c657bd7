// Random subproblem queries shaped like the conflicts ARC turns into
// subproblems (paper, "Database Construction": short start-goal distances
// in a reduced region), shared by the database builder and the synthetic
// entries of the retrieval benchmark.
#pragma once

#include <random>
#include <vector>

#include "earc/experience/experience.hpp"
#include "earc/experience/keys.hpp"
#include "earc/scene/robot_model.hpp"

namespace earc::exp {

struct QuerySampling {
  // Mobile: each start lies this far from the conflict point (units) ...
  // ARC's local queries are path states a window (8 steps of 0.05, more
  // after expansions) before and after the conflict: 0.2-0.9 units away.
  double min_start_distance = 0.25;
  double max_start_distance = 0.9;
  // ... and turns at most this much from start to goal (radians; within a
  // window a robot turns little). Headings are uniform.
  double max_heading_change = 0.8;
  // ... and its goal roughly across it: the direction back through the
  // conflict point turned by at most this much (radians), at a distance
  // drawn from the same range, so the straight paths cross.
  double cross_jitter = 0.35;
  // Manipulators: the first joint points the arm towards the other arm's
  // base, give or take this much; the others bend at most this much; each
  // goal joint lies within max_joint_step of its start joint (radians).
  // Uniform joints almost never bring two arms of the generated layouts
  // together (0.1-0.4% of draws conflict); these draws do 4-13% of the
  // time for facing and neighbouring pairs, so the database holds the
  // close encounters planning meets.
  double arm_toward_spread = 1.0;
  double arm_joint_spread = 1.0;
  double max_joint_step = 0.6;
};

struct Query {
  std::vector<std::vector<double>> starts;
  std::vector<std::vector<double>> goals;
};

// Mobile robots around a conflict point at the origin; start headings
// uniform, goal headings within max_heading_change of them.
Query sampleMobileQuery(int robots, std::mt19937_64& rng, const QuerySampling& sampling = {});

// Two arms reaching towards each other (see QuerySampling), clamped to the
// joint limits (RobotModel sampling bounds).
Query sampleArmQuery(const RobotModel& a, const RobotModel& b, std::mt19937_64& rng,
                     const QuerySampling& sampling = {});

// A stored-form experience whose paths are straight lines of `steps`
// states from the starts to the goals (no collision checking): synthetic
// entries for benchmarks and tests.
Experience straightLineExperience(std::span<const RobotTraits> robots, const Query& query, int steps,
                                  Source source = Source::Build);

}  // namespace earc::exp
