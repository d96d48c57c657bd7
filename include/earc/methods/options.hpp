// A plan's options as a user gives them (`earc-plan plan`, Python's
// earc.plan), checked and turned into PlannerSettings.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "earc/planning/planner.hpp"

namespace earc {

struct MethodOptions {
  std::string method = "arc";
  double time_limit = 60.0;
  std::uint64_t seed = 1;
  std::string db;            // E-ARC's experience database, Lightning's database
  bool trace = false;
  std::optional<int> window;
  bool learn = true;
  bool deterministic = false;
  bool crowd = true;
  bool compact = false;
  double refine = 0.0;
  bool shadow_decoupled = false;
  std::optional<int> db_k, db_repair_max;
  std::optional<double> db_max_stretch;
};

// How an option is named in errors: `earc-plan`'s "--db-k" (Cli) or
// Python's "db_k" (Python).
enum class OptionStyle { Cli, Python };
std::string optionName(const char* key, OptionStyle style);

// The settings for o, after the checks every front end shares (an option
// of another method, --deterministic for Lightning, earc without a
// database); InputError naming the option. Touches no file.
PlannerSettings plannerSettingsFor(const MethodOptions& o, OptionStyle style);

}  // namespace earc
