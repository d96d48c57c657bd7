#include "earc/service/service.hpp"

#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/methods/database_solver.hpp"
#include "earc/methods/options.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/planner.hpp"
#include "earc/scene/pass_through.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/format.hpp"
#include "earc/util/memory_reserve.hpp"
#include "earc/validate/scenario_check.hpp"

namespace earc::service {

using nlohmann::json;

namespace {

// Error messages quote what the client sent, which need not be UTF-8:
// never let the reply itself fail to encode.
std::string dumpLine(const json& doc) { return dumpCompact(doc); }

// obj printed as dumpLine prints it, with one more member `key` whose
// value extra(text) appends (nlohmann::json prints members in key order).
template <class Extra>
std::string dumpWith(const json& obj, const std::string& key, Extra&& extra) {
  std::string text = "{";
  auto member = [&](const std::string& k) {
    if (text.size() > 1) text += ',';
    text += dumpLine(json(k)) + ":";
  };
  bool added = false;
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    if (!added && it.key() > key) {
      member(key);
      extra(text);
      added = true;
    }
    member(it.key());
    text += dumpLine(it.value());
  }
  if (!added) {
    member(key);
    extra(text);
  }
  return text + "}";
}

const json& field(const json& request, const char* name) {
  static const json missing;
  auto it = request.find(name);
  return it == request.end() ? missing : *it;
}

// A whole number >= 0, parsed (unsigned) or built in code (a signed int).
std::optional<std::uint64_t> wholeNumber(const json& v) {
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_number_integer() && v.get<std::int64_t>() >= 0) return static_cast<std::uint64_t>(v.get<std::int64_t>());
  return std::nullopt;
}

InputError badField(const std::string& name, const std::string& reason) {
  return InputError("request", "$." + name, reason);
}

// The request's options, typed here (the protocol's messages), then checked
// as every front end checks them (plannerSettingsFor).
PlannerSettings settingsFrom(const json& request, const ServiceSettings& defaults) {
  MethodOptions o;
  o.method = defaults.method;
  if (const json& method = field(request, "method"); !method.is_null()) {
    if (!method.is_string()) throw badField("method", "must be a string");
    o.method = method.get<std::string>();
  }
  o.time_limit = defaults.time_limit_s;
  if (const json& t = field(request, "time_limit"); !t.is_null()) {
    if (!t.is_number() || !std::isfinite(t.get<double>()) || !(t.get<double>() > 0))
      throw badField("time_limit", "must be a positive number of seconds");
    o.time_limit = t.get<double>();
  }
  o.seed = defaults.seed;
  if (const json& k = field(request, "seed"); !k.is_null()) {
    const auto seed = wholeNumber(k);
    if (!seed) throw badField("seed", "must be a whole number >= 0");
    o.seed = *seed;
  }
  if (const json& l = field(request, "learn"); !l.is_null()) {
    if (!l.is_boolean()) throw badField("learn", "must be true or false");
    o.learn = l.get<bool>();
  }
  // The service's default leaves Lightning alone; a request's is refused for it.
  o.deterministic = defaults.deterministic && o.method != methodName(Method::Lightning);
  if (const json& d = field(request, "deterministic"); !d.is_null()) {
    if (!d.is_boolean()) throw badField("deterministic", "must be true or false");
    o.deterministic = d.get<bool>();
  }
  if (const json& c = field(request, "compact"); !c.is_null()) {
    if (!c.is_boolean()) throw badField("compact", "must be true or false");
    o.compact = c.get<bool>();
  }
  if (const json& r = field(request, "refine"); !r.is_null()) {
    if (!r.is_number() || !std::isfinite(r.get<double>()) || r.get<double>() < 0)
      throw badField("refine", "must be a number of seconds >= 0 (0: off)");
    o.refine = r.get<double>();
  }
  if (const json& w = field(request, "window"); !w.is_null()) {
    const auto steps = wholeNumber(w);
    if (!steps || *steps == 0 || *steps > 1000000)
      throw badField("window", "must be a whole number of steps from 1 to 1000000");
    o.window = static_cast<int>(*steps);
  }
  // E-ARC's retrieval settings, as earc-plan plan's --db-k, --db-repair-max
  // and --db-max-stretch (for another method refused by plannerSettingsFor).
  for (auto [name, target, least] : {std::tuple{"db_k", &o.db_k, 1}, std::tuple{"db_repair_max", &o.db_repair_max, 0}})
    if (const json& v = field(request, name); !v.is_null()) {
      const auto n = wholeNumber(v);
      if (!n || *n < static_cast<std::uint64_t>(least) || *n > 1000)
        throw badField(name, "must be a whole number from " + std::to_string(least) + " to 1000");
      *target = static_cast<int>(*n);
    }
  if (const json& f = field(request, "db_max_stretch"); !f.is_null()) {
    if (!f.is_number() || !std::isfinite(f.get<double>()) || f.get<double>() < 0)
      throw badField("db_max_stretch", "must be a number >= 0 (0: any length)");
    o.db_max_stretch = f.get<double>();
  }
  return plannerSettingsFor(o, OptionStyle::Request);
}

