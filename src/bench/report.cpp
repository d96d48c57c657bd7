#include "earc/bench/report.hpp"

#include <ompl/base/PlannerStatus.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <ostream>
#include <sstream>

#include "earc/bench/options.hpp"
#include "earc/bench/suites.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/format.hpp"
#include "earc/util/hash.hpp"

namespace earc::bench {

namespace {

int suiteRank(const std::string& s) {
  const auto& all = allSuites();
  for (std::size_t i = 0; i < all.size(); ++i)
    if (all[i].name == s) return static_cast<int>(i);
  return static_cast<int>(all.size());
}

int methodRank(const std::string& m) {
  const auto& all = allMethods();
  auto it = std::find(all.begin(), all.end(), m);
  return static_cast<int>(it - all.begin());
}

// Where a cell goes in the tables (see summarize).
auto cellOrder(const CellSummary& c) {
  return std::make_tuple(suiteRank(c.suite), c.suite, c.time_limit_s, c.robots, methodRank(c.method), c.method);
}

// Whether a trial or cell is of the table row of cell c: the same suite,
// time limit and robot count.
template <class T>
bool ofRow(const T& x, const CellSummary& c) {
  return x.suite == c.suite && x.time_limit_s == c.time_limit_s && x.robots == c.robots;
}

// The heading of a cell's table: its suite, and its time limit where the
// suite ran under several ("mobile, time limit 10 s"), as an OMPL log's
// name gets its limit where its cell has several.
std::string tableHeading(const std::vector<CellSummary>& cells, const CellSummary& c) {
  const bool several = std::any_of(cells.begin(), cells.end(), [&c](const CellSummary& x) {
    return x.suite == c.suite && x.time_limit_s != c.time_limit_s;
  });
  return several ? c.suite + ", time limit " + formatNumber("%g", c.time_limit_s) + " s" : c.suite;
}

// "0.60 [0.45, 0.78]": a value and its interval in one format.
std::string withInterval(const char* format, double v, const std::pair<double, double>& interval) {
  return formatNumber(format, v) + " [" + formatNumber(format, interval.first) + ", " +
         formatNumber(format, interval.second) + "]";
}

// The values at the given indices (one bootstrap resample).
std::vector<double> gather(const std::vector<double>& values, const std::vector<std::size_t>& idx) {
  std::vector<double> out;
  out.reserve(idx.size());
  for (std::size_t i : idx) out.push_back(values[i]);
  return out;
}

// Seconds with three significant digits, down to the microsecond, but
// never in exponent form (a sub-millisecond median read "0.000").
std::string secs(double s) {
  if (s >= 100) return formatNumber("%.0f", s);
  if (s >= 10) return formatNumber("%.1f", s);
  if (s >= 1) return formatNumber("%.2f", s);
  if (!(s > 0)) return formatNumber("%.3f", s);
  const int decimals = std::clamp(2 - static_cast<int>(std::floor(std::log10(s))), 3, 6);
  return formatNumber(("%." + std::to_string(decimals) + "f").c_str(), s);
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

template <class T>
std::string opt(const std::optional<T>& v) {
  if (!v) return "";
  std::ostringstream s;
  s.precision(10);
  s << *v;
  return s.str();
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

// What tables and OMPL logs call each method of the trials: its name,
// followed by the planner arguments its trials ran with (run
// --method-arg) where there are any: "earc --db-k=5". A results file
// holds one set per method (ResultsDb); trials given otherwise that mix
// several are named "earc (several sets of planner arguments)" rather
// than after one of them.
std::map<std::string, std::string> methodLabels(const std::vector<TrialRecord>& trials) {
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

// Text in a markdown table's cell: a '|' (an argument may hold one)
// would end the cell.
std::string markdownCell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
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

// A 95% bootstrap interval (percentile method) of a statistic of n paired
// items: `statistic` gets the indices of one resample (n draws from 0..n-1
// with replacement); 2,000 resamples from a generator seeded with `seed`,
// so the same items and seed give the same interval. n must be positive.
std::pair<double, double> bootstrapInterval(std::size_t n,
                                            const std::function<double(const std::vector<std::size_t>&)>& statistic,
                                            std::uint64_t seed) {
  // Enough resamples that the interval's ends move by less than the
  // printed precision from one seed to another.
  constexpr int kResamples = 2000;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::vector<double> values(kResamples);
  std::vector<std::size_t> sample(n);
  for (double& v : values) {
    for (std::size_t& i : sample) i = pick(rng);
    v = statistic(sample);
  }
  return {*quantile(values, 0.025), *quantile(values, 0.975)};
}

std::pair<double, double> medianInterval(const std::vector<double>& values, std::uint64_t seed) {
  return bootstrapInterval(
      values.size(), [&](const std::vector<std::size_t>& idx) { return *quantile(gather(values, idx), 0.5); }, seed);
}

std::optional<double> quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nullopt;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

bool TrialFilter::matches(const TrialRecord& t) const {
  return (!seed || t.seed == *seed) && (!time_limit_s || t.time_limit_s == *time_limit_s);
}

std::vector<TrialRecord> TrialFilter::apply(std::vector<TrialRecord> trials) const {
  std::erase_if(trials, [this](const TrialRecord& t) { return !matches(t); });
  return trials;
}

std::vector<TrialRecord> TrialFilter::applyRequired(std::vector<TrialRecord> trials, const std::string& results) const {
  if (trials.empty()) return trials;
  std::set<std::uint64_t> seeds;
  std::set<double> limits;
  for (const TrialRecord& t : trials) {
    seeds.insert(t.seed);
    limits.insert(t.time_limit_s);
  }
  trials = apply(std::move(trials));
  if (!trials.empty()) return trials;
  // Said of the first option that matches nothing on its own.
  auto list = [](const auto& values, auto text) {
    std::string out;
    for (const auto& v : values) out += (out.empty() ? "" : ", ") + text(v);
    return out;
  };
  auto seconds = [](double s) { return formatNumber(s) + " s"; };
  auto number = [](std::uint64_t n) { return std::to_string(n); };
  if (seed && !seeds.count(*seed))
    throw InputError(results, "--seed", "no trials of run seed " + std::to_string(*seed) + " (its trials' seeds: " +
                                             list(seeds, number) + ")");
  if (time_limit_s && !limits.count(*time_limit_s))
    throw InputError(results, "--time-limit", "no trials with a time limit of " + seconds(*time_limit_s) +
                                                  " (its trials' limits: " + list(limits, seconds) + ")");
  throw InputError(results, "--seed/--time-limit",
                   "no trials of run seed " + std::to_string(*seed) + " with a time limit of " + seconds(*time_limit_s));
}

std::vector<CellSummary> summarize(const std::vector<TrialRecord>& trials) {
  std::map<std::tuple<std::string, int, std::string, double>, std::vector<const TrialRecord*>> cells;
  for (const auto& t : trials) cells[{t.suite, t.robots, t.method, t.time_limit_s}].push_back(&t);
  std::vector<CellSummary> out;
  for (const auto& [key, list] : cells) {
    CellSummary c;
    std::tie(c.suite, c.robots, c.method, c.time_limit_s) = key;
    std::vector<double> times;
    for (const TrialRecord* t : list) {
      ++c.trials;
      if (t->success) {
        ++c.solved;
        if (t->planning_time_s) times.push_back(*t->planning_time_s);
      }
    }
    c.median_s = quantile(times, 0.5);
    c.q1_s = quantile(times, 0.25);
    c.q3_s = quantile(times, 0.75);
    out.push_back(std::move(c));
  }
  std::sort(out.begin(), out.end(),
            [](const CellSummary& a, const CellSummary& b) { return cellOrder(a) < cellOrder(b); });
  return out;
}

PairedRatio pairedRatio(const std::vector<TrialRecord>& trials, const std::string& suite, int robots,
                        const std::string& a, const std::string& b, std::optional<double> time_limit_s) {
  using Key = std::tuple<int, std::uint64_t, double>;
  std::map<Key, const TrialRecord*> ta, tb;
  for (const auto& t : trials) {
    if (t.suite != suite || t.robots != robots || !t.success || !t.planning_time_s) continue;
    if (time_limit_s && t.time_limit_s != *time_limit_s) continue;
    if (t.method == a) ta[{t.trial, t.seed, t.time_limit_s}] = &t;
    if (t.method == b) tb[{t.trial, t.seed, t.time_limit_s}] = &t;
  }
  std::vector<double> ratios, paired_a, paired_b, makespans_a, makespans_b;
  for (const auto& [k, ra] : ta) {
    auto it = tb.find(k);
    if (it == tb.end()) continue;
    const TrialRecord& rb = *it->second;
    const double va = *ra->planning_time_s, vb = *rb.planning_time_s;
    if (vb <= 0) continue;
    ratios.push_back(va / vb);
    paired_a.push_back(va);
    paired_b.push_back(vb);
    if (ra->makespan && rb.makespan) {
      makespans_a.push_back(static_cast<double>(*ra->makespan));
      makespans_b.push_back(static_cast<double>(*rb.makespan));
    }
  }
  PairedRatio r{static_cast<int>(ratios.size()), quantile(ratios, 0.5), std::nullopt, std::nullopt, std::nullopt,
                quantile(makespans_a, 0.5), quantile(makespans_b, 0.5)};
  if (ratios.empty()) return r;
  r.of_medians = *quantile(paired_a, 0.5) / *quantile(paired_b, 0.5);
  constexpr std::uint64_t kSeed = 1;
  r.median_interval = medianInterval(ratios, kSeed);
  r.of_medians_interval = bootstrapInterval(
      ratios.size(),
      [&](const std::vector<std::size_t>& idx) {
        return *quantile(gather(paired_a, idx), 0.5) / *quantile(gather(paired_b, idx), 0.5);
      },
      kSeed);
  return r;
}

namespace {

// How many trials have each known value of a field (`get` returns an
// optional), and how many have none.
template <class Get>
auto countBy(const std::vector<TrialRecord>& trials, Get get) {
  std::map<typename decltype(get(trials.front()))::value_type, std::size_t> known;
  std::size_t unknown = 0;
  for (const TrialRecord& t : trials)
    if (const auto v = get(t)) ++known[*v];
    else ++unknown;
  return std::pair{known, unknown};
}

// "N trials" / "1 trial".
std::string trialCount(std::size_t n) { return std::to_string(n) + (n == 1 ? " trial" : " trials"); }

// Adds to a note the sentence "WHAT was not recorded for N trials (WHY)."
// when unknown > 0.
void addNotRecorded(std::string& note, std::string_view what, std::size_t unknown, std::string_view why) {
  if (unknown == 0) return;
  note += std::string(note.empty() ? "" : " ") + std::string(what) + " was not recorded for " + trialCount(unknown) +
          " (" + std::string(why) + ").";
}

}  // namespace

std::string jobsNote(const std::vector<TrialRecord>& trials) {
  if (trials.empty()) return "";
  const auto [by_jobs, unknown] = countBy(trials, [](const TrialRecord& t) { return t.jobs; });
  std::string note;
  if (by_jobs.size() == 1) {
    const int n = by_jobs.begin()->first;
    note = n == 1 ? "Trials ran one at a time."
                  : "Trials ran " + std::to_string(n) + " at a time (--jobs " + std::to_string(n) +
                        "): side by side they slow each other; for timings, one at a time is steadiest.";
  } else if (by_jobs.size() > 1) {
    note = "Trials ran with";
    bool first = true;
    for (const auto& [n, count] : by_jobs) {
      note += std::string(first ? " " : ", ") + "--jobs " + std::to_string(n) + " (" + std::to_string(count) + ")";
      first = false;
    }
    note += ": timings of different runs are not alike.";
  }
  addNotRecorded(note, "How many trials ran at once", unknown, "results from before schema version 2");
  return note;
}

namespace {

// One build column of the trials (which planner planned them, which
// earc-bench timed them) and how the note names it.
struct BuildColumn {
  std::string TrialRecord::*field;
  std::string_view verb;          // "Planned"
  std::string_view program;       // "earc"
  std::string_view consequence;   // of more than one build
  std::string_view unknown_what;  // of trials that do not say
  std::string_view unknown_why;
};

// Which builds of the column's program did its verb to the trials, by the
// build each trial recorded, in one line (see versionNote).
std::string buildsNote(const std::vector<TrialRecord>& trials, const BuildColumn& column) {
  if (trials.empty()) return "";
  const auto [by_version, unknown] = countBy(trials, [&column](const TrialRecord& t) {
    const std::string& v = t.*column.field;
    return v.empty() ? std::nullopt : std::optional<std::string>(v);
  });
  const std::string prefix = std::string(column.verb) + " by ";
  std::string note;
  if (by_version.size() == 1) {
    note = prefix + std::string(column.program) + " " + by_version.begin()->first + ".";
  } else if (by_version.size() > 1) {
    note = prefix + std::to_string(by_version.size()) + " builds:";
    bool first = true;
    for (const auto& [version, count] : by_version) {
      note += std::string(first ? " " : ", ") + std::string(column.program) + " " + version + " (" + trialCount(count) + ")";
      first = false;
    }
    note += ": " + std::string(column.consequence) + ".";
  }
  addNotRecorded(note, column.unknown_what, unknown, column.unknown_why);
  return note;
}

}  // namespace

std::string versionNote(const std::vector<TrialRecord>& trials) {
  return buildsNote(trials, {.field = &TrialRecord::planner_version,
                             .verb = "Planned",
                             .program = "earc",
                             .consequence = "their times are of different code",
                             .unknown_what = "Which build planned",
                             .unknown_why = "results from before schema version 3, or a planner that does not say"});
}

std::string benchNote(const std::vector<TrialRecord>& trials) {
  return buildsNote(trials, {.field = &TrialRecord::bench_version,
                             .verb = "Timed",
                             .program = "earc-bench",
                             .consequence = "they were run and timed by different code",
                             .unknown_what = "Which earc-bench timed",
                             .unknown_why = "results from before schema version 4"});
}

std::string trialsNotes(const std::vector<TrialRecord>& trials) {
  if (trials.empty()) return "(no trials)\n";
  return "\n" + jobsNote(trials) + "\n" + versionNote(trials) + "\n" + benchNote(trials) + "\n";
}

// The same results laid out like the paper's figures: one table per suite,
// a row per robot count, a column per method ("solved/trials median s";
// "-" where the method was not run; headed as markdownTable names them), then E-ARC's time over ARC's on the
// same scenarios (ratio of medians, median of ratios) and E-ARC's hit rate
// (subproblems solved from the database, directly or repaired, over
// conflicts); then trialsNotes.
std::string markdownWideTable(const std::vector<TrialRecord>& trials) {
  std::ostringstream out;
  const auto cells = summarize(trials);
  std::vector<std::string> methods;
  for (const CellSummary& c : cells)
    if (std::find(methods.begin(), methods.end(), c.method) == methods.end()) methods.push_back(c.method);
  std::sort(methods.begin(), methods.end(),
            [](const std::string& a, const std::string& b) { return methodRank(a) < methodRank(b) || (methodRank(a) == methodRank(b) && a < b); });
  const bool both = std::find(methods.begin(), methods.end(), "earc") != methods.end() &&
                    std::find(methods.begin(), methods.end(), "arc") != methods.end();
  const auto labels = methodLabels(trials);
  std::string heading;
  std::set<std::tuple<std::string, double, int>> rows;
  for (const CellSummary& c : cells) {
    if (!rows.insert({c.suite, c.time_limit_s, c.robots}).second) continue;
    if (tableHeading(cells, c) != heading) {
      heading = tableHeading(cells, c);
      out << (out.tellp() > 0 ? "\n" : "") << "### " << heading << "\n\n| robots |";
      for (const auto& m : methods) out << " " << markdownCell(labels.at(m)) << " |";
      if (both) out << " E-ARC / ARC medians [95%] | E-ARC / ARC paired [95%] | E-ARC hit rate |";
      out << "\n|---:|";
      for (std::size_t i = 0; i < methods.size(); ++i) out << "---|";
      if (both) out << "---:|---:|---:|";
      out << "\n";
    }
    out << "| " << c.robots << " |";
    for (const auto& m : methods) {
      auto it = std::find_if(cells.begin(), cells.end(),
                             [&](const CellSummary& x) { return ofRow(x, c) && x.method == m; });
      if (it == cells.end()) {
        out << " - |";
        continue;
      }
      out << " " << it->solved << "/" << it->trials;
      if (it->median_s) out << " " << secs(*it->median_s);
      out << " |";
    }
    if (both) {
      PairedRatio r = pairedRatio(trials, c.suite, c.robots, "earc", "arc", c.time_limit_s);
      std::int64_t hits = 0, conflicts = 0;
      for (const TrialRecord& t : trials)
        if (ofRow(t, c) && t.method == "earc" && t.success) {
          hits += t.db_hits.value_or(0);
          conflicts += t.conflicts.value_or(0);
        }
      out << " " << (r.pairs ? withInterval("%.2f", *r.of_medians, *r.of_medians_interval) : "-") << " | "
          << (r.pairs ? withInterval("%.2f", *r.median, *r.median_interval) : "-") << " | "
          << (conflicts ? formatNumber("%.0f%%", 100.0 * static_cast<double>(hits) / static_cast<double>(conflicts)) : "-")
          << " |";
    }
    out << "\n";
  }
  out << trialsNotes(trials);
  return out.str();
}

// Markdown: per suite a table of success rate and median planning time
// (IQR) per robot count and method (named with the planner arguments its
// trials ran with, where they ran with any: "earc --db-k=5"), the E-ARC/ARC paired ratio, then the
// databases, then trialsNotes. A suite run under several time limits has
// a table per limit, headed "SUITE, time limit S s", and its ratios are
// paired within one limit (markdownWideTable too).
std::string markdownTable(const std::vector<TrialRecord>& trials, const std::vector<DatabaseRecord>& databases) {
  std::ostringstream out;
  const auto cells = summarize(trials);
  const auto labels = methodLabels(trials);
  std::string heading;
  for (const CellSummary& c : cells) {
    if (tableHeading(cells, c) != heading) {
      heading = tableHeading(cells, c);
      out << (out.tellp() > 0 ? "\n" : "") << "### " << heading << "\n\n"
          << "| robots | method | solved | median time (s) | IQR (s) |\n"
          << "|---:|:---|---:|---:|:---|\n";
    }
    out << "| " << c.robots << " | " << markdownCell(labels.at(c.method)) << " | " << c.solved << "/" << c.trials << " ("
        << formatNumber("%.0f", 100.0 * c.solved / std::max(1, c.trials)) << "%) | "
        << (c.median_s ? secs(*c.median_s) : "-") << " | "
        << (c.q1_s ? secs(*c.q1_s) + " - " + secs(*c.q3_s) : "-") << " |\n";
  }
  // E-ARC against ARC on the very same scenarios.
  std::vector<std::string> ratio_rows;
  std::set<std::tuple<std::string, double, int>> seen;
  for (const CellSummary& c : cells) {
    if (!seen.insert({c.suite, c.time_limit_s, c.robots}).second) continue;
    PairedRatio r = pairedRatio(trials, c.suite, c.robots, "earc", "arc", c.time_limit_s);
    if (r.pairs == 0) continue;
    ratio_rows.push_back("| " + tableHeading(cells, c) + " | " + std::to_string(c.robots) + " | " +
                         std::to_string(r.pairs) + " | " +
                         withInterval("%.3f", *r.of_medians, *r.of_medians_interval) + " | " +
                         withInterval("%.3f", *r.median, *r.median_interval) + " | " +
                         (r.makespan_a ? formatNumber("%g", *r.makespan_a) + " / " + formatNumber("%g", *r.makespan_b)
                                       : std::string("-")) +
                         " |");
  }
  if (!ratio_rows.empty()) {
    out << "\n### E-ARC / ARC planning time, paired by seed\n\n"
        << "| suite | robots | pairs solved by both | ratio of medians [95% interval] | median of ratios [95% interval] "
           "| median makespan E-ARC / ARC |\n"
        << "|:---|---:|---:|---:|---:|---:|\n";
    for (const auto& row : ratio_rows) out << row << "\n";
  }
  if (!databases.empty()) {
    out << "\n### Databases\n\n| method | suite | robots | construction (s) | entries | size (KiB) | problems |\n"
        << "|:---|:---|---:|---:|---:|---:|---:|\n";
    for (const auto& d : databases)
      out << "| " << d.method << " | " << d.suite << " | " << (d.robots ? std::to_string(d.robots) : "all") << " | "
          << (d.construction_time_s ? secs(*d.construction_time_s) : "-") << " | " << (d.entries ? opt(d.entries) : "-")
          << " | " << (d.size_bytes ? formatNumber("%.1f", static_cast<double>(*d.size_bytes) / 1024.0) : "-") << " | "
          << (d.problems ? opt(d.problems) : "-") << " |\n";
  }
  out << trialsNotes(trials);
  return out.str();
}

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
