#include "earc/bench/crowds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/suites.hpp"
#include "earc/util/format.hpp"

namespace earc::bench {

namespace {

std::optional<std::int64_t> count(const nlohmann::json& o, const char* key) {
  const auto v = o.find(key);
  // JSON's whole numbers of 0 and more are read as unsigned.
  if (v != o.end() && v->is_number_unsigned() &&
      v->get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    return v->get<std::int64_t>();
  return std::nullopt;
}

std::optional<double> seconds(const nlohmann::json& o, const char* key) {
  const auto v = o.find(key);
  if (v != o.end() && v->is_number() && std::isfinite(v->get<double>()) && v->get<double>() >= 0)
    return v->get<double>();
  return std::nullopt;
}

const Suite* crowdSuite(const std::string& name) {
  for (const Suite& s : allSuites())
    if (s.name == name && s.crowd()) return &s;
  return nullptr;
}

std::string median(std::vector<double> v, const char* format) {
  const auto m = quantile(std::move(v), 0.5);
  return m ? formatNumber(format, *m) : "-";
}

}  // namespace

void readRefineStats(const nlohmann::json& stats, TrialRecord& t) {
  const auto r = stats.find("refine");
  if (r == stats.end() || !r->is_object()) return;
  t.refine_first_time_s = seconds(*r, "first_s");
  t.refine_first_sum_of_costs = count(*r, "first_sum_of_costs");
  t.refine_final_sum_of_costs = count(*r, "final_sum_of_costs");
  t.refine_final_makespan = count(*r, "final_makespan");
  // The paper's suites have no bound of their own: the robots' own
  // shortest ways that refinement computed.
  if (!t.lower_bound) t.lower_bound = count(*r, "lower_bound");
}

// Columns: solved/trials, median time to the first solution, median sum
// of costs and makespan of the first plan, the bound, median sum of costs
// over it, and where trials refined the refined sum of costs and ratio.
std::string crowdTable(const std::vector<TrialRecord>& trials) {
  // (suite's rank, time limit, robots, method's rank) -> the cell's trials.
  using Key = std::tuple<std::size_t, double, int, std::size_t, std::string>;
  std::map<Key, std::vector<const TrialRecord*>> cells;
  std::map<std::string, std::set<double>> limits;
  const auto& suites = allSuites();
  const auto& methods = allMethods();
  for (const TrialRecord& t : trials) {
    if (!crowdSuite(t.suite)) continue;
    const auto s = std::find_if(suites.begin(), suites.end(), [&](const Suite& x) { return x.name == t.suite; });
    const auto m = std::find(methods.begin(), methods.end(), t.method);
    cells[{static_cast<std::size_t>(s - suites.begin()), t.time_limit_s, t.robots,
           static_cast<std::size_t>(m - methods.begin()), t.method}]
        .push_back(&t);
    limits[t.suite].insert(t.time_limit_s);
  }
  if (cells.empty()) return "";
  std::ostringstream out;
  std::string heading;
  bool refined_any = false;
  for (const auto& [key, cell] : cells)
    for (const TrialRecord* t : cell) refined_any = refined_any || t->refine_final_sum_of_costs.has_value();
  for (const auto& [key, cell] : cells) {
    const TrialRecord& first = *cell.front();
    const Suite& suite = *crowdSuite(first.suite);
    std::string h = suite.name + " (" + suite.scen + ".scen)";
    if (limits[suite.name].size() > 1) h += ", time limit " + formatNumber("%g", first.time_limit_s) + " s";
    if (h != heading) {
      heading = h;
      out << "\n### Crowds: " << heading << "\n\n"
          << "| robots | method | solved | time to first solution (s) | sum of costs | makespan | lower bound | "
             "sum of costs / lower bound |"
          << (refined_any ? " refined sum of costs | refined / lower bound |" : "") << "\n"
          << "|---:|:---|---:|---:|---:|---:|---:|---:|" << (refined_any ? "---:|---:|" : "") << "\n";
    }
    std::vector<double> time, soc, makespan, ratio, refined, refined_ratio;
    std::optional<std::int64_t> bound;
    int solved = 0;
    for (const TrialRecord* t : cell) {
      if (t->lower_bound) bound = t->lower_bound;
      if (!t->success) continue;
      ++solved;
      // The first plan's figures: refinement's record of it, else the plan.
      const auto t_first = t->refine_first_time_s ? t->refine_first_time_s : t->planning_time_s;
      const auto soc_first = t->refine_first_sum_of_costs ? t->refine_first_sum_of_costs : t->sum_of_costs;
      if (t_first) time.push_back(*t_first);
      if (soc_first) soc.push_back(static_cast<double>(*soc_first));
      if (t->makespan) makespan.push_back(static_cast<double>(*t->makespan));
      if (soc_first && t->lower_bound && *t->lower_bound > 0)
        ratio.push_back(static_cast<double>(*soc_first) / static_cast<double>(*t->lower_bound));
      if (t->refine_final_sum_of_costs) {
        refined.push_back(static_cast<double>(*t->refine_final_sum_of_costs));
        if (t->lower_bound && *t->lower_bound > 0)
          refined_ratio.push_back(static_cast<double>(*t->refine_final_sum_of_costs) /
                                  static_cast<double>(*t->lower_bound));
      }
    }
    const std::string label =
        first.planner_args.empty() ? first.method : first.method + " " + plannerArgsText(first.planner_args);
    out << "| " << first.robots << " | " << label << " | " << solved << "/" << cell.size() << " | "
        << median(time, "%.3g") << " | " << median(soc, "%.0f") << " | " << median(makespan, "%.0f") << " | "
        << (bound ? std::to_string(*bound) : "-") << " | " << median(ratio, "%.2f") << " |";
    if (refined_any) out << " " << median(refined, "%.0f") << " | " << median(refined_ratio, "%.2f") << " |";
    out << "\n";
  }
  out << "\nLower bound: the sum over robots of each one's shortest path on the 4-connected grid of free cells, "
         "ignoring the others, in moves times 20 steps a move (ceil(1 / 0.05), the default translation "
         "resolution). Medians over solved trials. With --cutoff a method's counts above one it solved none of "
         "are not run.\n";
  return out.str();
}

}  // namespace earc::bench
