#include "earc/bench/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <tuple>
#include <utility>

#include "earc/bench/child.hpp"
#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/runner.hpp"
#include "earc/bench/suites.hpp"
#include "earc/cli/stop_signals.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/planning/plan_stats.hpp"
#include "earc/render/svg.hpp"
#include "earc/util/format.hpp"
#include "earc/util/progress.hpp"
#include "earc/validate/scenario_check.hpp"

namespace fs = std::filesystem;

namespace earc::bench {

namespace {

std::optional<double> medianOf(const std::vector<double>& v) { return quantile(v, 0.5); }

// Per scenario, in the order first seen: each side's solved times.
struct ScenarioTimes {
  std::vector<double> old_s, new_s;
  std::vector<double> old_makespan, new_makespan, old_soc, new_soc;
  int repeats = 0;
  bool differed = false;
};

std::vector<std::pair<std::string, ScenarioTimes>> byScenario(const std::vector<ComparePair>& pairs) {
  std::vector<std::pair<std::string, ScenarioTimes>> out;
  std::map<std::string, std::size_t> index;
  for (const ComparePair& p : pairs) {
    auto [it, inserted] = index.emplace(p.scenario, out.size());
    if (inserted) out.emplace_back(p.scenario, ScenarioTimes{});
    ScenarioTimes& s = out[it->second].second;
    ++s.repeats;
    if (p.old_plan.solved && p.old_plan.time_s) s.old_s.push_back(*p.old_plan.time_s);
    if (p.new_plan.solved && p.new_plan.time_s) s.new_s.push_back(*p.new_plan.time_s);
    auto keep = [](const ComparePlan& plan, const std::optional<double>& v, std::vector<double>& into) {
      if (plan.solved && v) into.push_back(*v);
    };
    keep(p.old_plan, p.old_plan.makespan, s.old_makespan);
    keep(p.new_plan, p.new_plan.makespan, s.new_makespan);
    keep(p.old_plan, p.old_plan.sum_of_costs, s.old_soc);
    keep(p.new_plan, p.new_plan.sum_of_costs, s.new_soc);
    if (p.old_plan.solved && p.new_plan.solved && !p.same_paths) s.differed = true;
  }
  return out;
}

// A scenario counts in the ratios when both sides solved it in every repeat.
bool pairedInEveryRepeat(const ScenarioTimes& s) {
  return static_cast<int>(s.old_s.size()) == s.repeats && static_cast<int>(s.new_s.size()) == s.repeats &&
         *medianOf(s.old_s) > 0;
}

}  // namespace

CompareStats compareStats(const std::vector<ComparePair>& pairs, std::uint64_t seed) {
  CompareStats st;
  st.plans = static_cast<int>(pairs.size());
  for (const ComparePair& p : pairs) {
    st.old_solved += p.old_plan.solved;
    st.new_solved += p.new_plan.solved;
    st.invalid += p.old_plan.invalid + p.new_plan.invalid;
    st.same_paths += p.same_paths;
  }
  const auto scenarios = byScenario(pairs);
  st.scenarios = static_cast<int>(scenarios.size());
  std::vector<double> olds, news, ratios;
  std::vector<double> quality[4];  // old and new makespan, old and new sum of costs
  for (const auto& [name, s] : scenarios) {
    if (!pairedInEveryRepeat(s)) continue;
    const double o = *medianOf(s.old_s), n = *medianOf(s.new_s);
    olds.push_back(o);
    news.push_back(n);
    ratios.push_back(n / o);
    const std::vector<double>* q[4] = {&s.old_makespan, &s.new_makespan, &s.old_soc, &s.new_soc};
    for (int k = 0; k < 4; ++k)
      if (auto m = medianOf(*q[k])) quality[k].push_back(*m);
  }
  st.old_makespan = medianOf(quality[0]);
  st.new_makespan = medianOf(quality[1]);
  st.old_sum_of_costs = medianOf(quality[2]);
  st.new_sum_of_costs = medianOf(quality[3]);
  st.paired = static_cast<int>(ratios.size());
  if (ratios.empty()) return st;
  st.old_median_s = medianOf(olds);
  st.new_median_s = medianOf(news);
  if (*st.old_median_s > 0) st.of_medians = *st.new_median_s / *st.old_median_s;
  st.paired_median = medianOf(ratios);
  const auto interval = medianInterval(ratios, seed);
  st.paired_lo = interval.first;
  st.paired_hi = interval.second;
  return st;
}

// Under the heading: how many plans each side failed, and the ratios.
std::string compareSvg(const std::vector<ComparePair>& pairs, const CompareStats& stats,
                       const std::vector<std::string>& heading) {
  struct Point {
    double x, y;
    bool differed;
  };
  std::vector<Point> pts;
  for (const auto& [name, s] : byScenario(pairs))
    if (pairedInEveryRepeat(s) && *medianOf(s.new_s) > 0) pts.push_back({*medianOf(s.old_s), *medianOf(s.new_s), s.differed});
  // Axes: whole decades around every point, the same for both.
  double lo = 1e-3, hi = 1.0;
  if (!pts.empty()) {
    lo = hi = pts.front().x;
    for (const Point& p : pts) lo = std::min({lo, p.x, p.y}), hi = std::max({hi, p.x, p.y});
  }
  const double dlo = std::floor(std::log10(lo)), dhi = std::max(dlo + 1, std::ceil(std::log10(hi)));
  // Under the heading: how many plans each side failed (they have no
  // point: the ratios are over the scenarios both solved), then the ratios.
  std::vector<std::string> lines = heading;
  const std::size_t heading_lines = lines.size();
  lines.push_back("failed: old " + std::to_string(stats.plans - stats.old_solved) + " of " +
                  std::to_string(stats.plans) + " plans, new " + std::to_string(stats.plans - stats.new_solved) +
                  " of " + std::to_string(stats.plans) + "; " + std::to_string(stats.paired) +
                  (stats.paired == 1 ? " scenario" : " scenarios") + " solved by both");
  if (stats.paired_median)
    lines.push_back("new/old over those: medians " + formatNumber("%.2f", stats.of_medians.value_or(NAN)) +
                    ", paired " + formatNumber("%.2f", *stats.paired_median) + " [" +
                    formatNumber("%.2f", *stats.paired_lo) + ", " + formatNumber("%.2f", *stats.paired_hi) + "]");
  const double line_h = 17;
  const double size = 420, left = 70, top = 18 + line_h * static_cast<double>(lines.size()), w = left + size + 70,
               h = top + size + 60;
  auto px = [&](double v) { return left + (std::log10(v) - dlo) / (dhi - dlo) * size; };
  auto py = [&](double v) { return top + size - (std::log10(v) - dlo) / (dhi - dlo) * size; };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h << "\" viewBox=\"0 0 " << w
      << " " << h << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (std::size_t k = 0; k < lines.size(); ++k)
    svg << "<text x=\"" << 18 << "\" y=\"" << 20 + line_h * static_cast<double>(k) << "\""
        << (k == 0 ? " font-size=\"14\"" : k < heading_lines ? "" : " fill=\"#444\"") << ">" << xmlText(lines[k])
        << "</text>\n";
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << size << "\" height=\"" << size
      << "\" fill=\"none\" stroke=\"#888\"/>\n";
  for (double d = dlo; d <= dhi + 1e-9; d += 1) {
    for (int m : {1, 2, 5}) {
      const double v = m * std::pow(10.0, d);
      if (std::log10(v) > dhi + 1e-9) break;
      const double x = px(v), y = py(v);
      const char* stroke = m == 1 ? "#ccc" : "#eee";
      svg << "<line x1=\"" << x << "\" y1=\"" << top << "\" x2=\"" << x << "\" y2=\"" << top + size << "\" stroke=\""
          << stroke << "\"/>\n<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + size << "\" y2=\"" << y
          << "\" stroke=\"" << stroke << "\"/>\n";
      // Over more than two decades 2 and 5 get grid lines but no labels:
      // their labels would run into each other ("0.00010.0002").
      if (m != 1 && dhi - dlo > 2) continue;
      svg << "<text x=\"" << x << "\" y=\"" << top + size + 16 << "\" text-anchor=\"middle\">" << formatNumber("%g", v)
          << "</text>\n<text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">" << formatNumber("%g", v)
          << "</text>\n";
    }
  }
  const double a = std::pow(10.0, dlo), b = std::pow(10.0, dhi);
  svg << "<line x1=\"" << px(a) << "\" y1=\"" << py(a) << "\" x2=\"" << px(b) << "\" y2=\"" << py(b)
      << "\" stroke=\"#888\" stroke-dasharray=\"4 3\"/>\n";
  if (stats.paired_median) {
    // new = r * old, clipped to the square.
    const double r = *stats.paired_median;
    const double x0 = std::max(a, a / r), x1 = std::min(b, b / r);
    if (x0 < x1)
      svg << "<line x1=\"" << px(x0) << "\" y1=\"" << py(r * x0) << "\" x2=\"" << px(x1) << "\" y2=\"" << py(r * x1)
          << "\" stroke=\"#1f77b4\"/>\n";
  }
  for (const Point& p : pts)
    svg << "<circle cx=\"" << px(p.x) << "\" cy=\"" << py(p.y) << "\" r=\"4\" "
        << (p.differed ? "fill=\"white\" stroke=\"#d62728\"" : "fill=\"#1f77b4\" fill-opacity=\"0.7\"") << "/>\n";
  svg << "<text x=\"" << left + size / 2 << "\" y=\"" << top + size + 36
      << "\" text-anchor=\"middle\">old: planning time (s)</text>\n"
      << "<text transform=\"translate(18," << top + size / 2
      << ") rotate(-90)\" text-anchor=\"middle\">new: planning time (s)</text>\n"
      << "<text x=\"" << left + size << "\" y=\"" << top + size + 52
      << "\" text-anchor=\"end\" fill=\"#444\">dashed: new = old; blue: paired median; hollow red: plans "
         "differed</text>\n</svg>\n";
  return svg.str();
}

namespace {

// Methods that plan with a database (--db).

// One side's method: --old-method or --new-method, else --method.
const std::string& sideMethod(const CompareOptions& o, bool old_side) {
  const std::string& own = old_side ? o.old_method : o.new_method;
  return own.empty() ? o.method : own;
}

struct Job {
  std::string scenario_file, name;
  std::uint64_t planner_seed = 0;
};

class Comparer {
 public:
  Comparer(const CompareOptions& o, std::vector<Job> jobs, std::ostream& log)
      : o_(o), jobs_(std::move(jobs)), log_(log) {
    const std::string here = executableDir();
    new_ = o.new_program.empty() ? here + "/earc-plan" : o.new_program;
    old_method_ = sideMethod(o, true);
    new_method_ = sideMethod(o, false);
    validator_ = o.validator.empty() ? here + "/earc-plan" : o.validator;
    for (const char* sub : {"solutions", "logs"}) fs::create_directories(o.work_dir + "/" + sub);
  }

