// Reading results back: summary statistics per cell, the markdown table,
// CSV, and OMPL benchmark logs (the text format of
// ompl::tools::Benchmark::saveResultsToStream, which
// ompl_benchmark_statistics.py and Planner Arena read).
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "earc/bench/results_db.hpp"

namespace earc::bench {

// Quantile q in [0, 1] of values, linear between order statistics (numpy's
// default); nullopt for no values.
std::optional<double> quantile(std::vector<double> values, double q);

// A 95% bootstrap interval (percentile method, 2,000 resamples seeded with
// `seed`) of a statistic of n > 0 paired items; `statistic` gets a resample's indices.
std::pair<double, double> bootstrapInterval(std::size_t n,
                                            const std::function<double(const std::vector<std::size_t>&)>& statistic,
                                            std::uint64_t seed);
// The same for the median of `values`, resampling the values themselves.
std::pair<double, double> medianInterval(const std::vector<double>& values, std::uint64_t seed);

struct TrialFilter {
  std::optional<std::uint64_t> seed;
  std::optional<double> time_limit_s;
  bool matches(const TrialRecord& t) const;
  std::vector<TrialRecord> apply(std::vector<TrialRecord> trials) const;
  // The matching trials; when there are trials and none matches, an
  // InputError naming `results` and the option, with the values its
  // trials have (an empty table would not say the filter was mistyped).
  std::vector<TrialRecord> applyRequired(std::vector<TrialRecord> trials, const std::string& results) const;
};

// One (suite, robots, method, time limit) cell. Trials under another time
// limit are another experiment (what one leaves unsolved another may
// solve), as they are another OMPL log, so they never share a cell.
struct CellSummary {
  std::string suite;
  int robots = 0;
  std::string method;
  double time_limit_s = 0;
  int trials = 0;
  int solved = 0;
  std::optional<double> median_s, q1_s, q3_s;  // planning time of solved trials
};

// Cells in suite order (allSuites), then time limit, then robots, then
// method (allMethods); unknown suites and methods after the known ones,
// alphabetically.
std::vector<CellSummary> summarize(const std::vector<TrialRecord>& trials);

// Method a against b on the scenarios both solved (within time_limit_s when
// given): the median of per-scenario time ratios and the ratio of medians.
struct PairedRatio {
  int pairs = 0;
  std::optional<double> median;
  std::optional<double> of_medians;
  // 95% bootstrap intervals of both, resampling the pairs (bootstrapInterval
  // with a fixed seed: the table is the same every time it is printed).
  std::optional<std::pair<double, double>> median_interval, of_medians_interval;
  // Plan length on the same pairs (those whose trials both have one): a
  // faster method may plan longer paths.
  std::optional<double> makespan_a, makespan_b;
};
PairedRatio pairedRatio(const std::vector<TrialRecord>& trials, const std::string& suite, int robots,
                        const std::string& a, const std::string& b,
                        std::optional<double> time_limit_s = std::nullopt);

// How many trials ran at once, in one line for under a table: "Trials ran
// one at a time." / "Trials ran 2 at a time (--jobs 2)." / the mix, and
// how many trials did not record it (results from before schema 2).
std::string jobsNote(const std::vector<TrialRecord>& trials);

// Which builds planned the trials (TrialRecord::planner_version), in one
// line: "Planned by earc 0.1.0+HASH." / "Planned by 2 builds: earc A
// (N trials), earc B (M trials): ..." / how many trials did not record it.
std::string versionNote(const std::vector<TrialRecord>& trials);

// Which builds of earc-bench ran and timed the trials
// (TrialRecord::bench_version), the same way: "Timed by earc-bench
// 0.1.0+HASH." / ... / how many did not record it (before schema 4).
std::string benchNote(const std::vector<TrialRecord>& trials);

// What goes under a table: jobsNote, versionNote and benchNote, a line each, after a
// blank line; "(no trials)" when there are none.
std::string trialsNotes(const std::vector<TrialRecord>& trials);

// Markdown: per suite (and time limit) a table of success rate and median
// planning time per robot count and method, the E-ARC/ARC paired ratio, then
// the databases, then trialsNotes.
std::string markdownTable(const std::vector<TrialRecord>& trials, const std::vector<DatabaseRecord>& databases);

// The same laid out like the paper's figures: a table per suite, a row per
// robot count, a column per method, then E-ARC over ARC and its hit rate.
std::string markdownWideTable(const std::vector<TrialRecord>& trials);

// One CSV row per trial (RFC 4180), a header line first: the trials table's
// columns but its id, each schema version's added last; NULL as "".
void writeCsv(const std::vector<TrialRecord>& trials, std::ostream& out);
void writeDatabasesCsv(const std::vector<DatabaseRecord>& databases, std::ostream& out);

// One OMPL benchmark log per (suite, robots, time limit) into dir (created),
// SUITE-ROBOTS[-tlLIMIT].log, never outside dir. Returns the files written.
std::vector<std::string> writeOmplLogs(const std::vector<TrialRecord>& trials, const std::string& dir);
// The files writeOmplLogs(trials, dir) would write, in its order.
std::vector<std::string> omplLogFiles(const std::vector<TrialRecord>& trials, const std::string& dir);

}  // namespace earc::bench
