// The cache of timed paths' states behind compaction and ARC's stamping:
// each robot's state filled only when asked for, once per instant kept.
#include <doctest/doctest.h>

#include <vector>

#include "../../src/planning/compact_states.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/scene/robot_model.hpp"
#include "support.hpp"

using namespace earc;

namespace compact_states_test {

std::vector<double> stateOf(const RobotModel& m, const Path& p, std::size_t k) {
  std::vector<double> q(static_cast<std::size_t>(m.dim()));
  stateAtInstant(m, p, k, q.data());
  return q;
}

std::vector<double> copied(const RobotModel& m, const double* q) { return {q, q + m.dim()}; }

}  // namespace compact_states_test

TEST_CASE("Cached instant states are filled robot by robot when asked, and again after forget") {
  namespace cs = compact_states_test;
  Scenario s;
  s.workspace = {{0, 0}, {12, 12}};
  for (const char* name : {"a", "b"}) {
    RobotSpec r = RobotSpec::mobileDisc(name, 0.3);
    r.start = r.goal = {1, 1, 0};
    s.robots.push_back(r);
  }
  const RobotModels models(s);
  const RobotModel& m = *models.raw[0];
  Path a = test::line({1, 1, 0}, {1, 9, 0}, 161);
  const Path b = test::line({9, 1, 0}, {9, 9, 0}, 161);
  InstantStates states;
  // b seen from its step 3 on, standing still after local instant 4.
  states.assign({{&m, &a}, {&m, &b, 3, 4}}, 4);
  const std::uint64_t w0 = t_work_done;
  CHECK(cs::copied(m, states.at(0, 7)) == cs::stateOf(m, a, 7));
  CHECK(t_work_done - w0 == 1);  // only a's state at 7
  CHECK(cs::copied(m, states.at(0, 7)) == cs::stateOf(m, a, 7));
  CHECK(t_work_done - w0 == 1);  // kept
  CHECK(cs::copied(m, states.at(1, 7)) == cs::stateOf(m, b, 6 + 4));
  CHECK(cs::copied(m, states.at(1, 2)) == cs::stateOf(m, b, 6 + 2));
  CHECK(t_work_done - w0 == 3);
  // Instant 11 takes 7's slot: a's state there is filled again.
  CHECK(cs::copied(m, states.at(0, 11)) == cs::stateOf(m, a, 11));
  CHECK(cs::copied(m, states.at(0, 7)) == cs::stateOf(m, a, 7));
  CHECK(t_work_done - w0 == 5);
  // A changed path is read again once forgotten.
  const Path a_before = a;
  a = test::line({2, 1, 0}, {2, 9, 0}, 161);
  states.forget(0);
  CHECK(cs::copied(m, states.at(0, 7)) == cs::stateOf(m, a, 7));
  CHECK(cs::copied(m, states.at(0, 7)) != cs::stateOf(m, a_before, 7));
  CHECK(t_work_done - w0 == 6);
}