  CompareSummary run() {
    CompareSummary out;
    log_ << "earc-bench compare: " << jobs_.size() << (jobs_.size() == 1 ? " scenario" : " scenarios") << " x "
         << o_.repeats << (o_.repeats == 1 ? " repeat" : " repeats") << ", " << methods() << ", time limit "
         << formatNumber("%g", o_.time_limit_s) << " s\n  old: " << describe(o_.old_program, o_.old_args)
         << "\n  new: " << describe(new_, o_.new_args) << "\n";
    log_.flush();
    Progress progress("compare", jobs_.size() * static_cast<std::size_t>(o_.repeats));
    for (std::size_t i = 0; i < jobs_.size() && !cli::stopFlag().load(); ++i) {
      for (int r = 0; r < o_.repeats && !cli::stopFlag().load(); ++r) {
        progress.setStatus(jobs_[i].name);
        ComparePair p = runPair(jobs_[i], r, (i + static_cast<std::size_t>(r)) % 2 == 1);
        if (cli::stopFlag().load()) break;
        if (out.pairs.empty()) stopIfRefused(p);
        out.pairs.push_back(std::move(p));
        progress.tick();
      }
      if (o_.verbose && !out.pairs.empty() && out.pairs.back().scenario == jobs_[i].name) scenarioLine(out.pairs, jobs_[i].name);
    }
    progress.finish();
    out.interrupted = cli::stopFlag().load();
    out.stats = compareStats(out.pairs, o_.seed);
    report(out);
    if (!o_.csv.empty()) writeCsv(out.pairs);
    if (!o_.picture.empty())
      render::writeImage(o_.picture, compareSvg(out.pairs, out.stats, pictureHeading(out)));
    return out;
  }

