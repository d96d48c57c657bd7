// earc.solution.v1 documents (shared/spec/formats.md, "Solution").
#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "earc/io/json_io.hpp"
#include "json_reader.hpp"

namespace earc {
namespace {

using namespace io;  // JsonReader, member, element, json

// states: an array of states of `dim` numbers each; dim < 0 takes the
// length of the first state.
Path readStates(const JsonReader& r, const json& states, int dim, const std::string& p) {
  r.array(states, p);
  if (dim < 0) {
    if (states.empty()) return Path(0);
    const std::string s0 = element(p, 0);
    dim = static_cast<int>(r.array(states[0], s0).size());
    if (dim == 0) r.fail(s0, "a state needs at least one number");
  }
  Path path(dim);
  path.reserve(states.size());
  auto& raw = path.raw();
  for (std::size_t t = 0; t < states.size(); ++t) {
    const json& s = states[t];
    const std::string sp = element(p, t);
    if (!s.is_array() || s.size() != static_cast<std::size_t>(dim))
      r.fail(sp, "expected a state of " + std::to_string(dim) + " numbers, got " + io::describe(s));
    for (std::size_t i = 0; i < s.size(); ++i) raw.push_back(r.number(s[i], element(sp, i)));
  }
  return path;
}

// Throws std::invalid_argument unless every path has its robot's name.
void requireRobotNames(const Solution& s, const char* who) {
  if (s.robot_names.size() != s.paths.size())
    throw std::invalid_argument(std::string(who) + ": robot_names must name every path (" +
                                std::to_string(s.robot_names.size()) + " names, " +
                                std::to_string(s.paths.size()) + " paths); call Solution::nameRobots");
}

}  // namespace

Solution solutionFromJson(const json& doc, const Scenario* scenario, const std::string& file,
                          InputWarnings* warnings) {
  InputWarnings found;
  const JsonReader r(file, &found);
  r.object(doc, "$");
  r.format(doc, kSolutionFormat);
  // "stats" is free-form: its keys are the method's own.
  r.unknownKeys(doc, "$", {"format", "scenario", "method", "solved", "stats", "paths"});
  Solution sol;
  if (const json* v = r.optional(doc, "scenario", true)) sol.scenario = r.string(*v, "$.scenario");
  if (const json* v = r.optional(doc, "method", true)) sol.method = r.string(*v, "$.method");
  sol.solved = r.boolean(r.required(doc, "solved", "$"), "$.solved");
  if (const json* v = r.optional(doc, "stats")) sol.stats = *v;

  // An unsolved solution may leave "paths" out.
  const json* paths = sol.solved ? &r.required(doc, "paths", "$") : r.optional(doc, "paths");
  if (paths == nullptr) {
    r.deliverWarnings(warnings);
    return sol;
  }
  r.array(*paths, "$.paths");
  std::unordered_map<std::string, int> dims;
  if (scenario != nullptr)
    for (const RobotSpec& spec : scenario->robots) dims.emplace(spec.name, spec.dim());
  for (std::size_t i = 0; i < paths->size(); ++i) {
    const std::string p = element("$.paths", i);
    const json& entry = r.object((*paths)[i], p);
    r.unknownKeys(entry, p, {"robot", "states"});
    std::string name = r.string(r.required(entry, "robot", p), member(p, "robot"));
    const json& states = r.required(entry, "states", p);
    int dim = -1;
    if (scenario != nullptr) {
      auto it = dims.find(name);
      // A path for a robot the scenario does not have is a violation the
      // validator reports, not malformed input: keep the name, not the states.
      if (it == dims.end()) {
        sol.paths.emplace_back(0);
        sol.robot_names.push_back(std::move(name));
        continue;
      }
      dim = it->second;
    }
    sol.paths.push_back(readStates(r, states, dim, member(p, "states")));
    sol.robot_names.push_back(std::move(name));
  }
  r.deliverWarnings(warnings);
  return sol;
}

namespace {

// One state as a JSON array of numbers, as nlohmann::json prints it.
void appendState(std::string& out, const Path& path, std::size_t t) {
  out += '[';
  const auto q = path.state(t);
  for (std::size_t j = 0; j < q.size(); ++j) {
    if (j) out += ',';
    appendJsonDouble(out, q[j]);
  }
  out += ']';
}

std::size_t numbersIn(const Solution& s) {
  std::size_t numbers = 0;
  for (const Path& p : s.paths) numbers += p.size() * static_cast<std::size_t>(std::max(0, p.dim()));
  return numbers;
}

}  // namespace

json solutionToJson(const Solution& s, bool with_paths) {
  requireRobotNames(s, "solutionToJson");
  json doc = json::object();
  doc["format"] = kSolutionFormat;
  doc["scenario"] = s.scenario;
  doc["method"] = s.method;
  doc["solved"] = s.solved;
  if (with_paths) {
    json paths = json::array();
    for (std::size_t i = 0; i < s.paths.size(); ++i) {
      const Path& path = s.paths[i];
      json states = json::array();
      for (std::size_t t = 0; t < path.size(); ++t) {
        const auto q = path.state(t);
        states.push_back(json(std::vector<double>(q.begin(), q.end())));
      }
      paths.push_back({{"robot", s.robot_names[i]}, {"states", std::move(states)}});
    }
    doc["paths"] = std::move(paths);
  }
  doc["stats"] = s.stats;
  return doc;
}

void appendSolutionPaths(std::string& out, const Solution& s) {
  requireRobotNames(s, "appendSolutionPaths");
  out.reserve(out.size() + 24 * numbersIn(s) + 64 * s.paths.size());
  out += '[';
  for (std::size_t i = 0; i < s.paths.size(); ++i) {
    if (i) out += ',';
    out += "{\"robot\":" + dumpCompact(s.robot_names[i]) + ",\"states\":[";
    for (std::size_t t = 0; t < s.paths[i].size(); ++t) {
      if (t) out += ',';
      appendState(out, s.paths[i], t);
    }
    out += "]}";
  }
  out += ']';
}

Solution loadSolution(const std::string& path, const Scenario* scenario, InputWarnings* warnings) {
  return solutionFromJson(readJsonFile(path), scenario, path, warnings);
}

void saveSolution(const std::string& path, const Solution& s) {
  requireRobotNames(s, "saveSolution");
  // One state per line: readable and diffable, yet compact for long paths.
  // Written straight from the paths: a plan of many robots holds millions
  // of numbers, and a JSON document of them took longer than the plan.
  // Planner-made text (stats, names) could hold invalid UTF-8: replaced, not thrown on.
  const auto dump = dumpCompact;
  std::string text = "{\n";
  const std::pair<const char*, json> head[] = {{"format", kSolutionFormat},
                                                {"scenario", s.scenario},
                                                {"method", s.method},
                                                {"solved", s.solved}};
  for (const auto& [key, value] : head) text += "  " + json(key).dump() + ": " + dump(value) + ",\n";
  text += "  \"stats\": " + dump(s.stats) + ",\n";
  text += "  \"paths\": [";
  text.reserve(text.size() + 24 * numbersIn(s) + 64 * s.paths.size());
  for (std::size_t i = 0; i < s.paths.size(); ++i) {
    text += i ? ",\n" : "\n";
    text += "    {\"robot\": " + dump(s.robot_names[i]) + ", \"states\": [";
    const Path& path = s.paths[i];
    for (std::size_t t = 0; t < path.size(); ++t) {
      text += t ? ",\n      " : "\n      ";
      appendState(text, path, t);
    }
    text += path.size() == 0 ? "]}" : "\n    ]}";
  }
  text += s.paths.empty() ? "]\n}\n" : "\n  ]\n}\n";
  writeTextFileAtomic(path, text);
}

}  // namespace earc
