// The report's files: CSV of trials and databases, and OMPL benchmark logs.
#include "earc/bench/report.hpp"

#include <ompl/base/PlannerStatus.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <ostream>

#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/format.hpp"
#include "earc/util/hash.hpp"
#include "report_util.hpp"

namespace earc::bench {

using report_detail::methodLabels;
using report_detail::methodRank;
using report_detail::opt;
using report_detail::suiteRank;

namespace {

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// A suite name as part of a file name. The names come from the results
// database, which anyone can edit: characters outside [A-Za-z0-9._-] (a
// '/' above all) and a leading '.' become '_', so that a name like
// "../../x" can never write outside the directory or hide its file; a name
// that had to change gets a hash of itself, so that two odd names never
// share (and overwrite) one file. The suites' own names pass unchanged.
std::string fileNamePart(const std::string& name) {
  std::string safe = name;
  for (char& c : safe)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  if (!safe.empty() && safe[0] == '.') safe[0] = '_';
  if (safe == name && !safe.empty()) return safe;
  char hash[24];
  std::snprintf(hash, sizeof hash, "-%08llx", static_cast<unsigned long long>(fnv1a64(name) & 0xffffffffULL));
  return safe + hash;
}

// OMPL's PlannerStatus for a trial: what ompl_benchmark_statistics.py
// tabulates as the "status" enum.
int omplStatus(const TrialRecord& t) {
  using S = ompl::base::PlannerStatus;
  if (t.success) return S::EXACT_SOLUTION;
  if (t.term_signal && t.failure.rfind("killed at", 0) != 0) return S::CRASH;
  if (t.failure.find("time_limit") != std::string::npos || t.failure.rfind("killed at", 0) == 0 ||
      t.failure.rfind("solved after", 0) == 0)
    return S::TIMEOUT;
  if (t.failure.find("invalid_input") != std::string::npos) return S::INVALID_START;
  return S::ABORT;
}

std::string hostName() {
  char buf[256] = {0};
  if (gethostname(buf, sizeof buf - 1) != 0) return "UNKNOWN";
  return buf;
}

}  // namespace

// One row per trial, RFC 4180 quoting, a header line first: the columns
// of the trials table but its id, each version's added last (so that a
// script that reads the first columns by position reads them still);
// planner_args as plannerArgsText writes them, learn as 1 or 0, and ""
// for what a trial does not record (NULL).
void writeCsv(const std::vector<TrialRecord>& trials, std::ostream& out) {
  out << "suite,robots,method,trial,seed,time_limit_s,scenario_seed,planner_seed,success,planning_time_s,"
         "wall_time_s,makespan,sum_of_costs,conflicts,db_hits,peak_memory_kb,exit_status,term_signal,failure,"
         "finished_at,jobs,planner_version,bench_version,planner_args,scenario_file,lightning_problems,"
         "lightning_problems_per_robot,lightning_problem_time_limit_s,learn,earc_db,earc_db_state,lower_bound,"
         "refine_first_time_s,refine_first_sum_of_costs,refine_final_sum_of_costs,refine_final_makespan\n";
  for (const auto& t : trials) {
    const std::optional<LightningSettings>& l = t.lightning;
    out << csvField(t.suite) << ',' << t.robots << ',' << csvField(t.method) << ',' << t.trial << ',' << t.seed
        << ',' << opt(std::optional<double>(t.time_limit_s)) << ',' << t.scenario_seed << ',' << t.planner_seed
        << ',' << (t.success ? 1 : 0) << ',' << opt(t.planning_time_s) << ','
        << opt(std::optional<double>(t.wall_time_s)) << ',' << opt(t.makespan) << ',' << opt(t.sum_of_costs) << ','
        << opt(t.conflicts) << ',' << opt(t.db_hits) << ',' << opt(t.peak_memory_kb) << ',' << opt(t.exit_status)
        << ',' << opt(t.term_signal) << ',' << csvField(t.failure) << ',' << t.finished_at << ',' << opt(t.jobs)
        << ',' << csvField(t.planner_version) << ',' << csvField(t.bench_version) << ','
        << csvField(plannerArgsText(t.planner_args)) << ',' << csvField(t.scenario_file) << ','
        << opt(l ? l->problems : std::nullopt) << ',' << opt(l ? l->problems_per_robot : std::nullopt) << ','
        << opt(l ? std::optional<double>(l->problem_time_limit_s) : std::nullopt) << ','
        << opt(t.learn) << ',' << csvField(t.earc_db) << ','
        << opt(t.earc_db_state) << ',' << opt(t.lower_bound) << ',' << opt(t.refine_first_time_s) << ','
        << opt(t.refine_first_sum_of_costs) << ',' << opt(t.refine_final_sum_of_costs) << ','
        << opt(t.refine_final_makespan) << "\n";
  }
}

void writeDatabasesCsv(const std::vector<DatabaseRecord>& databases, std::ostream& out) {
  out << "method,suite,robots,path,construction_time_s,entries,size_bytes,problems,seed,recorded_at\n";
  for (const auto& d : databases)
    out << csvField(d.method) << ',' << csvField(d.suite) << ',' << d.robots << ',' << csvField(d.path) << ','
        << opt(d.construction_time_s) << ',' << opt(d.entries) << ',' << opt(d.size_bytes) << ',' << opt(d.problems)
        << ',' << opt(d.seed) << ',' << d.recorded_at << "\n";
}

namespace {

// One OMPL log: its name (without ".log") and its trials.
struct OmplExperiment {
  std::string name;
  std::vector<const TrialRecord*> runs;
};

// The logs' experiments in the order they are written: (suite's rank,
// suite, robots, time limit).
std::map<std::tuple<int, std::string, int, double>, OmplExperiment> omplExperiments(
    const std::vector<TrialRecord>& trials) {
  std::map<std::tuple<int, std::string, int, double>, OmplExperiment> experiments;
  std::map<std::pair<std::string, int>, std::set<double>> limits;
  for (const auto& t : trials) {
    experiments[{suiteRank(t.suite), t.suite, t.robots, t.time_limit_s}].runs.push_back(&t);
    limits[{t.suite, t.robots}].insert(t.time_limit_s);
  }
  for (auto& [key, e] : experiments) {
    const auto& [rank, suite, robots, limit] = key;
    e.name = fileNamePart(suite) + "-" + std::to_string(robots);
    if (limits[{suite, robots}].size() > 1) e.name += "-tl" + formatNumber("%g", limit);
  }
  return experiments;
}

}  // namespace

std::vector<std::string> omplLogFiles(const std::vector<TrialRecord>& trials, const std::string& dir) {
  std::vector<std::string> files;
  for (const auto& [key, e] : omplExperiments(trials)) files.push_back(dir + "/" + e.name + ".log");
  return files;
}

// One log per (suite, robots, time limit) experiment, planners = methods
// (named as markdownTable names them),
// into dir (created), named SUITE-ROBOTS.log (SUITE-ROBOTS-tlLIMIT.log
// where a cell has several limits). A suite name with characters outside
// [A-Za-z0-9._-] or a leading '.' is made safe (those become '_', plus a
// hash of the name): no file is ever written outside dir. Returns the
// files written.
std::vector<std::string> writeOmplLogs(const std::vector<TrialRecord>& trials, const std::string& dir) {
  std::filesystem::create_directories(dir);
  // Run properties: "name TYPE", as Benchmark::saveResultsToStream writes
  // them, in sorted order.
  const std::vector<std::string> props = {
      "conflicts INTEGER", "database hits INTEGER", "makespan INTEGER", "memory REAL",   "solved BOOLEAN",
      "status ENUM",       "sum of costs INTEGER",  "time REAL",        "trial INTEGER", "wall time REAL"};
  std::vector<std::string> files;
  const auto labels = methodLabels(trials);
  for (const auto& [key, experiment] : omplExperiments(trials)) {
    const auto& [rank, suite, robots, limit] = key;
    const auto& [name, runs] = experiment;
    const std::string path = dir + "/" + name + ".log";
    std::map<std::string, std::vector<const TrialRecord*>> by_method;
    std::set<std::uint64_t> seeds;
    double total = 0, memory_mb = 0;
    std::string first;
    for (const TrialRecord* t : runs) {
      by_method[t->method].push_back(t);
      seeds.insert(t->seed);
      total += t->wall_time_s;
      if (first.empty() || t->finished_at < first) first = t->finished_at;
    }
    std::size_t most = 0;
    for (const auto& [m, list] : by_method) most = std::max(most, list.size());
    std::vector<std::string> methods;
    for (const auto& [m, list] : by_method) methods.push_back(m);
    std::sort(methods.begin(), methods.end(),
              [](const std::string& a, const std::string& b) { return std::make_pair(methodRank(a), a) < std::make_pair(methodRank(b), b); });
    std::ostringstream o;
    o << "earc-bench version 1\n";
    o << "Experiment " << name << "\n";
    o << "3 experiment properties\n";
    o << "suite TEXT = " << oneLine(suite) << "\n";
    o << "robots INTEGER = " << robots << "\n";
    o << "run_seeds TEXT = ";
    for (auto it = seeds.begin(); it != seeds.end(); ++it) o << (it == seeds.begin() ? "" : "+") << *it;
    o << "\n";
    o << "Running on " << hostName() << "\n";
    o << "Starting at " << (first.empty() ? "UNKNOWN" : first) << "\n";
    o << "<<<|\nearc-bench: scenarios of suite " << oneLine(suite) << " with " << robots
      << " robots; each method planned each scenario once in its own process\n|>>>\n";
    o << "<<<|\n|>>>\n";
    o << (seeds.empty() ? 0 : *seeds.begin()) << " is the random seed\n";
    o << limit << " seconds per run\n";
    o << memory_mb << " MB per run\n";
    o << most << " runs per planner\n";
    o << total << " seconds spent to collect the data\n";
    o << "1 enum type\nstatus";
    for (int i = 0; i < ompl::base::PlannerStatus::TYPE_COUNT; ++i)
      o << '|' << ompl::base::PlannerStatus(static_cast<ompl::base::PlannerStatus::StatusType>(i)).asString();
    o << "\n" << methods.size() << " planners\n";
    for (const std::string& m : methods) {
      o << oneLine(labels.at(m)) << "\n0 common properties\n" << props.size() << " properties for each run\n";
      for (const auto& p : props) o << p << "\n";
      auto list = by_method[m];
      std::sort(list.begin(), list.end(), [](const TrialRecord* a, const TrialRecord* b) { return a->trial < b->trial; });
      o << list.size() << " runs\n";
      for (const TrialRecord* t : list) {
        const double time = t->planning_time_s ? *t->planning_time_s : t->wall_time_s;
        const std::string mem = t->peak_memory_kb ? formatNumber("%.3f", static_cast<double>(*t->peak_memory_kb) / 1024.0) : "";
        o << opt(t->conflicts) << "; " << opt(t->db_hits) << "; " << opt(t->makespan) << "; " << mem << "; "
          << (t->success ? 1 : 0) << "; " << omplStatus(*t) << "; " << opt(t->sum_of_costs) << "; "
          << opt(std::optional<double>(time)) << "; " << t->trial << "; " << opt(std::optional<double>(t->wall_time_s))
          << "; \n";
      }
      o << ".\n";
    }
    writeTextFileAtomic(path, o.str());
    files.push_back(path);
  }
  return files;
}

}  // namespace earc::bench
