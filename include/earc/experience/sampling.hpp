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
  // Mobile robots: each rests (start = goal) or passes in a straight line
  // through a point within pass_offset of the conflict point, from
  // min_travel-max_travel before it to as far after it.
  double rest_probability = 0.15;
  double rest_radius = 0.8;  // a resting robot lies within this of the conflict point
  double pass_offset = 0.5;
  double min_travel = 0.1;
  double max_travel = 0.8;
  // Those distances grow by this fraction for each robot beyond three:
  // four robots so close together rarely find room.
  double spread_per_robot = 0.25;
  // A robot's heading is uniform and turns at most this much from start
  // to goal (radians; within a window a robot turns little).
  double max_heading_change = 0.8;
  // Arms (radians): the first joint points towards the other arm's base
  // within arm_toward_spread, the others bend at most arm_joint_spread, a
  // goal joint lies within max_joint_step of its start.
  double arm_toward_spread = 1.0;
  double arm_joint_spread = 1.0;
  double max_joint_step = 0.6;
};

struct Query {
  std::vector<std::vector<double>> starts;
  std::vector<std::vector<double>> goals;
};

// Mobile robots around a conflict point at the origin (QuerySampling):
// each rests or passes by it.
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
