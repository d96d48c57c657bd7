// The planning-layer methods behind plan() (methods/plan.hpp), each
// callable on its own; E-ARC and Lightning are in the methods layer.
#pragma once

#include <memory>
#include <vector>

#include "earc/planning/planner.hpp"
#include "earc/planning/solver.hpp"

namespace earc {

// ARC's hierarchy: decoupled (prioritized space-time) first, then coupled,
// both holding parked robots first when `arc` says so.
std::vector<std::unique_ptr<SubproblemSolver>> arcHierarchy(const ArcSettings& arc = {});

// Whole-problem prioritized planning in space-time over the roadmaps.
PlanResult planPrioritized(const Scenario& scenario, const PlannerSettings& settings,
                           const PlanContext& context = {});
// Whole-problem RRT-Connect in the composite space of all robots.
PlanResult planCoupled(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context = {});
// The crowd solver (LaCAM over a lattice roadmap, lacam.hpp) on the whole problem.
PlanResult planLacam(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context = {});

}  // namespace earc
