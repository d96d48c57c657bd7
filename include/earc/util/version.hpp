// Which build of earc this is, so that every plan and every benchmark
// figure can be traced to the code that made it: `--version` of every
// program, the `earc_version` of a solution's stats, the `planner_version`
// of a benchmark trial.
#pragma once
#include <string_view>

namespace earc {

// The project's version and, when built from a git checkout, its commit:
// "0.1.0+66772d4"; "0.1.0+66772d4.dirty" when tracked files differed from
// that commit; "0.1.0" from a tree without git (tools/version.cmake).
std::string_view version();

}  // namespace earc
