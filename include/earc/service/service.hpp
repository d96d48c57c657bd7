// The planner service behind `earc-plan serve`: one long-running process
// that keeps an experience store open (its k-d indexes warm) and answers
// planning requests, one JSON object per line in, one per line out
// (protocol earc.service.v1, documented in docs/service.md).
//
// Requests (unknown keys are refused, so a misspelt option never passes
// silently):
//   {"id": any, "op": "plan" (default),
//    "scenario": {earc.scenario.v1} | "scenario_file": "path",
//    "method": "earc"|"arc"|"prioritized"|"coupled"|"lightning",
//    "time_limit": seconds > 0, "seed": integer >= 0, "learn": bool,
//    "window": steps > 0,
//    method earc only: "db_k": 1..1000, "db_repair_max": 0..1000,
//    "db_max_stretch": number >= 0}
//   {"id": any, "op": "ping"}
//   {"id": any, "op": "stats"}
// Responses echo "id" (null when the request had none or was unreadable):
//   {"id":..., "ok": true, "solved": bool, "interrupted": bool,
//    "solution": {earc.solution.v1, only when solved},
//    "warnings": ["one line", ...: only when there are any], "stats": {...}}
//   {"id":..., "ok": false, "error": "one line"}
// Planning goes through earc::plan(), so a solution reported solved has
// passed the validator. The store is refreshed before every request, so
// experiences other processes committed since are used; what E-ARC learns
// is committed before the response is written, and its row ids are listed
// in stats.db_learned_ids.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "earc/methods/database_solver.hpp"
#include "earc/util/deadline.hpp"

namespace earc::exp { class ExperienceStore; }

namespace earc::service {

inline constexpr const char* kProtocol = "earc.service.v1";
// A longer request line is answered with an error and skipped.
inline constexpr std::size_t kMaxRequestBytes = std::size_t{64} << 20;

struct ServiceSettings {
  std::string method = "earc";  // for requests that name none
  double time_limit_s = 60.0;
  std::uint64_t seed = 1;
  bool deterministic = false;   // work budgets (PlannerSettings::work_budgets)
  // Roadmaps kept between requests (PlanContext::roadmap_cache), at
  // most this many MiB; 0 keeps none.
  std::size_t roadmap_cache_mib = 256;
};

// Counters over the service's life (op "stats").
struct ServiceCounters {
  std::int64_t requests = 0;  // lines answered, errors included
  std::int64_t plans = 0;     // planning requests that ran
  std::int64_t solved = 0;
  std::int64_t errors = 0;    // responses with ok false
  std::int64_t learned = 0;   // experiences inserted
  // Over method earc's plans: the subproblems solved and how many of them
  // the database answered (as retrieved or repaired), and answers refused
  // as too long (db_max_stretch).
  DatabaseAnswers db;
  std::int64_t db_refused_too_long = 0;
};

class Service {
 public:
  // store may be null (then method earc is refused per request). stop: the
  // stop request its plans watch (PlanContext::stop), its own when null.
  Service(std::shared_ptr<exp::ExperienceStore> store, ServiceSettings settings, StopFlag* stop = nullptr);
  ~Service();
  Service(const Service&) = delete;
  Service& operator=(const Service&) = delete;

  // One request line in, one response line out (compact JSON, no newline).
  // Never throws for anything a client sends.
  std::string handleLine(std::string_view line);
  // The same for a parsed request.
  nlohmann::json handle(const nlohmann::json& request);
  // The response to a line that was too long to read (kMaxRequestBytes).
  std::string tooLongResponse();

  const ServiceCounters& counters() const { return counters_; }
  // Stops the plan in flight and every later one (answered "interrupted")
  // until clearStop(). Both thread-safe and async-signal-safe.
  void requestStop() noexcept { stop_->store(true, std::memory_order_relaxed); }
  void clearStop() noexcept { stop_->store(false, std::memory_order_relaxed); }
  // Writes pending usage counters, checkpoints and closes the store.
  // Throws when the store cannot be closed cleanly.
  void close();

 private:
  // paths: when given, a solved plan's solution is moved there and the
  // response's "solution" has no "paths" (handleLine prints them).
  nlohmann::json respond(const nlohmann::json& request, Solution* paths);
  nlohmann::json plan(const nlohmann::json& request, Solution* paths);
  nlohmann::json stats();
  nlohmann::json error(const nlohmann::json& id, const std::string& message);

  std::shared_ptr<exp::ExperienceStore> store_;
  ServiceSettings settings_;
  std::unique_ptr<RoadmapCache> roadmaps_;  // null: none kept
  ServiceCounters counters_;
  std::chrono::steady_clock::time_point started_;
  StopFlag own_stop_{false};
  StopFlag* stop_;  // own_stop_ or the one given
};

// Splits a byte stream into lines ('\n', a trailing '\r' dropped, blank
// lines skipped); a line over the limit is reported once (too_long) and
// skipped, never buffered whole. Not thread-safe.
class LineSplitter {
 public:
  explicit LineSplitter(std::size_t max_line = kMaxRequestBytes) : max_(max_line) {}
  struct Line {
    std::string text;
    bool too_long = false;
  };
  std::vector<Line> feed(std::string_view bytes);
  // At end of input: the last line when it had no newline.
  std::vector<Line> finish();

 private:
  void emit(std::vector<Line>& out);
  std::size_t max_;
  std::string buffer_;
  bool skipping_ = false;
};

}  // namespace earc::service
