// Helpers shared by the report's parts (report.cpp, report_stats.cpp,
// report_files.cpp). Internal to src/bench.
#pragma once

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "earc/bench/options.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/bench/suites.hpp"

namespace earc::bench::report_detail {

inline int suiteRank(const std::string& s) {
  const auto& all = allSuites();
  for (std::size_t i = 0; i < all.size(); ++i)
    if (all[i].name == s) return static_cast<int>(i);
  return static_cast<int>(all.size());
}

inline int methodRank(const std::string& m) {
  const auto& all = allMethods();
  auto it = std::find(all.begin(), all.end(), m);
  return static_cast<int>(it - all.begin());
}

// What tables and OMPL logs call each method of the trials: its name and its
// planner arguments, if any ("earc --db-k=5"); "earc (several sets of planner
// arguments)" when its trials mix several, as no results file does.
inline std::map<std::string, std::string> methodLabels(const std::vector<TrialRecord>& trials) {
  std::map<std::string, const std::vector<std::string>*> args;
  std::map<std::string, std::string> labels;
  for (const TrialRecord& t : trials) {
    const auto [it, inserted] = args.emplace(t.method, &t.planner_args);
    if (inserted)
      labels[t.method] = t.planner_args.empty() ? t.method : t.method + " " + plannerArgsText(t.planner_args);
    else if (*it->second != t.planner_args)
      labels[t.method] = t.method + " (several sets of planner arguments)";
  }
  return labels;
}

template <class T>
inline std::string opt(const std::optional<T>& v) {
  if (!v) return "";
  std::ostringstream s;
  s.precision(10);
  s << *v;
  return s.str();
}

}  // namespace earc::bench::report_detail
