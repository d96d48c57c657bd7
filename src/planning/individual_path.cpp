// ARC's first step: every robot planned alone (individualPath, arc.hpp).
#include <random>

#include "earc/planning/arc.hpp"
#include "earc/planning/composite.hpp"

namespace earc {

namespace {

// Shortcutting iterations for an individual path: enough to remove most of
// a roadmap path's zig-zag, cheap next to the roadmap query.
constexpr int kIndividualShortcuts = 80;
// Times the roadmap is doubled before a robot is declared pathless.
constexpr int kRoadmapGrowths = 3;

}  // namespace

std::optional<Path> individualPath(const CollisionWorld& world, RoadmapSet& roadmaps, const RobotModel& model,
                                   int robot, const Deadline& deadline, std::uint64_t seed) {
  const RobotSpec& spec = model.spec();
  // The straight motion first: where it is free, the roadmap's path
  // shortcut comes out as that same motion (the same paths on 60 16-arm
  // plans), and a robot that needs no roadmap does not build one. A
  // roadmap is then built when a solver first plans for the robot from
  // scratch: ARC at its first decoupled attempt, E-ARC only when the
  // database does not answer.
  CompositeChecker checker(world, {&model}, deadline);
  if (checker.motionValid({spec.start}, {spec.goal})) return timeStamp(model, {spec.start, spec.goal});
  Roadmap& rm = roadmaps.forRobot(robot);
  // When no valid edges join the start's part of the roadmap to the
  // goal's, the roadmap grows in the box around the part with the smaller
  // box: a pocket behind a narrow way out (or everywhere, doubling, when
  // that box is everything): on a large map a few doublings join such a
  // pocket up.
  std::optional<ConfigBox> where;
  auto configsOf = [&](const QueryGraph& graph, const std::vector<int>& vertices) {
    std::vector<double> out;
    for (int v : vertices) out.insert(out.end(), graph.config(v), graph.config(v) + model.dim());
    return out;
  };
  for (int attempt = 0; attempt <= kRoadmapGrowths; ++attempt) {
    if (attempt > 0) roadmaps.growWithin(robot, *where);  // set by the failed attempt
    QueryGraph graph(rm, model);
    int s = graph.addVertex(spec.start.data(), 10);
    int g = graph.addVertex(spec.goal.data(), 10);
    std::vector<int> reached;
    auto vertices = shortestPath(graph, s, g, deadline, &reached);
    if (deadline.expired()) return std::nullopt;
    if (!vertices) {
      where = rm.boxAround(configsOf(graph, reached));
      // The start's part is large: the goal's may be the pocket.
      if (rm.share(*where) > 0.25) {
        shortestPath(graph, g, s, deadline, &reached);
        ConfigBox other = rm.boxAround(configsOf(graph, reached));
        if (rm.share(other) < rm.share(*where)) where = std::move(other);
      }
      continue;
    }
    std::vector<CompositeState> waypoints;
    for (int v : *vertices) waypoints.push_back({std::vector<double>(graph.config(v), graph.config(v) + model.dim())});
    std::mt19937_64 rng(seed);
    shortcutComposite(checker, waypoints, kIndividualShortcuts, rng, deadline);
    std::vector<std::vector<double>> qs;
    for (auto& w : waypoints) qs.push_back(std::move(w[0]));
    return timeStamp(model, qs);
  }
  return std::nullopt;
}

}  // namespace earc