// Warnings about the scenario (unknown keys and the like) go to `warnings`.
Scenario scenarioFrom(const json& request, InputWarnings& warnings) {
  const json& inline_doc = field(request, "scenario");
  const json& file = field(request, "scenario_file");
  if (inline_doc.is_null() == file.is_null())
    throw InputError("request", "", "give exactly one of \"scenario\" (an object) and \"scenario_file\" (a path)");
  if (!file.is_null()) {
    if (!file.is_string() || file.get<std::string>().empty())
      throw badField("scenario_file", "must be a file name");
    // Requests are answered one at a time: a FIFO would hold up every
    // client until someone wrote to it.
    std::error_code ec;
    const auto st = std::filesystem::status(file.get<std::string>(), ec);
    if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st) && !std::filesystem::is_directory(st))
      throw InputError(file.get<std::string>(), "scenario_file", "not a regular file (a device, FIFO or socket)");
    return requireRobots(loadScenario(file.get<std::string>(), &warnings), file.get<std::string>());
  }
  if (!inline_doc.is_object()) throw badField("scenario", "must be a scenario object (earc.scenario.v1)");
  // Errors name "scenario" and the JSON path inside it.
  InputWarnings found;
  Scenario s = scenarioFromJson(inline_doc, "scenario", &found);
  checkScenarioGeometry(s, "scenario");
  warnings.insert(warnings.end(), found.begin(), found.end());
  return requireRobots(std::move(s), "scenario");
}

void requireKnownKeys(const json& request, const std::set<std::string>& known) {
  for (const auto& [key, value] : request.items())
    if (!known.count(key)) throw InputError("request", "$." + key, "unknown key for op \"" +
                                                                      request.value("op", std::string("plan")) + "\"");
}

}  // namespace

Service::Service(std::shared_ptr<exp::ExperienceStore> store, ServiceSettings settings, StopFlag* stop)
    : store_(std::move(store)),
      settings_(std::move(settings)),
      started_(std::chrono::steady_clock::now()),
      stop_(stop ? stop : &own_stop_) {
  methodFromName(settings_.method);  // throws std::invalid_argument for a bad default
  if (settings_.roadmap_cache_mib > 0)
    roadmaps_ = std::make_unique<RoadmapCache>(settings_.roadmap_cache_mib * (std::size_t{1} << 20));
}

Service::~Service() = default;

std::string Service::handleLine(std::string_view line) {
  json request;
  try {
    request = parseJsonText(std::string(line), "request");
  } catch (const std::exception& e) {
    ++counters_.requests;
    return dumpLine(error(nullptr, e.what()));
  }
  // A crowd's paths are millions of numbers: printed straight from the
  // plan, not built as a JSON tree first.
  Solution solution;
  json out = respond(request, &solution);
  const auto at = out.find("solution");
  if (at == out.end()) return dumpLine(out);
  const json head = std::move(*at);
  out.erase(at);
  return dumpWith(out, "solution", [&](std::string& text) {
    text += dumpWith(head, "paths", [&](std::string& inner) { appendSolutionPaths(inner, solution); });
  });
}

std::string Service::tooLongResponse() {
  ++counters_.requests;
  return dumpLine(error(nullptr, "request: longer than " + std::to_string(kMaxRequestBytes) +
                                     " bytes: not read (send a scenario_file instead)"));
}

json Service::handle(const json& request) { return respond(request, nullptr); }

json Service::respond(const json& request, Solution* paths) {
  ++counters_.requests;
  const json id = request.is_object() ? field(request, "id") : json();
  try {
    if (!request.is_object()) throw InputError("request", "", "must be a JSON object");
    const json& op = field(request, "op");
    if (!op.is_null() && !op.is_string()) throw badField("op", "must be a string");
    const std::string name = op.is_null() ? "plan" : op.get<std::string>();
    json response;
    if (name == "plan") {
      requireKnownKeys(request, {"id", "op", "scenario", "scenario_file", "method", "time_limit", "seed", "learn",
                                 "deterministic", "compact", "refine", "window", "db_k", "db_repair_max", "db_max_stretch"});
      response = plan(request, paths);
    } else if (name == "ping") {
      requireKnownKeys(request, {"id", "op"});
      response = {{"ok", true}, {"protocol", kProtocol}};
    } else if (name == "stats") {
      requireKnownKeys(request, {"id", "op"});
      response = {{"ok", true}, {"stats", stats()}};
    } else {
      throw badField("op", "unknown op \"" + name + "\" (plan, ping, stats)");
    }
    json out = {{"id", id}};
    out.update(response);
    return out;
  } catch (const InputError& e) {
    return error(id, e.what());
  } catch (const std::bad_alloc& e) {
    json out = error(id, outOfMemoryMessage(e, "while handling the request"));
    armMemoryReserve();  // given back to let this request unwind; set aside for the next
    return out;
  } catch (const std::exception& e) {
    // Not the client's fault (a database error, say): said as it is.
    return error(id, std::string("internal error: ") + e.what());
  }
}

