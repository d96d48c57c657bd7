// earc-bench compare's statistics and picture: which scenarios are paired,
// the two ratios, the bootstrap interval, and one point per paired scenario.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "earc/bench/compare.hpp"
#include "earc/methods/plan.hpp"

using namespace earc::bench;

namespace {

ComparePlan solvedIn(double s) {
  ComparePlan p;
  p.solved = true;
  p.time_s = s;
  return p;
}

ComparePlan failed(const std::string& why) {
  ComparePlan p;
  p.failure = why;
  return p;
}

ComparePair pair(const std::string& scenario, int repeat, ComparePlan o, ComparePlan n, bool same = true) {
  ComparePair p;
  p.scenario = scenario;
  p.repeat = repeat;
  p.old_plan = o;
  p.new_plan = n;
  p.same_paths = same && o.solved && n.solved;
  return p;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("A comparison pairs the scenarios both sides solved in every repeat") {
  // Old times 1, 2, 4, 8 and new times half, equal, a quarter, equal:
  // ratios 0.5, 1, 0.25, 1. A fifth scenario the new side failed once
  // counts in the solved plans only.
  std::vector<ComparePair> pairs = {
      pair("a", 0, solvedIn(1.0), solvedIn(0.5), false),
      pair("b", 0, solvedIn(2.0), solvedIn(2.0)),
      pair("c", 0, solvedIn(4.0), solvedIn(1.0)),
      pair("d", 0, solvedIn(8.0), solvedIn(8.0)),
      pair("e", 0, solvedIn(3.0), failed("not solved")),
  };
  const CompareStats s = compareStats(pairs, 7);
  CHECK(s.scenarios == 5);
  CHECK(s.plans == 5);
  CHECK(s.old_solved == 5);
  CHECK(s.new_solved == 4);
  CHECK(s.paired == 4);
  CHECK(s.same_paths == 3);
  CHECK(s.invalid == 0);
  REQUIRE(s.paired_median);
  CHECK(*s.old_median_s == doctest::Approx(3.0));   // median of 1, 2, 4, 8
  CHECK(*s.new_median_s == doctest::Approx(1.5));   // of 0.5, 1, 2, 8
  CHECK(*s.of_medians == doctest::Approx(0.5));
  CHECK(*s.paired_median == doctest::Approx(0.75));  // of 0.25, 0.5, 1, 1
  // The interval holds the estimate and lies within the ratios' range.
  CHECK(*s.paired_lo <= *s.paired_median);
  CHECK(*s.paired_hi >= *s.paired_median);
  CHECK(*s.paired_lo >= 0.25);
  CHECK(*s.paired_hi <= 1.0);
  // It follows the seed, and only the seed.
  const CompareStats again = compareStats(pairs, 7);
  CHECK(*again.paired_lo == *s.paired_lo);
  CHECK(*again.paired_hi == *s.paired_hi);
}

TEST_CASE("A comparison gives the plans' makespan and sum of costs over the paired scenarios") {
  auto plan = [](double s, double makespan, double soc) {
    ComparePlan p = solvedIn(s);
    p.makespan = makespan;
    p.sum_of_costs = soc;
    return p;
  };
  // The third scenario is not paired: its long plan must not count.
  const CompareStats s = compareStats({pair("a", 0, plan(1, 10, 30), plan(1, 12, 31), false),
                                       pair("b", 0, plan(1, 20, 50), plan(1, 20, 50)),
                                       pair("c", 0, plan(1, 900, 900), failed("not solved"))},
                                      1);
  REQUIRE(s.old_makespan);
  CHECK(*s.old_makespan == doctest::Approx(15));
  CHECK(*s.new_makespan == doctest::Approx(16));
  CHECK(*s.old_sum_of_costs == doctest::Approx(40));
  CHECK(*s.new_sum_of_costs == doctest::Approx(40.5));
}

TEST_CASE("Repeated plans of a scenario count by their median") {
  // Old 1, 1, 10 (median 1); new 2, 2, 0.1 (median 2): ratio 2, though
  // the sums would say 12 against 4.1.
  std::vector<ComparePair> pairs = {
      pair("a", 0, solvedIn(1.0), solvedIn(2.0)),
      pair("a", 1, solvedIn(1.0), solvedIn(2.0)),
      pair("a", 2, solvedIn(10.0), solvedIn(0.1)),
  };
  const CompareStats s = compareStats(pairs, 1);
  CHECK(s.scenarios == 1);
  CHECK(s.plans == 3);
  REQUIRE(s.paired == 1);
  CHECK(*s.paired_median == doctest::Approx(2.0));
  CHECK(*s.paired_lo == doctest::Approx(2.0));
  CHECK(*s.paired_hi == doctest::Approx(2.0));
  // One failed repeat and the scenario is no longer paired.
  pairs[1].new_plan = failed("killed at the wall-clock limit (35 s)");
  CHECK(compareStats(pairs, 1).paired == 0);
  CHECK_FALSE(compareStats(pairs, 1).paired_median);
}

TEST_CASE("Invalid plans are counted, and nothing paired gives no ratio") {
  ComparePlan bad = failed("invalid solution: INVALID: robots r0 and r1 collide");
  bad.invalid = true;
  const CompareStats s = compareStats({pair("a", 0, bad, solvedIn(1.0))}, 1);
  CHECK(s.invalid == 1);
  CHECK(s.paired == 0);
  CHECK_FALSE(s.of_medians);
  CHECK_FALSE(s.paired_lo);
  CHECK(compareStats({}, 1).plans == 0);
}

TEST_CASE("The comparison's picture has a point per paired scenario, hollow where plans differed") {
  std::vector<ComparePair> pairs = {
      pair("a", 0, solvedIn(0.01), solvedIn(0.02), false),
      pair("b", 0, solvedIn(0.2), solvedIn(0.1)),
      pair("c", 0, solvedIn(3.0), solvedIn(2.0)),
      pair("d", 0, solvedIn(1.0), failed("not solved")),
  };
  const CompareStats s = compareStats(pairs, 1);
  const std::string svg = compareSvg(pairs, s, {"title here"});
  CHECK(svg.rfind("<svg", 0) == 0);
  CHECK(svg.find("</svg>") != std::string::npos);
  CHECK(count(svg, "<circle") == 3);
  CHECK(count(svg, "fill=\"white\" stroke=\"#d62728\"") == 1);
  CHECK(svg.find("title here") != std::string::npos);
  CHECK(svg.find("paired 0.67") != std::string::npos);  // of 2, 0.5 and 2/3
  // Decades 0.01 to 10 are labelled: every point is inside the axes.
  CHECK(svg.find(">0.01<") != std::string::npos);
  CHECK(svg.find(">10<") != std::string::npos);
  // Over three decades only the decades are labelled (the 2s and 5s ran
  // into each other); over two, 2 and 5 are too.
  CHECK(svg.find(">0.02<") == std::string::npos);
  CHECK(svg.find(">0.05<") == std::string::npos);
  const std::vector<ComparePair> narrow = {pair("a", 0, solvedIn(0.01), solvedIn(0.02)),
                                           pair("b", 0, solvedIn(0.2), solvedIn(0.1))};
  const std::string two = compareSvg(narrow, compareStats(narrow, 1), {"two decades"});
  CHECK(two.find(">0.02<") != std::string::npos);
  CHECK(two.find(">0.5<") != std::string::npos);
  // An empty comparison still draws its axes.
  CHECK(count(compareSvg({}, compareStats({}, 1), {"none"}), "<circle") == 0);
}

TEST_CASE("The comparison's picture says how many plans each side failed, and what was compared, escaped") {
  // Old fails two of four plans: its failures have no point, and the
  // subtitle once said only "2 scenarios solved by both".
  const std::vector<ComparePair> pairs = {
      pair("a", 0, solvedIn(0.5), solvedIn(0.1)), pair("b", 0, failed("not solved: time_limit"), solvedIn(0.2)),
      pair("c", 0, solvedIn(0.4), solvedIn(0.1)), pair("d", 0, failed("not solved: time_limit"), solvedIn(0.3))};
  const std::string svg = compareSvg(pairs, compareStats(pairs, 1),
                                     {"earc-bench compare: mobile-obst, 8 robots, 4 scenarios, time limit 1 s",
                                      "old: coupled (earc 1)", "new: arc --window=<30> & more (earc 1)"});
  CHECK(svg.find(">failed: old 2 of 4 plans, new 0 of 4; 2 scenarios solved by both</text>") != std::string::npos);
  CHECK(svg.find(">earc-bench compare: mobile-obst, 8 robots, 4 scenarios, time limit 1 s</text>") != std::string::npos);
  CHECK(svg.find(">old: coupled (earc 1)</text>") != std::string::npos);
  CHECK(svg.find(">new: arc --window=&lt;30&gt; &amp; more (earc 1)</text>") != std::string::npos);
  CHECK(count(svg, "<circle") == 2);
  // The heading lines lie above the axes' square.
  const auto square = svg.find("<rect x=");
  const double square_top = std::stod(svg.substr(svg.find(" y=\"", square) + 4));
  for (auto at = svg.find("<text"); at < square; at = svg.find("<text", at + 1))
    CHECK(std::stod(svg.substr(svg.find(" y=\"", at) + 4)) < square_top);
}
