// `earc-bench compare`: one planner build (or set of options) against
// another on the same scenarios, to say whether a change made planning
// faster and whether it changed the plans. The two run one plan at a time,
// interleaved plan by plan, the order alternating, each E-ARC or Lightning
// plan on a fresh copy of the same database; every solved plan is checked
// by the validator; each pair of plans is compared path by path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace earc::bench {

struct CompareOptions {
  std::string old_program;                    // an earc-plan
  std::string new_program;                    // empty: earc-plan next to earc-bench
  std::vector<std::string> old_args, new_args;  // appended to each side's `plan` command (plannerArgsProblem)
  // Scenario files; empty: `trials` scenarios of (suite, robots) generated
  // from `seed` exactly as `earc-bench run` makes them.
  std::vector<std::string> scenarios;
  std::string suite = "mobile-obst";
  int robots = 32;
  int trials = 20;
  std::string method = "arc";
  std::string old_method, new_method;  // one side's method; empty: `method`
  std::string db;             // earc and lightning: copied afresh for every plan
  double time_limit_s = 20.0;
  std::uint64_t seed = 1;
  int repeats = 1;            // plans per scenario and side; the median counts
  std::string work_dir = "compare.work";
  std::string csv;            // one row per plan pair
  std::string picture;        // .svg or .png: new against old, one point per scenario
  std::size_t memory_limit_mb = 4096;
  bool verbose = false;       // one line per scenario
  std::string validator;      // empty: earc-plan next to earc-bench
};

// One plan of one side.
struct ComparePlan {
  bool solved = false;            // solved and valid
  std::optional<double> time_s;   // planning_time_s, when solved
  std::optional<double> makespan, sum_of_costs;  // the solution's stats, when solved
  std::string failure;            // why not solved ("" when solved)
  bool invalid = false;           // solved, but the validator refused it
  std::string version;            // the build that planned it (plannerVersion), "" unknown
  bool refused = false;           // refusedItsCommand: refused its options or database, not the scenario
  bool silent = false;            // exit status 0 without a readable solution: not an earc-plan
};

struct ComparePair {
  std::string scenario;  // its name
  int repeat = 0;
  ComparePlan old_plan, new_plan;
  bool same_paths = false;  // both solved with identical paths
};

struct CompareStats {
  int scenarios = 0;
  int plans = 0;                  // pairs of plans
  int old_solved = 0, new_solved = 0;  // plans
  int invalid = 0;                // plans the validator refused (either side)
  int paired = 0;                 // scenarios both sides solved (in every repeat)
  int same_paths = 0;             // plan pairs with identical paths
  // Over the paired scenarios, each side's time being its median over
  // the repeats:
  std::optional<double> old_median_s, new_median_s;
  std::optional<double> of_medians;   // new median / old median
  std::optional<double> paired_median;  // median of per-scenario new / old
  std::optional<double> paired_lo, paired_hi;  // 95% bootstrap interval of it
  // What the plans are like, over the same scenarios (each side's median
  // over the repeats, then the median over the scenarios): a change that
  // alters the plans may trade time for longer ones.
  std::optional<double> old_makespan, new_makespan, old_sum_of_costs, new_sum_of_costs;
};

// The statistics of a comparison; the bootstrap resamples scenarios with
// a generator seeded by `seed`, so the interval is reproducible.
CompareStats compareStats(const std::vector<ComparePair>& pairs, std::uint64_t seed);

// A log-log scatter plot (SVG) of old time against new time per scenario,
// with new = old and the median ratio; hollow points: the plans differed.
// heading: lines above the plot, the first its title.
std::string compareSvg(const std::vector<ComparePair>& pairs, const CompareStats& stats,
                       const std::vector<std::string>& heading);

struct CompareSummary {
  CompareStats stats;
  std::vector<ComparePair> pairs;
  bool interrupted = false;
};

// Runs the comparison, writing the summary (verbose: a line per scenario)
// on `log`. Throws InputError for bad options before any plan runs.
// SIGINT or SIGTERM stop it early (CompareSummary::interrupted).
CompareSummary runCompare(const CompareOptions& options, std::ostream& log);

}  // namespace earc::bench