json Service::plan(const json& request, Solution* paths) {
  InputWarnings read_warnings;
  Scenario scenario = scenarioFrom(request, read_warnings);
  const PlannerSettings s = settingsFrom(request, settings_);
  PlanContext context;
  context.roadmap_cache = roadmaps_.get();
  context.stop = stop_;
  if (s.method == Method::Earc && !store_)
    throw badField("method", "method earc needs the service to have an experience database");
  // Rows other processes committed since the last request.
  std::size_t entries_before = 0;
  if (store_) {
    store_->refresh();
    entries_before = store_->size();
  }
  // What earc-plan plan says on stderr, given with the answer (only when
  // there is something to say); before planning, which may learn.
  json warnings = json::array();
  for (const InputWarning& w : read_warnings) warnings.push_back(w.text());
  if (const std::string w = passThroughWarning(scenario); !w.empty()) warnings.push_back(w);
  if (s.method == Method::Earc)
    if (const std::string w = exp::noClassFitsWarning(*store_, scenario, store_->path()); !w.empty())
      warnings.push_back(w);
  ++counters_.plans;
  Stopwatch clock;
  PlanResult r = earc::plan(scenario, s, s.method == Method::Earc ? store_.get() : nullptr, context);
  const bool interrupted = stopSet(stop_);
  if (r.stats.db) counters_.learned += r.stats.db->db_learned;
  if (s.method == Method::Earc) {
    counters_.db += databaseAnswers(r.stats);
    if (r.stats.db) counters_.db_refused_too_long += r.stats.db->db_refused_too_long;
  }
  json st = r.stats.toJson();
  st["request_s"] = clock.seconds();
  if (store_) {
    st["db_entries_before"] = entries_before;
    st["db_entries"] = store_->size();
  }
  json out = {{"ok", true}, {"solved", r.solution.solved}, {"interrupted", interrupted}};
  if (!warnings.empty()) out["warnings"] = std::move(warnings);
  if (r.solution.solved) {
    ++counters_.solved;
    out["solution"] = solutionToJson(r.solution, paths == nullptr);
    if (paths) *paths = std::move(r.solution);
  }
  out["stats"] = std::move(st);
  return out;
}

json Service::stats() {
  json st = {{"protocol", kProtocol},
             {"requests", counters_.requests},
             {"plans", counters_.plans},
             {"solved", counters_.solved},
             {"errors", counters_.errors},
             {"learned", counters_.learned},
             {"uptime_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count()}};
  if (roadmaps_)
    st["roadmap_cache"] = {{"roadmaps", roadmaps_->size()},
                           {"bytes", roadmaps_->bytes()},
                           {"capacity_bytes", roadmaps_->capacity()},
                           {"reused", roadmaps_->hits()},
                           {"built", roadmaps_->misses()}};
  if (store_) {
    store_->refresh();
    st["db"] = store_->path();
    st["db_entries"] = store_->size();
    st["db_session"] = store_->session();
    const ServiceCounters& c = counters_;
    st["db_subproblems"] = c.db.solved;
    st["db_answered"] = c.db.answered();
    st["db_hit_rate"] = c.db.hitRate();
    st["db_refused_too_long"] = c.db_refused_too_long;
  }
  return st;
}

json Service::error(const json& id, const std::string& message) {
  ++counters_.errors;
  return {{"id", id}, {"ok", false}, {"error", oneLine(message)}};
}

void Service::close() {
  if (store_) store_->close();
}

std::vector<LineSplitter::Line> LineSplitter::feed(std::string_view bytes) {
  std::vector<Line> out;
  while (!bytes.empty()) {
    const std::size_t nl = bytes.find('\n');
    const std::string_view part = bytes.substr(0, nl);
    if (!skipping_) {
      if (buffer_.size() + part.size() > max_) {
        // Report once, then drop everything up to the newline.
        out.push_back({std::string(), true});
        buffer_.clear();
        skipping_ = true;
      } else {
        buffer_.append(part);
      }
    }
    if (nl == std::string_view::npos) break;
    if (skipping_) skipping_ = false;
    else emit(out);
    bytes.remove_prefix(nl + 1);
  }
  return out;
}

std::vector<LineSplitter::Line> LineSplitter::finish() {
  std::vector<Line> out;
  if (!skipping_) emit(out);
  skipping_ = false;
  buffer_.clear();
  return out;
}

void LineSplitter::emit(std::vector<Line>& out) {
  if (!buffer_.empty() && buffer_.back() == '\r') buffer_.pop_back();
  if (buffer_.find_first_not_of(" \t") != std::string::npos) out.push_back({std::move(buffer_), false});
  buffer_.clear();
}

}  // namespace earc::service