 private:
  // A side that refuses the first plan's input for a reason that is not
  // the scenario's (refusedItsCommand: exit status 2 and a message that
  // does not name the scenario file: an option it does not know, a
  // database too new for it) would refuse every plan alike, and so would one that exits 0
  // without a solution (not an earc-plan at all): say so at once rather
  // than run the whole comparison for a table of failures. A scenario it cannot
  // read is that pair's failure, as any other.
  void stopIfRefused(const ComparePair& first) const {
    for (const auto& [plan, program, option] : {std::tuple{&first.old_plan, &o_.old_program, "--old"},
                                                std::tuple{&first.new_plan, &new_, "--new"}})
      if (plan->refused)
        throw InputError(*program, option, "refused the first plan (" + first.scenario + "), so would every plan: " +
                                               plan->failure);
      else if (plan->silent)
        throw InputError(*program, option, "exited 0 on the first plan (" + first.scenario +
                                               ") without a readable solution: is it an earc-plan? (" +
                                               plan->failure + ")");
  }

  static std::string describe(const std::string& program, const std::vector<std::string>& args) {
    return args.empty() ? program : program + " " + plannerArgsText(args);
  }

  const std::string& methodOf(const std::string& side) const { return side == "old" ? old_method_ : new_method_; }

  // The picture's heading: what was planned, under what limit, and each
  // side's method, options and build, so that it can be read on its own.
  std::vector<std::string> pictureHeading(const CompareSummary& out) const {
    std::string what = "earc-bench compare: ";
    if (o_.scenarios.empty()) what += o_.suite + ", " + std::to_string(o_.robots) + " robots, ";
    what += std::to_string(out.stats.scenarios) + (out.stats.scenarios == 1 ? " scenario" : " scenarios");
    if (o_.repeats > 1) what += " x " + std::to_string(o_.repeats) + " repeats";
    what += ", time limit " + formatNumber("%g", o_.time_limit_s) + " s";
    auto side = [&](const char* name, const std::string& method, const std::vector<std::string>& args,
                    ComparePlan ComparePair::*plan) {
      return std::string(name) + ": " + method + (args.empty() ? "" : " " + plannerArgsText(args)) + " (" +
             builds(out.pairs, plan) + ")";
    };
    return {what, side("old", old_method_, o_.old_args, &ComparePair::old_plan),
            side("new", new_method_, o_.new_args, &ComparePair::new_plan)};
  }

