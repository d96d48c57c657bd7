// plan(): every planning method behind one call (`earc-plan plan`).
#pragma once

#include "earc/planning/planner.hpp"

namespace earc {

// Plans with settings.method; the store is used (and learned into) only by
// Method::Earc. Solved only if validateSolution passed. Thread-safe for
// distinct stores and contexts (a context's stop flag may be shared).
PlanResult plan(const Scenario& scenario, const PlannerSettings& settings, exp::ExperienceStore* store = nullptr,
                const PlanContext& context = {});

// plan() with a store opened with check_in_background, then its check's
// verdict: DamagedDatabaseError is thrown; a write lost to the disk or
// server (WriteLostError) goes to stats.db_learn_error and the file's stats.
PlanResult planThenAwaitCheck(const Scenario& scenario, const PlannerSettings& settings, exp::ExperienceStore& store,
                              const PlanContext& context = {});

}  // namespace earc
