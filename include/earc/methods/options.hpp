// A plan's options as a user gives them (`earc-plan plan`, Python's
// earc.plan, a request to `earc-plan serve`), checked and turned into
// PlannerSettings: the one place every front end builds them.
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
  bool retime_windows = false;
  bool restamp_coupled = false;
  double refine = 0.0;
  bool shadow_decoupled = false;
  std::optional<int> db_k, db_repair_max;
  std::optional<double> db_max_stretch;
};

// How an option is named in errors: `earc-plan`'s "--db-k" (Cli),
// Python's "db_k" (Python) or a service request's "$.db_k" (Request).
enum class OptionStyle { Cli, Python, Request };
std::string optionName(const char* key, OptionStyle style);

// The settings for o, after the checks every front end shares (a method
// name, an option of another method, --deterministic for Lightning).
// Throws InputError naming the option (source "request" for Request).
PlannerSettings plannerSettingsFor(const MethodOptions& o, OptionStyle style);

}  // namespace earc
