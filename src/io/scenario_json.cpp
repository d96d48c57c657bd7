// earc.scenario.v1 documents (shared/spec/formats.md, "Scenario").
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "earc/io/json_io.hpp"
#include "json_reader.hpp"

namespace earc {
namespace {

using namespace io;  // JsonReader, member, element, json

// Longest straight path across the workspace, in translation steps.
constexpr double kMaxStepsAcrossWorkspace = 1e7;

// Headings are compared modulo 2 pi; beyond this a double has too few
// digits left below the radian for that (at 1e6 its spacing is 1e-10).
constexpr double kMaxHeading = 1e6;

void requireHeading(const JsonReader& r, double theta, const std::string& path) {
  if (!(std::abs(theta) <= kMaxHeading))
    r.fail(path, "heading " + io::formatNumber(theta) + " is beyond +-1e6 rad; give it modulo 2 pi");
}

// Any finite angle is allowed, but nobody means a turn of 90 rad: beyond a
// full turn (and a little, for 2 pi rounded up) it was written in degrees.
constexpr double kFullTurnSlack = 0.01;

void warnIfDegrees(const JsonReader& r, double angle, const std::string& path, const char* what) {
  if (!(std::abs(angle) > 2 * std::numbers::pi + kFullTurnSlack)) return;
  r.warn(path, std::string(what) + " " + io::formatNumber(angle) +
                   " is more than a full turn: angles are in radians, and this looks like degrees (" +
                   io::formatNumber(angle) + " degrees is " + io::formatNumber(angle * std::numbers::pi / 180) +
                   " rad)");
}

// "[0, 20] x [0, 12]"
std::string extent(const geo::Aabb& b) {
  return "[" + io::formatNumber(b.lo.x) + ", " + io::formatNumber(b.hi.x) + "] x [" + io::formatNumber(b.lo.y) +
         ", " + io::formatNumber(b.hi.y) + "]";
}

// Robots stay inside the workspace, so an obstacle wholly outside it (or
// only touching its edge) can never meet one: most likely a mistyped
// center or size. Read all the same: it changes nothing.
void warnIfOutside(const JsonReader& r, const Obstacle& o, const geo::Aabb& workspace, const std::string& p) {
  const geo::Aabb b = geo::bounds(o.body());
  if (b.lo.x < workspace.hi.x && workspace.lo.x < b.hi.x && b.lo.y < workspace.hi.y && workspace.lo.y < b.hi.y)
    return;
  r.warn(p, "obstacle entirely outside the workspace " + extent(workspace) + " (it spans " + extent(b) +
                "): no robot can touch it; is its center right?");
}

Obstacle readObstacle(const JsonReader& r, const json& v, const std::string& p) {
  r.object(v, p);
  Obstacle o;
  const std::string type = r.string(r.required(v, "type", p), member(p, "type"));
  // The type first: another kind ({"type": "polygon", "points": ...}) has
  // no centre, and "missing center" would send the user after the wrong field.
  if (type != "box" && type != "circle")
    r.fail(member(p, "type"), "unknown obstacle type \"" + type + "\" (expected \"box\" or \"circle\")");
  if (type == "box")
    r.unknownKeys(v, p, {"type", "center", "size", "angle"}, {{"radius", "a circle's"}}, "a box");
  else
    r.unknownKeys(v, p, {"type", "center", "radius"}, {{"size", "a box's"}, {"angle", "a box's"}}, "a circle");
  o.center = r.vec2(r.required(v, "center", p), member(p, "center"));
  if (type == "box") {
    o.type = Obstacle::Type::Box;
    const std::string sp = member(p, "size");
    const json& size = r.required(v, "size", p);
    r.numbers(size, 2, sp);
    o.size = {r.positive(size[0], element(sp, 0)), r.positive(size[1], element(sp, 1))};
    if (const json* a = r.optional(v, "angle")) {
      o.angle = r.number(*a, member(p, "angle"));
      warnIfDegrees(r, o.angle, member(p, "angle"), "angle");
    }
  } else {
    o.type = Obstacle::Type::Circle;
    o.radius = r.positive(r.required(v, "radius", p), member(p, "radius"));
  }
  return o;
}

void readMobile(const JsonReader& r, const json& v, const std::string& p, RobotSpec& spec) {
  spec.kind = RobotKind::Mobile;
  r.unknownKeys(v, p, {"name", "type", "shape", "start", "goal"},
                {{"base", "a manipulator's"},
                 {"links", "a manipulator's"},
                 {"link_radius", "a manipulator's"},
                 {"joint_limits", "a manipulator's"}},
                "a mobile robot");
  const std::string sp = member(p, "shape");
  const json& shape = r.object(r.required(v, "shape", p), sp);
  const std::string type = r.string(r.required(shape, "type", sp), member(sp, "type"));
  if (type == "disc") {
    r.unknownKeys(shape, sp, {"type", "radius"}, {{"size", "a box shape's"}}, "a disc");
    spec.shape = MobileShape::Disc;
    spec.radius = r.positive(r.required(shape, "radius", sp), member(sp, "radius"));
  } else if (type == "box") {
    r.unknownKeys(shape, sp, {"type", "size"}, {{"radius", "a disc shape's"}}, "a box shape");
    spec.shape = MobileShape::Box;
    const std::string zp = member(sp, "size");
    const json& size = r.required(shape, "size", sp);
    r.numbers(size, 2, zp);
    spec.box_size = {r.positive(size[0], element(zp, 0)), r.positive(size[1], element(zp, 1))};
  } else {
    r.fail(member(sp, "type"), "unknown shape type \"" + type + "\" (expected \"disc\" or \"box\")");
  }
  spec.start = r.numbers(r.required(v, "start", p), 3, member(p, "start"), "x, y, theta");
  spec.goal = r.numbers(r.required(v, "goal", p), 3, member(p, "goal"), "x, y, theta");
  for (const auto& [end, q] : {std::pair{"start", &spec.start}, std::pair{"goal", &spec.goal}}) {
    const std::string theta = element(member(p, end), 2);
    requireHeading(r, (*q)[2], theta);
    warnIfDegrees(r, (*q)[2], theta, "heading");
  }
}

void readManipulator(const JsonReader& r, const json& v, const std::string& p, RobotSpec& spec) {
  spec.kind = RobotKind::Manipulator;
  r.unknownKeys(v, p, {"name", "type", "base", "links", "link_radius", "joint_limits", "start", "goal"},
                {{"shape", "a mobile robot's"}}, "a manipulator");
  const auto base = r.numbers(r.required(v, "base", p), 3, member(p, "base"), "x, y, theta0");
  spec.base_position = {base[0], base[1]};
  spec.base_angle = base[2];
  requireHeading(r, spec.base_angle, element(member(p, "base"), 2));
  warnIfDegrees(r, spec.base_angle, element(member(p, "base"), 2), "base angle");
  const std::string lp = member(p, "links");
  const json& links = r.array(r.required(v, "links", p), lp);
  if (links.empty()) r.fail(lp, "an arm needs at least one link");
  for (std::size_t i = 0; i < links.size(); ++i) spec.links.push_back(r.positive(links[i], element(lp, i)));
  const std::size_t n = spec.links.size();
  spec.link_radius = r.nonNegative(r.required(v, "link_radius", p), member(p, "link_radius"));
  if (const json* lim = r.optional(v, "joint_limits", true)) {
    const std::string jp = member(p, "joint_limits");
    r.array(*lim, jp);
    if (lim->size() != n)
      r.fail(jp, "expected " + std::to_string(n) + " [lo, hi] pairs (one per link), got " + std::to_string(lim->size()));
    for (std::size_t j = 0; j < n; ++j) {
      const auto lh = r.numbers((*lim)[j], 2, element(jp, j), "lo, hi");
      if (lh[0] > lh[1])
        r.fail(element(jp, j), "lo " + io::formatNumber(lh[0]) + " > hi " + io::formatNumber(lh[1]));
      spec.joint_limits.emplace_back(lh[0], lh[1]);
    }
  } else {
    spec.joint_limits.assign(n, {-std::numbers::pi, std::numbers::pi});
  }
  spec.start = r.numbers(r.required(v, "start", p), n, member(p, "start"), "one per link");
  spec.goal = r.numbers(r.required(v, "goal", p), n, member(p, "goal"), "one per link");
}

json vec(geo::Vec2 v) { return json::array({v.x, v.y}); }

}  // namespace

Scenario scenarioFromJson(const json& doc, const std::string& file, InputWarnings* warnings) {
  InputWarnings found;
  const JsonReader r(file, &found);
  r.object(doc, "$");
  r.format(doc, kScenarioFormat);
  r.unknownKeys(doc, "$", {"format", "name", "workspace", "resolution", "obstacles", "robots"});
  Scenario s;
  if (const json* name = r.optional(doc, "name", true)) s.name = r.string(*name, "$.name");

  const json& ws = r.object(r.required(doc, "workspace", "$"), "$.workspace");
  r.unknownKeys(ws, "$.workspace", {"min", "max"});
  s.workspace.lo = r.vec2(r.required(ws, "min", "$.workspace"), "$.workspace.min");
  s.workspace.hi = r.vec2(r.required(ws, "max", "$.workspace"), "$.workspace.max");
  if (!(s.workspace.lo.x < s.workspace.hi.x && s.workspace.lo.y < s.workspace.hi.y))
    r.fail("$.workspace", "min must be below max in x and y");

  if (const json* res = r.optional(doc, "resolution", true)) {
    r.object(*res, "$.resolution");
    r.unknownKeys(*res, "$.resolution", {"translation", "rotation", "joint"});
    // Each key defaults on its own.
    if (const json* v = r.optional(*res, "translation")) s.resolution.translation = r.positive(*v, "$.resolution.translation");
    if (const json* v = r.optional(*res, "rotation")) s.resolution.rotation = r.positive(*v, "$.resolution.rotation");
    if (const json* v = r.optional(*res, "joint")) s.resolution.joint = r.positive(*v, "$.resolution.joint");
  }
  // Step counts are ints; a path across the workspace must have one (and
  // ten million steps is already far beyond anything plannable).
  const geo::Vec2 extent{s.workspace.hi.x - s.workspace.lo.x, s.workspace.hi.y - s.workspace.lo.y};
  const double across = std::hypot(extent.x, extent.y) / s.resolution.translation;
  if (!(across <= kMaxStepsAcrossWorkspace))
    r.fail("$.workspace", io::formatNumber(across) + " steps across at translation resolution " +
                              io::formatNumber(s.resolution.translation) + "; at most " +
                              std::to_string(static_cast<long>(kMaxStepsAcrossWorkspace)));

  if (const json* obs = r.optional(doc, "obstacles", true)) {
    r.array(*obs, "$.obstacles");
    for (std::size_t i = 0; i < obs->size(); ++i) {
      const std::string p = element("$.obstacles", i);
      s.obstacles.push_back(readObstacle(r, (*obs)[i], p));
      warnIfOutside(r, s.obstacles.back(), s.workspace, p);
    }
  }

  const json& robots = r.array(r.required(doc, "robots", "$"), "$.robots");
  std::unordered_map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const std::string p = element("$.robots", i);
    const json& v = r.object(robots[i], p);
    RobotSpec spec;
    // The type first, as for obstacles: a robot of another kind
    // ({"type": "drone", "id": 3}) is wrong in its type, not in a missing name.
    const std::string type = r.string(r.required(v, "type", p), member(p, "type"));
    if (type != "mobile" && type != "manipulator")
      r.fail(member(p, "type"), "unknown robot type \"" + type + "\" (expected \"mobile\" or \"manipulator\")");
    spec.name = r.string(r.required(v, "name", p), member(p, "name"));
    // A solution's paths name their robots: "" names none.
    if (spec.name.empty()) r.fail(member(p, "name"), "empty robot name (a solution names each robot's path by it)");
    if (auto [it, fresh] = seen.emplace(spec.name, i); !fresh)
      r.fail(member(p, "name"), "duplicate robot name \"" + spec.name + "\" (also " +
                                    element("$.robots", it->second) + ")");
    if (type == "mobile") readMobile(r, v, p, spec);
    else readManipulator(r, v, p, spec);
    s.robots.push_back(std::move(spec));
  }
  r.deliverWarnings(warnings);
  return s;
}

