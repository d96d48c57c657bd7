// Reading a planner trace (earc.trace.v1) for the viewer. The planner
// writes it (src/planning/arc.cpp); the viewer trusts nothing in it: every
// robot index and reference is checked, since a trace from another
// scenario would otherwise draw nonsense or break the page.
#include <cmath>
#include <set>

#include "../io/json_reader.hpp"
#include "earc/io/json_io.hpp"
#include "earc/view/viewer.hpp"

namespace earc::view {
namespace {

using io::element;
using io::json;
using io::member;

// Seconds are shown with microsecond resolution; places and windows with
// the states' 4 decimals.
constexpr double kSecondsQuantum = 1e-6;

double rounded(double v, double quantum) { return std::round(v / quantum) * quantum; }

class TraceReader {
 public:
  TraceReader(const std::string& file, std::size_t robots) : r_(file), robots_(robots) {}

  json read(const json& doc) {
    r_.object(doc, "$");
    r_.format(doc, kTraceFormat);
    const json& events = r_.array(r_.required(doc, "events", "$"), "$.events");
    json conflicts = json::array(), subproblems = json::array();
    for (std::size_t i = 0; i < events.size(); ++i) {
      const std::string p = element("$.events", i);
      const json& ev = r_.object(events[i], p);
      const std::string type = r_.string(r_.required(ev, "type", p), member(p, "type"));
      if (type == "conflict") conflicts.push_back(conflict(ev, p));
      else if (type == "subproblem") subproblems.push_back(subproblem(ev, p));
    }
    return {{"conflicts", std::move(conflicts)}, {"subproblems", std::move(subproblems)}};
  }

 private:
  long long count(const json& v, const std::string& p) const {
    const double x = r_.nonNegative(v, p);
    if (x != std::floor(x) || x > 1e15) r_.fail(p, "expected a whole number, got " + io::formatNumber(x));
    return static_cast<long long>(x);
  }
  long long optionalCount(const json& ev, const char* key, const std::string& p) const {
    const json* v = r_.optional(ev, key, true);
    return v ? count(*v, member(p, key)) : 0;
  }
  double step(const json& v, const std::string& p) const { return rounded(r_.nonNegative(v, p), kStateQuantum); }
  json vec2(const json& v, const std::string& p) const {
    const geo::Vec2 a = r_.vec2(v, p);
    return {rounded(a.x, kStateQuantum), rounded(a.y, kStateQuantum)};
  }
  json robotList(const json& ev, const std::string& p, std::size_t min_size) const {
    const std::string rp = member(p, "robots");
    const json& list = r_.array(r_.required(ev, "robots", p), rp);
    if (list.size() < min_size) r_.fail(rp, "expected at least " + std::to_string(min_size) + " robots");
    json out = json::array();
    for (std::size_t k = 0; k < list.size(); ++k) {
      const long long idx = count(list[k], element(rp, k));
      if (static_cast<std::size_t>(idx) >= robots_)
        r_.fail(element(rp, k), "robot index " + std::to_string(idx) + " does not exist (the scenario has " +
                                    std::to_string(robots_) + " robots): is this the trace of another scenario?");
      out.push_back(idx);
    }
    return out;
  }

  json conflict(const json& ev, const std::string& p) {
    const long long id = count(r_.required(ev, "id", p), member(p, "id"));
    if (!conflict_ids_.insert(id).second) r_.fail(member(p, "id"), "conflict " + std::to_string(id) + " appears twice");
    json c = {{"id", id},
              {"robots", robotList(ev, p, 2)},
              {"t", step(r_.required(ev, "t", p), member(p, "t"))},
              {"place", vec2(r_.required(ev, "place", p), member(p, "place"))}};
    if (const json* v = r_.optional(ev, "at_s", true))
      c["at_s"] = rounded(r_.nonNegative(*v, member(p, "at_s")), kSecondsQuantum);
    return c;
  }

  json subproblem(const json& ev, const std::string& p) {
    const long long conflict_id = count(r_.required(ev, "conflict", p), member(p, "conflict"));
    if (!conflict_ids_.count(conflict_id))
      r_.fail(member(p, "conflict"), "refers to conflict " + std::to_string(conflict_id) +
                                         ", which no earlier event of the trace reports");
    const std::string wp = member(p, "window");
    const json& w = r_.array(r_.required(ev, "window", p), wp);
    if (w.size() != 2) r_.fail(wp, "expected [t_start, t_end]");
    const double t0 = step(w[0], element(wp, 0)), t1 = step(w[1], element(wp, 1));
    if (t1 < t0) r_.fail(wp, "the window ends before it starts");
    const std::string gp = member(p, "region");
    const json& g = r_.array(r_.required(ev, "region", p), gp);
    if (g.size() != 2) r_.fail(gp, "expected [[xmin, ymin], [xmax, ymax]]");
    const json lo = vec2(g[0], element(gp, 0)), hi = vec2(g[1], element(gp, 1));
    if (hi[0] < lo[0] || hi[1] < lo[1]) r_.fail(gp, "the region's max corner is below its min corner");
    json s = {{"id", count(r_.required(ev, "id", p), member(p, "id"))},
              {"conflict", conflict_id},
              {"robots", robotList(ev, p, 1)},
              {"window", {t0, t1}},
              {"region", {lo, hi}},
              {"expansions", optionalCount(ev, "expansions", p)},
              {"merged", optionalCount(ev, "merged", p)},
              {"solved_by", r_.string(r_.required(ev, "solved_by", p), member(p, "solved_by"))}};
    if (const json* v = r_.optional(ev, "entry", true)) s["entry"] = count(*v, member(p, "entry"));
    if (const json* v = r_.optional(ev, "length", true)) s["length"] = count(*v, member(p, "length"));
    if (const json* v = r_.optional(ev, "merge_cap", true)) s["merge_cap"] = count(*v, member(p, "merge_cap"));
    if (const json* v = r_.optional(ev, "ignore_others", true))
      s["ignore_others"] = r_.boolean(*v, member(p, "ignore_others"));
    json attempts = json::array();
    if (const json* list = r_.optional(ev, "attempts", true)) {
      const std::string ap = member(p, "attempts");
      r_.array(*list, ap);
      for (std::size_t k = 0; k < list->size(); ++k) {
        const std::string a = element(ap, k);
        const json& at = r_.object((*list)[k], a);
        json attempt = {{"solver", r_.string(r_.required(at, "solver", a), member(a, "solver"))},
                        {"ok", r_.boolean(r_.required(at, "ok", a), member(a, "ok"))},
                        {"time_s", rounded(r_.nonNegative(r_.required(at, "time_s", a), member(a, "time_s")),
                                           kSecondsQuantum)}};
        if (const json* d = r_.optional(at, "detail", true)) attempt["detail"] = r_.string(*d, member(a, "detail"));
        attempts.push_back(std::move(attempt));
      }
    }
    s["attempts"] = std::move(attempts);
    return s;
  }

  io::JsonReader r_;
  std::size_t robots_;
  std::set<long long> conflict_ids_;
};

}  // namespace

json traceFromJson(const json& doc, const Scenario& scenario, const std::string& file) {
  return TraceReader(file, scenario.robots.size()).read(doc);
}

json loadTrace(const std::string& path, const Scenario& scenario) {
  return traceFromJson(readJsonFile(path), scenario, path);
}

}  // namespace earc::view