  // "method earc", or "methods old arc, new earc".
  std::string methods() const {
    return old_method_ == new_method_ ? "method " + old_method_ : "methods old " + old_method_ + ", new " + new_method_;
  }

  // The database a plan starts from: a fresh copy of the given one (and of
  // its write-ahead log), so that neither side sees what the other did.
  std::string freshDb(const std::string& side) const {
    const std::string copy = o_.work_dir + "/db-" + side + (methodOf(side) == "lightning" ? ".lightning" : ".sqlite");
    exp::removeDatabaseFiles(copy);
    fs::copy_file(o_.db, copy);
    // Beside the real file, through any link.
    if (const std::string wal = exp::databaseFile(o_.db) + "-wal"; fs::exists(wal)) fs::copy_file(wal, copy + "-wal");
    return copy;
  }

  ComparePlan plan(const Job& job, int repeat, const std::string& side, nlohmann::json& paths) {
    ComparePlan p;
    const std::string stem = job.name + "-r" + std::to_string(repeat) + "-" + side;
    const std::string solution = o_.work_dir + "/solutions/" + stem + ".json";
    const std::string out = o_.work_dir + "/logs/" + stem + ".out", err = o_.work_dir + "/logs/" + stem + ".err";
    fs::remove(solution);
    ChildSpec spec;
    // Each plan starts from a fresh copy of the database and learns nothing.
    spec.argv = planArgv({side == "old" ? o_.old_program : new_, job.scenario_file, solution, methodOf(side),
                          o_.time_limit_s, job.planner_seed, usesDatabase(methodOf(side)) ? freshDb(side) : "",
                          /*learn=*/false, side == "old" ? o_.old_args : o_.new_args});
    spec.stdout_path = out;
    spec.stderr_path = err;
    spec.wall_limit_s = o_.time_limit_s + wallMargin(o_.time_limit_s);
    spec.memory_limit_mb = o_.memory_limit_mb;
    const ChildOutcome run = runChild(spec, &cli::stopFlag());
    p.failure = childFailure(run, spec, err);
    p.refused = refusedItsCommand(run, p.failure, job.scenario_file);
    if (!p.failure.empty()) return p;
    nlohmann::json doc;
    if (auto why = readPlanSolution(run, solution, err, doc)) {
      p.failure = *why;
      p.silent = run.exit_code == 0;
      return p;
    }
    p.version = plannerVersion(doc);
    if (!doc["solved"].get<bool>()) {
      p.failure = "not solved";
      return p;
    }
    if (const auto why = validateSolution(validator_, job.scenario_file, solution, o_.work_dir + "/logs/" + stem,
                                          o_.memory_limit_mb)) {
      if (*why == "interrupted") {
        p.failure = *why;
        return p;
      }
      p.invalid = true;
      p.failure = "invalid solution: " + *why;
      std::cerr << "INVALID SOLUTION: " << side << " (" << spec.argv[0] << ") on " << job.scenario_file << ": " << *why
                << " (solution " << solution << ")\n";
      return p;
    }
    const PlanStats stats = PlanStats::fromJson(doc.value("stats", nlohmann::json::object()));
    const auto number = [](const std::optional<std::int64_t>& n) -> std::optional<double> {
      return n ? std::optional<double>(static_cast<double>(*n)) : std::nullopt;
    };
    p.time_s = stats.planning_time_s;
    p.makespan = number(stats.makespan);
    p.sum_of_costs = number(stats.sum_of_costs);
    if (!p.time_s) {
      p.failure = "no planning_time_s in the solution's stats";
      return p;
    }
    p.solved = true;
    paths = doc.value("paths", nlohmann::json());
    fs::remove(solution);
    fs::remove(out);
    fs::remove(err);
    return p;
  }