json scenarioToJson(const Scenario& s) {
  json doc = json::object();
  doc["format"] = kScenarioFormat;
  doc["name"] = s.name;
  doc["workspace"] = {{"min", vec(s.workspace.lo)}, {"max", vec(s.workspace.hi)}};
  doc["resolution"] = {{"translation", s.resolution.translation},
                       {"rotation", s.resolution.rotation},
                       {"joint", s.resolution.joint}};
  json obstacles = json::array();
  for (const Obstacle& o : s.obstacles) {
    if (o.type == Obstacle::Type::Box)
      obstacles.push_back({{"type", "box"}, {"center", vec(o.center)}, {"size", vec(o.size)}, {"angle", o.angle}});
    else
      obstacles.push_back({{"type", "circle"}, {"center", vec(o.center)}, {"radius", o.radius}});
  }
  doc["obstacles"] = std::move(obstacles);
  json robots = json::array();
  for (const RobotSpec& r : s.robots) {
    json j = {{"name", r.name}};
    if (r.kind == RobotKind::Mobile) {
      j["type"] = "mobile";
      j["shape"] = r.shape == MobileShape::Disc ? json{{"type", "disc"}, {"radius", r.radius}}
                                                 : json{{"type", "box"}, {"size", vec(r.box_size)}};
    } else {
      j["type"] = "manipulator";
      j["base"] = {r.base_position.x, r.base_position.y, r.base_angle};
      j["links"] = r.links;
      j["link_radius"] = r.link_radius;
      json limits = json::array();
      for (auto [lo, hi] : r.joint_limits) limits.push_back({lo, hi});
      j["joint_limits"] = std::move(limits);
    }
    j["start"] = r.start;
    j["goal"] = r.goal;
    robots.push_back(std::move(j));
  }
  doc["robots"] = std::move(robots);
  return doc;
}

Scenario readScenarioFile(const std::string& path, InputWarnings* warnings) {
  return scenarioFromJson(readJsonFile(path), path, warnings);
}

}  // namespace earc
