// The plan viewer: one self-contained HTML page (inline script, style and
// data; no network access) that animates a solution on its scenario and,
// given a planner trace, shows where conflicts were found and which
// subproblems resolved them. The page's sources live in tools/viewer/ and
// are embedded into the library (tools/viewer/embed.sh).
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>

#include "earc/scene/scenario.hpp"
#include "earc/scene/solution.hpp"

namespace earc::view {

inline constexpr const char* kTraceFormat = "earc.trace.v1";

// States are written to the page rounded to this quantum (4 decimals): the
// picture cannot show finer, and 128 robots x 5,000 steps stay a few MB.
inline constexpr double kStateQuantum = 1e-4;

// Checks that a solution belongs to the scenario (its name, one path per
// robot of the right dimension unless it has none). Throws InputError naming `file`.
void checkSolutionMatches(const Scenario& scenario, const Solution& solution, const std::string& file);

// Reads an earc.trace.v1 document into the fields the page shows, numbers
// rounded; unknown events skipped. Throws InputError naming `file` and the
// JSON path for a robot or conflict the trace does not have.
nlohmann::json traceFromJson(const nlohmann::json& doc, const Scenario& scenario, const std::string& file);
nlohmann::json loadTrace(const std::string& path, const Scenario& scenario);

// Everything the page draws as one JSON value: the scenario, the paths
// quantized and delta-coded (encodePath), stats and trace (null without
// one). Call checkSolutionMatches first.
nlohmann::json viewerData(const Scenario& scenario, const Solution& solution, const nlohmann::json& trace);

// A path as integers in units of kStateQuantum: the first state as is, then
// each state's difference from the previous one (waiting robots cost "0,").
// The page decodes it with running sums, so no rounding error accumulates.
nlohmann::json encodePath(const Path& path);

// The complete HTML page for viewerData's value.
std::string viewerHtml(const nlohmann::json& data);

// The page's sources as embedded at build time, by file name under
// tools/viewer/ (a unit test checks they are up to date).
struct Asset {
  const char* name;
  std::string_view text;
};
std::span<const Asset> viewerAssets();

}  // namespace earc::view
