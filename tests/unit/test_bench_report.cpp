// The benchmark's reports: statistics, pairing by seed, tables, CSV and
// OMPL benchmark logs.
#include <doctest/doctest.h>


#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>
#include <unistd.h>

#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/bench/suites.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/movingai.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/cli/subcommands.hpp"

using namespace earc;
using namespace earc::bench;
#include "bench_results_fixtures.hpp"

using namespace earc::bench_test;

TEST_CASE("quantiles interpolate between order statistics like numpy") {
  CHECK_FALSE(quantile({}, 0.5).has_value());
  CHECK(*quantile({3, 1, 2}, 0.5) == doctest::Approx(2));
  CHECK(*quantile({1, 2, 3, 4}, 0.5) == doctest::Approx(2.5));
  CHECK(*quantile({1, 2, 3, 4}, 0.25) == doctest::Approx(1.75));
  CHECK(*quantile({7}, 0.75) == doctest::Approx(7));
}

TEST_CASE("cells count every trial but time only the solved ones") {
  std::vector<TrialRecord> t = {trial("arc", 0, true, 1), trial("arc", 1, true, 3), trial("arc", 2, false, 60)};
  const auto cells = summarize(t);
  REQUIRE(cells.size() == 1);
  CHECK(cells[0].trials == 3);
  CHECK(cells[0].solved == 2);
  CHECK(*cells[0].median_s == doctest::Approx(2));
}

TEST_CASE("the table gives times with three significant digits, also below a millisecond") {
  // Medians of one trial each: a sub-millisecond plan read "0.000".
  const std::string md = markdownTable({trial("arc", 0, true, 0.000123), trial("earc", 0, true, 0.0456),
                                        trial("prioritized", 0, true, 0.5), trial("coupled", 0, true, 12.34)},
                                       {});
  CHECK(md.find("| 0.000123 |") != std::string::npos);
  CHECK(md.find("| 0.0456 |") != std::string::npos);
  CHECK(md.find("| 0.500 |") != std::string::npos);
  CHECK(md.find("| 12.3 |") != std::string::npos);
  CHECK(md.find("0.000 ") == std::string::npos);
}

TEST_CASE("the E-ARC/ARC ratio pairs trials by scenario and skips unpaired ones") {
  std::vector<TrialRecord> t = {trial("arc", 0, true, 2), trial("earc", 0, true, 1),   // 0.5
                                trial("arc", 1, true, 4), trial("earc", 1, true, 3),   // 0.75
                                trial("arc", 2, true, 4), trial("earc", 2, false, 60),  // unpaired
                                trial("earc", 3, true, 1)};
  PairedRatio r = pairedRatio(t, "mobile", 4, "earc", "arc");
  CHECK(r.pairs == 2);
  CHECK(*r.median == doctest::Approx(0.625));
  CHECK(*r.of_medians == doctest::Approx(2.0 / 3.0));  // medians of the paired trials: 2 and 3
  const std::string md = markdownTable(t, {});
  CHECK(md.find("### mobile") != std::string::npos);
  CHECK(md.find("| 4 | earc | 3/4 (75%) |") != std::string::npos);
  // Resampling two pairs gives ratios 0.5 or 0.75 alike: the interval
  // spans both, whichever statistic.
  REQUIRE(r.median_interval);
  CHECK(r.median_interval->first == doctest::Approx(0.5));
  CHECK(r.median_interval->second == doctest::Approx(0.75));
  CHECK(r.of_medians_interval->first == doctest::Approx(0.5));
  CHECK(r.of_medians_interval->second == doctest::Approx(0.75));
  CHECK(md.find("| mobile | 4 | 2 | 0.667 [0.500, 0.750] | 0.625 [0.500, 0.750] | 100 / 100 |") != std::string::npos);
  // Makespans on the same pairs only: E-ARC's unpaired trial 3 does not
  // count; none known, none shown.
  t[0].makespan = 100;
  t[1].makespan = 110;
  t[2].makespan = 200;
  t[3].makespan = 130;
  t[6].makespan = 999;
  r = pairedRatio(t, "mobile", 4, "earc", "arc");
  CHECK(*r.makespan_a == doctest::Approx(120));
  CHECK(*r.makespan_b == doctest::Approx(150));
  CHECK(markdownTable(t, {}).find("| 0.625 [0.500, 0.750] | 120 / 150 |") != std::string::npos);
  for (TrialRecord& x : t) x.makespan.reset();
  CHECK_FALSE(pairedRatio(t, "mobile", 4, "earc", "arc").makespan_a);
  CHECK(markdownTable(t, {}).find("| 0.625 [0.500, 0.750] | - |") != std::string::npos);
}