  // Which builds planned one side's plans, as their solutions said:
  // "earc 0.1.0+66772d4", several joined by " and ", "unknown".
  static std::string builds(const std::vector<ComparePair>& pairs, ComparePlan ComparePair::*side) {
    std::set<std::string> versions;
    for (const ComparePair& p : pairs)
      if (!(p.*side).version.empty()) versions.insert((p.*side).version);
    std::string out;
    for (const std::string& v : versions) out += (out.empty() ? "earc " : " and earc ") + v;
    return out.empty() ? "unknown" : out;
  }

  ComparePair runPair(const Job& job, int repeat, bool new_first) {
    ComparePair pair;
    pair.scenario = job.name;
    pair.repeat = repeat;
    nlohmann::json old_paths, new_paths;
    if (new_first) {
      pair.new_plan = plan(job, repeat, "new", new_paths);
      pair.old_plan = plan(job, repeat, "old", old_paths);
    } else {
      pair.old_plan = plan(job, repeat, "old", old_paths);
      pair.new_plan = plan(job, repeat, "new", new_paths);
    }
    pair.same_paths = pair.old_plan.solved && pair.new_plan.solved && old_paths == new_paths;
    return pair;
  }

  void scenarioLine(const std::vector<ComparePair>& pairs, const std::string& name) {
    std::vector<ComparePair> mine;
    for (const ComparePair& p : pairs)
      if (p.scenario == name) mine.push_back(p);
    const CompareStats s = compareStats(mine, o_.seed);
    log_ << name << ": ";
    if (s.paired) {
      log_ << "old " << formatNumber("%.4f", *s.old_median_s) << " s, new " << formatNumber("%.4f", *s.new_median_s) << " s, new/old "
           << formatNumber("%.2f", *s.paired_median) << ", " << (s.same_paths == s.plans ? "same paths" : "paths differ");
    } else {
      for (const ComparePair& p : mine) {
        if (!p.old_plan.solved) log_ << "old: " << p.old_plan.failure << "; ";
        if (!p.new_plan.solved) log_ << "new: " << p.new_plan.failure << "; ";
      }
    }
    log_ << "\n";
    log_.flush();
  }

