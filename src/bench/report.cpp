// The report's tables: Markdown per suite and in the paper's layout, and
// the notes on what the trials did not record.
#include "earc/bench/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "earc/util/format.hpp"
#include "report_util.hpp"

namespace earc::bench {

using report_detail::methodLabels;
using report_detail::methodRank;
using report_detail::opt;

namespace {

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

// Text in a markdown table's cell: a '|' (an argument may hold one)
// would end the cell.
std::string markdownCell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

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

}  // namespace earc::bench