TEST_CASE("the wide table has a row per robot count, a column per method, the paired ratio and the hit rate") {
  std::vector<TrialRecord> t = {trial("arc", 0, true, 2), trial("earc", 0, true, 1),  // 0.5
                                trial("arc", 1, true, 4), trial("earc", 1, true, 3),  // 0.75
                                trial("coupled", 0, false, 60), trial("arc", 0, true, 8, "mobile", 8)};
  t[1].db_hits = 3;
  t[1].conflicts = 4;
  t[3].db_hits = 1;
  t[3].conflicts = 4;
  const std::string md = markdownWideTable(t);
  CHECK(md.find("| robots | earc | arc | coupled | E-ARC / ARC medians [95%] | E-ARC / ARC paired [95%] | E-ARC hit rate |") !=
        std::string::npos);
  CHECK(md.find("| 4 | 2/2 2.00 | 2/2 3.00 | 0/1 | 0.67 [0.50, 0.75] | 0.62 [0.50, 0.75] | 50% |") != std::string::npos);
  // E-ARC and coupled did not run at 8 robots.
  CHECK(md.find("| 8 | - | 1/1 8.00 | - | - | - | - |") != std::string::npos);
}

TEST_CASE("trials under different time limits are kept apart, each limit named where a suite has several") {
  // Two runs of one cell into one file, at 20 s and at 10 s: what the
  // 10 s run left unsolved the 20 s run solved, so one cell of both
  // would be neither experiment's.
  std::vector<TrialRecord> t = {trial("arc", 0, true, 2),  trial("earc", 0, true, 1),   // 20 s
                                trial("arc", 1, true, 4),  trial("earc", 1, true, 3),   // 20 s
                                trial("arc", 0, false, 10), trial("earc", 0, true, 5),  // 10 s
                                trial("arc", 0, true, 7, "arms", 2)};                    // 60 s, one limit
  for (std::size_t i = 0; i < 4; ++i) t[i].time_limit_s = 20;
  t[4].time_limit_s = t[5].time_limit_s = 10;
  const auto cells = summarize(t);
  REQUIRE(cells.size() == 5);
  CHECK(cells[0].method == "earc");
  CHECK(cells[0].time_limit_s == 10);
  CHECK(cells[2].time_limit_s == 20);
  CHECK(cells[3].trials == 2);

  const std::string md = markdownTable(t, {});
  const auto at10 = md.find("### mobile, time limit 10 s\n"), at20 = md.find("### mobile, time limit 20 s\n");
  REQUIRE(at10 != std::string::npos);
  REQUIRE(at20 != std::string::npos);
  CHECK(at10 < at20);
  CHECK(md.find("| 4 | arc | 0/1 (0%) | - | - |", at10) < at20);
  CHECK(md.find("| 4 | arc | 2/2 (100%) | 3.00 | 2.50 - 3.50 |", at20) != std::string::npos);
  CHECK(md.find("### mobile\n") == std::string::npos);
  CHECK(md.find("### arms\n") != std::string::npos);  // one limit: no need to name it
  // Paired within one limit: the 10 s run has no pair, the 20 s run two.
  CHECK(md.find("| mobile, time limit 10 s | 4 |") == std::string::npos);
  CHECK(md.find("| mobile, time limit 20 s | 4 | 2 | 0.667 [0.500, 0.750] |") != std::string::npos);
  CHECK(pairedRatio(t, "mobile", 4, "earc", "arc", 20.0).pairs == 2);
  CHECK(pairedRatio(t, "mobile", 4, "earc", "arc", 10.0).pairs == 0);

  t[5].db_hits = 1;
  t[5].conflicts = 1;
  const std::string wide = markdownWideTable(t);
  const auto w10 = wide.find("### mobile, time limit 10 s\n"), w20 = wide.find("### mobile, time limit 20 s\n");
  REQUIRE(w10 != std::string::npos);
  REQUIRE(w20 != std::string::npos);
  CHECK(wide.find("| 4 | 1/1 5.00 | 0/1 | - | - | 100% |", w10) < w20);
  CHECK(wide.find("| 4 | 2/2 2.00 | 2/2 3.00 | 0.67 [0.50, 0.75] | 0.62 [0.50, 0.75] | - |", w20) != std::string::npos);
  CHECK(wide.find("### arms\n") != std::string::npos);
}

TEST_CASE("CSV has one quoted-as-needed row per trial under a header") {
  TrialRecord t = trial("arc", 0, false, 1);
  t.failure = "exit 2: bad \"input\", really";
  std::ostringstream out;
  writeCsv({t}, out);
  std::istringstream in(out.str());
  std::string header, row, extra;
  std::getline(in, header);
  std::getline(in, row);
  CHECK_FALSE(std::getline(in, extra));
  CHECK(header.rfind("suite,robots,method,trial,seed,", 0) == 0);
  CHECK(row.find("\"exit 2: bad \"\"input\"\", really\"") != std::string::npos);
}

