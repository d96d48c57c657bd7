// plan(): every planning method behind one call (`earc-plan plan`).
#pragma once

#include "earc/planning/planner.hpp"

namespace earc {

// Plans with settings.method; the store is used (and learned into) only by
// Method::Earc (nullptr otherwise). Solved only if validateSolution passed,
// else FailureCause::InvalidResult. Thread-safe for distinct settings.
PlanResult plan(const Scenario& scenario, const PlannerSettings& settings,
                exp::ExperienceStore* store = nullptr);

}  // namespace earc
