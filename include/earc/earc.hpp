// earc as a library: one include to load a scenario, plan it, validate the
// plan and open, fill or export an experience store.
//
//   earc::Scenario s = earc::loadScenario("scenario.json");  // throws InputError
//   earc::PlannerSettings settings;                           // method, seed, limits
//   earc::PlanResult r = earc::plan(s, settings);             // validated when solved
//   if (r.stats.arc) r.stats.arc->conflicts;                  // typed statistics (PlanStats)
//   earc::ValidationReport v = earc::validateSolution(s, r.solution);
//   earc::exp::ExperienceStore store("experience.sqlite");    // for Method::Earc
#pragma once

#include "earc/experience/store.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/methods/builder.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/planner.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/scene/solution.hpp"
#include "earc/util/version.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/validate/validator.hpp"