TEST_CASE("a method run with planner arguments is named with them in the tables, the CSV and the OMPL logs") {
  std::vector<TrialRecord> t = {trial("earc", 0, true, 1), trial("earc", 1, true, 2), trial("arc", 0, true, 3),
                                trial("arc", 1, true, 4)};
  for (int i : {0, 1}) t[i].planner_args = {"--db-k=5", "--window", "4"};
  const std::string table = markdownTable(t, {});
  CHECK(table.find("\n| 4 | earc --db-k=5 --window 4 | 2/2 (100%) |") != std::string::npos);
  CHECK(table.find("\n| 4 | arc | 2/2 (100%) |") != std::string::npos);  // none: the plain name
  CHECK(markdownWideTable(t).find("\n| robots | earc --db-k=5 --window 4 | arc |") != std::string::npos);
  std::ostringstream csv;
  writeCsv(t, csv);
  const auto csv_lines = [&] {
    std::vector<std::string> out;
    std::istringstream in(csv.str());
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
  }();
  REQUIRE(csv_lines.size() == 5);
  CHECK(csv_lines[0].find(",planner_args,scenario_file,") != std::string::npos);
  CHECK(csv_lines[1].find(",--db-k=5 --window 4,") != std::string::npos);
  CHECK(csv_lines[1].rfind("mobile,4,earc,0,", 0) == 0);  // the method column stays the method
  const auto rows = csvByColumn(csv.str());
  CHECK(rows[0].at("planner_args") == "--db-k=5 --window 4");
  CHECK(rows[2].at("planner_args").empty());
  TempPath dir("earc-ompl-logs-args");
  writeOmplLogs(t, dir.path);
  const auto log = lines(dir.path + "/mobile-4.log");
  CHECK(std::count(log.begin(), log.end(), "earc --db-k=5 --window 4") == 1);
  CHECK(std::count(log.begin(), log.end(), "arc") == 1);

  // Quoted as a shell (and shlex.join) would take them; a '|' kept from
  // ending the markdown cell.
  t[0].planner_args = t[1].planner_args = {"--x=a|b c", "--y=it's"};
  CHECK(plannerArgsText(t[0].planner_args) == R"('--x=a|b c' '--y=it'"'"'s')");
  CHECK(markdownTable(t, {}).find(R"(| 4 | earc '--x=a\|b c' '--y=it'"'"'s' |)") != std::string::npos);
  // Trials that mix sets (a results file never does) are not named after one.
  t[1].planner_args.clear();
  CHECK(markdownTable(t, {}).find("| 4 | earc (several sets of planner arguments) |") != std::string::npos);
}

TEST_CASE("planner arguments that earc-bench sets itself, or that would stop or confuse every plan, are refused") {
  using Args = std::vector<std::string>;
  for (const Args& ok : {Args{}, Args{"--db-k=5"}, Args{"--window", "4"}, Args{"--db-max-stretch=4", "--shadow-decoupled"},
                         Args{"--dbx"}, Args{"--db-k", "-1"}})
    CHECK_FALSE(plannerArgsProblem(ok).has_value());
  const std::pair<Args, const char*> refused[] = {
      {{"--seed=3"}, "'--seed=3' sets what earc-bench gives earc-plan itself (the scenario, -o, --method,"},
      {{"--time-limit", "5"}, "'--time-limit' sets what earc-bench gives earc-plan itself"},
      {{"--db=x.sqlite"}, "'--db=x.sqlite' sets what"},
      {{"--output=x"}, "'--output=x' sets what"},
      {{"-ox.json"}, "'-ox.json' sets what"},
      {{"--method=arc"}, "'--method=arc' sets what"},
      {{"--no-learn"}, "'--no-learn' sets what"},
      {{"--quiet"}, "'--quiet' sets what"},
      {{"-q"}, "'-q' sets what"},
      {{"--help"}, "'--help' would stop every plan before it planned"},
      {{"-h"}, "'-h' would stop every plan"},
      {{"--version"}, "'--version' would stop every plan"},
      {{"--"}, "'--' ends earc-plan's options"},
      {{"s.json"}, "'s.json' is not an option (nor the value of one): the scenario is earc-bench's to give"},
      {{"--window=4", "s.json"}, "'s.json' is not an option"},
      {{""}, "an empty argument"},
      {{"--x=a\nb"}, "'--x=a?b' has a control character or a byte that is not UTF-8 text"},
      {{"--x=\xff"}, "'--x=?' has a control character or a byte that is not UTF-8 text"},
  };
  for (const auto& [args, says] : refused) {
    CAPTURE(args.front());
    const auto why = plannerArgsProblem(args);
    REQUIRE(why.has_value());
    CHECK_MESSAGE(why->rfind(says, 0) == 0, *why);
  }
  CHECK_THROWS_WITH_AS(requirePlannerArgs({"--seed=3"}, "--new-arg"),
                       doctest::Contains("--new-arg: '--seed=3' sets what earc-bench gives"), InputError);
  CHECK(plannerArgsText({}).empty());
  CHECK(plannerArgsText({"--db-k=5", "--window", "4", "@%+=:,./-_"}) == "--db-k=5 --window 4 @%+=:,./-_");
}

TEST_CASE("OMPL benchmark logs follow Benchmark::saveResultsToStream's layout") {
  TempPath dir("earc-ompl-logs");
  std::vector<TrialRecord> t = {trial("arc", 0, true, 2), trial("earc", 0, true, 1), trial("arc", 1, false, 60),
                                trial("arc", 0, true, 5, "arms", 2)};
  const auto files = writeOmplLogs(t, dir.path);
  REQUIRE(files.size() == 2);
  const auto l = lines(dir.path + "/mobile-4.log");
  REQUIRE(l.size() > 20);
  CHECK(l[0] == "earc-bench version 1");
  CHECK(l[1] == "Experiment mobile-4");
  CHECK(l[2] == "3 experiment properties");
  CHECK(l[6].rfind("Running on ", 0) == 0);
  CHECK(l[7].rfind("Starting at ", 0) == 0);
  CHECK(l[8] == "<<<|");
  std::size_t i = 9;
  while (l[i] != "|>>>") ++i;
  CHECK(l[++i] == "<<<|");
  CHECK(l[++i] == "|>>>");
  CHECK(l[++i] == "1 is the random seed");
  CHECK(l[++i] == "60 seconds per run");
  CHECK(l[++i].find(" MB per run") != std::string::npos);
  CHECK(l[++i] == "2 runs per planner");
  CHECK(l[++i].find(" seconds spent to collect the data") != std::string::npos);
  CHECK(l[++i] == "1 enum type");
  CHECK(l[++i].rfind("status|", 0) == 0);
  CHECK(l[++i] == "2 planners");
  CHECK(l[++i] == "earc");  // methods in the tables' order
  CHECK(l[++i] == "0 common properties");
  CHECK(l[++i] == "10 properties for each run");
  const std::size_t props = i + 1;
  CHECK(l[props + 7] == "time REAL");
  CHECK(l[props + 4] == "solved BOOLEAN");
  i = props + 10;
  CHECK(l[i] == "1 runs");
  // Every value followed by "; ", the time where "time REAL" says.
  const std::string run = l[++i];
  CHECK(run.substr(run.size() - 2) == "; ");
  CHECK(std::count(run.begin(), run.end(), ';') == 10);
  CHECK(l[++i] == ".");
  CHECK(l[++i] == "arc");
}

TEST_CASE("OMPL log names from odd suite names stay inside the directory; the suites' names stay as they are") {
  TempPath parent("earc-ompl-escape");
  const std::string dir = parent.path + "/a/b/logs";
  std::vector<TrialRecord> t;
  for (const std::string suite : {"../../escaped", "..", "x/y", "x_y", ".hidden", "a\nb"})
    t.push_back(trial("arc", 0, true, 1, suite));
  for (const Suite& s : allSuites()) t.push_back(trial("arc", 0, true, 1, s.name));
  const auto files = writeOmplLogs(t, dir);
  CHECK(files.size() == t.size());  // no two suites share a file
  std::set<std::string> names;
  for (const auto& e : std::filesystem::recursive_directory_iterator(parent.path))
    if (e.is_regular_file()) {
      CHECK(e.path().parent_path() == std::filesystem::path(dir));
      const std::string name = e.path().filename().string();
      CHECK(name[0] != '.');
      CHECK(name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") ==
            std::string::npos);
      names.insert(name);
    }
  CHECK(names.size() == t.size());
  for (const Suite& s : allSuites()) CHECK(names.count(s.name + "-4.log") == 1);
  // A line break in a name does not break the log's lines.
  int one_line = 0;
  for (const std::string& f : files)
    for (const std::string& line : lines(f)) {
      CHECK(line != "b");
      one_line += line == "suite TEXT = a b";
    }
  CHECK(one_line == 1);
}

TEST_CASE("export knows the OMPL logs' files before it writes them") {
  TempPath dir("earc-ompl-names");
  std::vector<TrialRecord> t = {trial("arc", 0, true, 1), trial("arc", 0, true, 1, "arms", 2),
                                trial("arc", 0, true, 1, "a/b")};
  t.push_back(trial("arc", 0, true, 1));
  t.back().time_limit_s = 30;  // two limits in one cell: -tl in the names
  const auto names = omplLogFiles(t, dir.path);
  CHECK(names == writeOmplLogs(t, dir.path));
  CHECK(std::count(names.begin(), names.end(), dir.path + "/mobile-4-tl30.log") == 1);
}

// earc-bench's counts and limits are checked as they are parsed.