  void report(const CompareSummary& out) {
    const CompareStats& s = out.stats;
    log_ << "builds: old " << builds(out.pairs, &ComparePair::old_plan) << ", new "
         << builds(out.pairs, &ComparePair::new_plan) << "\n";
    log_ << "old solved " << s.old_solved << " of " << s.plans << " plans, new " << s.new_solved << " of " << s.plans;
    if (s.invalid) log_ << "; " << s.invalid << " INVALID solutions";
    log_ << "\n";
    if (s.paired) {
      log_ << "medians over the " << s.paired << " scenarios both solved: old " << formatNumber("%.4f", *s.old_median_s)
           << " s, new " << formatNumber("%.4f", *s.new_median_s) << " s\n"
           << "new/old: ratio of medians " << formatNumber("%.3f", s.of_medians.value_or(NAN)) << ", paired median "
           << formatNumber("%.3f", *s.paired_median) << " (95% bootstrap interval " << formatNumber("%.3f", *s.paired_lo) << " to "
           << formatNumber("%.3f", *s.paired_hi) << ")\n";
    } else {
      log_ << "no scenario was solved by both: no ratio\n";
    }
    log_ << "same paths: " << s.same_paths << " of " << s.plans << " plan pairs\n";
    if (s.old_makespan && s.new_makespan && s.old_sum_of_costs && s.new_sum_of_costs)
      log_ << "plans (medians over the same scenarios): makespan old " << formatNumber("%g", *s.old_makespan)
           << ", new " << formatNumber("%g", *s.new_makespan) << "; sum of costs old "
           << formatNumber("%g", *s.old_sum_of_costs) << ", new " << formatNumber("%g", *s.new_sum_of_costs) << "\n";
    if (out.interrupted) log_ << "interrupted: the figures above cover the plans that finished\n";
  }

  void writeCsv(const std::vector<ComparePair>& pairs) const {
    std::ostringstream csv;
    csv << "scenario,repeat,old_solved,old_time_s,old_makespan,old_sum_of_costs,old_failure,new_solved,new_time_s,"
           "new_makespan,new_sum_of_costs,new_failure,same_paths\n";
    auto quoted = [](const std::string& s) {
      std::string q = "\"";
      for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
      return q + "\"";
    };
    for (const ComparePair& p : pairs) {
      csv << quoted(p.scenario) << "," << p.repeat;
      for (const ComparePlan* plan : {&p.old_plan, &p.new_plan})
        csv << "," << plan->solved << "," << (plan->time_s ? formatNumber("%.6f", *plan->time_s) : "") << ","
            << (plan->makespan ? formatNumber("%g", *plan->makespan) : "") << ","
            << (plan->sum_of_costs ? formatNumber("%g", *plan->sum_of_costs) : "") << "," << quoted(plan->failure);
      csv << "," << p.same_paths << "\n";
    }
    writeTextFileAtomic(o_.csv, csv.str());
  }

