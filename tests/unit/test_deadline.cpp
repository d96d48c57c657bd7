// Deadlines whose budgets count work instead of seconds (earc-plan plan
// --deterministic): a budget ends after its units of work on the thread,
// however long they took, alone or nested in others.
#include <doctest/doctest.h>

#include <chrono>
#include <thread>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/composite.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

using namespace earc;

namespace {

// A budget of `units` of work, in the seconds capped() takes.
double secondsOfWork(double units) { return units / kWorkPerBudgetSecond; }

void sleepPastBudget() { std::this_thread::sleep_for(std::chrono::milliseconds(30)); }

}  // namespace

TEST_CASE("A work budget ends after its units of work, however long they took") {
  const Deadline d = Deadline().withWorkBudgets(true).capped(secondsOfWork(1000));
  CHECK(d.countsWork());
  sleepPastBudget();  // 30 ms, far beyond the budget's 1000 units in seconds
  CHECK_FALSE(d.expired());
  countWork(999);
  CHECK_FALSE(d.expired());
  CHECK(d.remaining() == doctest::Approx(secondsOfWork(1)));
  countWork(1);
  CHECK(d.workSpent());
  CHECK(d.expired());
  CHECK(d.remaining() == 0.0);
}

TEST_CASE("A budget in seconds still ends with the clock, doing no work") {
  const Deadline d = Deadline().capped(0.01);
  CHECK_FALSE(d.countsWork());
  sleepPastBudget();
  CHECK(d.expired());
  CHECK_FALSE(d.workSpent());
}

TEST_CASE("Nested budgets end at the earliest, work or seconds") {
  const Deadline outer = Deadline().withWorkBudgets(true).capped(secondsOfWork(500));
  // A larger inner budget does not outlast the outer one.
  const Deadline inner = outer.capped(1e6);
  countWork(499);
  CHECK_FALSE(inner.expired());
  countWork(1);
  CHECK(inner.expired());
  // A smaller one ends first.
  const Deadline outer2 = Deadline().withWorkBudgets(true).capped(secondsOfWork(500));
  const Deadline inner2 = outer2.capped(secondsOfWork(100));
  countWork(100);
  CHECK(inner2.expired());
  CHECK_FALSE(outer2.expired());
  // Capped in seconds inside a work budget: the work budget still holds.
  const Deadline mixed = Deadline().withWorkBudgets(true).capped(secondsOfWork(200)).withWorkBudgets(false).capped(1e6);
  countWork(200);
  CHECK(mixed.expired());
}

TEST_CASE("A poll of a work budget ends at its unit of work, not at its next clock read") {
  const Deadline d = Deadline().withWorkBudgets(true).capped(secondsOfWork(1000));
  DeadlinePoll poll(d, kWorkPerClockRead);  // reads the clock every 4096 units
  int steps = 0;
  while (!poll.expired(10)) ++steps;
  CHECK(steps == 99);  // the 100th step of 10 units spends the budget
  CHECK(poll.seenExpired());
}

TEST_CASE("A composite checker on a work budget calls states invalid after the same number of checks, slow or not") {
  Scenario s;
  s.name = "two";
  s.workspace = {{0, 0}, {10, 10}};
  for (int i = 0; i < 2; ++i) {
    RobotSpec r = RobotSpec::mobileBox("r" + std::to_string(i), {0.6, 0.4});
    r.start = {2.0 + 4 * i, 2, 0};
    r.goal = {2.0 + 4 * i, 8, 0};
    s.robots.push_back(r);
  }
  const RobotModels m(s);
  const CollisionWorld world(s);
  const CompositeState q = {{2, 2, 0}, {6, 2, 0}};
  auto validBeforeBudget = [&](bool slow) {
    // Two robots of dim 3: 6 units a state; a budget of 10 states.
    const Deadline d = Deadline().withWorkBudgets(true).capped(secondsOfWork(60));
    CompositeChecker checker(world, m.raw, d);
    int valid = 0;
    for (int i = 0; i < 20 && checker.stateValid(q); ++i) {
      ++valid;
      if (slow) sleepPastBudget();
    }
    return valid;
  };
  const int fast = validBeforeBudget(false);
  CHECK(fast == 9);  // the 10th state's work spends the budget
  CHECK(validBeforeBudget(true) == fast);
}