  const CompareOptions& o_;
  std::vector<Job> jobs_;
  std::ostream& log_;
  std::string new_, validator_, old_method_, new_method_;
};

// Every option checked, and the scenarios made or read, before any plan.
std::vector<Job> prepareJobs(const CompareOptions& o) {
  if (o.old_program.empty()) throw InputError("", "--old", "no program given");
  requireExecutable(o.old_program, "--old");
  if (!o.new_program.empty()) requireExecutable(o.new_program, "--new");
  else requireExecutable(executableDir() + "/earc-plan", "--new (default: earc-plan beside earc-bench)");
  for (const auto& [method, option] : {std::pair{&o.method, "--method"}, std::pair{&o.old_method, "--old-method"},
                                       std::pair{&o.new_method, "--new-method"}}) {
    if (method->empty() && option != std::string_view("--method")) continue;
    if (std::find(allMethods().begin(), allMethods().end(), *method) == allMethods().end())
      throw InputError("", option, "unknown method '" + *method + "' (earc, arc, lightning, prioritized, coupled)");
  }
  const std::string& old_method = sideMethod(o, true);
  const std::string& new_method = sideMethod(o, false);
  if (usesDatabase(old_method) && usesDatabase(new_method) && old_method != new_method)
    throw InputError("", "--db", "methods " + old_method + " and " + new_method + " read different kinds of database");
  for (const std::string* method : {&old_method, &new_method})
    if (usesDatabase(*method)) {
      if (o.db.empty()) throw InputError("", "--db", "method " + *method + " needs a database to start from");
      if (!fs::is_regular_file(o.db)) throw InputError(o.db, "--db", "no such file");
    }
  requirePlannerArgs(o.old_args, "--old-arg");
  requirePlannerArgs(o.new_args, "--new-arg");
  if (!o.picture.empty()) render::requireImageOutput(o.picture, "--picture");
  requireSeparateOutputs(o.db, "--db", {{o.csv, "--csv"}, {o.picture, "--picture"}});
  std::vector<Job> jobs;
  if (!o.scenarios.empty()) {
    for (const std::string& f : o.scenarios) {
      const Scenario s = loadScenario(f);  // InputError naming the file and field
      Job j{f, s.name, o.seed};
      // Two files may carry one name: the solution files must not collide.
      for (const Job& other : jobs)
        if (other.name == j.name) j.name += "-" + std::to_string(jobs.size());
      jobs.push_back(std::move(j));
    }
    return jobs;
  }
  const Suite& suite = suiteByName(o.suite, "--suite");
  // A crowd suite takes any count up to its file's agents.
  if (!suiteTakes(suite, o.robots))
    throw InputError("", "--robots", "suite " + suite.name + " has no " + std::to_string(o.robots) + "-robot trials (" +
                                         suiteCountsText(suite) + ")");
  fs::create_directories(o.work_dir + "/scenarios");
  for (int t = 0; t < o.trials; ++t) {
    const TrialSeeds seeds = trialSeeds(suite, o.robots, t, o.seed);
    const std::string name = suite.name + "-" + std::to_string(o.robots) + "-t" + std::to_string(t);
    const std::string path = o.work_dir + "/scenarios/" + name + ".json";
    // Made afresh each time: a file left by a run with another seed must
    // not stand in for this seed's scenario.
    writeTextFileAtomic(path, scenarioToJson(trialScenario(suite, o.robots, t, o.seed)).dump(1) + "\n");
    jobs.push_back({path, name, seeds.planner});
  }
  return jobs;
}

}  // namespace

// Bad options: a program that cannot run, a database missing for earc, a
// scenario file that is not one, an argument plannerArgsProblem refuses.
CompareSummary runCompare(const CompareOptions& options, std::ostream& log) {
  std::vector<Job> jobs = prepareJobs(options);
  cli::StopSignals guard(cli::StopSignals::Repeats::Caught);
  Comparer comparer(options, std::move(jobs), log);
  return comparer.run();
}

}  // namespace earc::bench
