#include <algorithm>
#include <map>
#include <string>

#include "earc/io/json_io.hpp"
#include "earc/planning/solver.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/random.hpp"

namespace earc {

namespace {
constexpr int kArmRoadmapSamples = 1000;
}  // namespace

RoadmapSet::RoadmapSet(const CollisionWorld& world, std::vector<const RobotModel*> models, int samples,
                       int neighbors, std::uint64_t seed, const Deadline& deadline)
    : world_(world), models_(std::move(models)), samples_(samples), neighbors_(neighbors), seed_(seed),
      deadline_(deadline) {
  // Robots for which the same configurations are valid share a roadmap:
  // mobile robots by geometry alone; arms by geometry when nothing lies
  // within their reach (the disc of their reach about the base is inside
  // the workspace and touches no obstacle, so validity is joint limits and
  // self-collision only, wherever the base is), else by geometry and base.
  std::map<std::string, int> slots;
  for (const RobotModel* m : models_) {
    std::string key = m->geometrySignature();
    if (!m->isMobile()) {
      const RobotSpec& s = m->spec();
      if (world_.bodyFree(geo::Body::disc(s.base_position, m->boundingRadius())))
        key += "@anywhere";
      else
        key += "@" + std::to_string(s.base_position.x) + "," + std::to_string(s.base_position.y) + "," +
               std::to_string(s.base_angle);
    }
    auto [it, inserted] = slots.emplace(key, static_cast<int>(slots.size()));
    slot_.push_back(it->second);
    if (inserted) anywhere_.push_back(key.ends_with("@anywhere"));
  }
  roadmaps_.resize(slots.size());
}

void RoadmapSet::useCache(RoadmapCache& cache, const Scenario& scenario) {
  // Everything building depends on, numbers written exactly (JSON's
  // shortest round trip): the scenario but its robots and name, the
  // robot's description but where it starts and ends (and for an arm with
  // nothing in reach, its base), the sample count, the neighbours and the
  // roadmap's own seed. Equal keys build equal roadmaps.
  nlohmann::json world = scenarioToJson(scenario);
  const nlohmann::json robots = std::move(world["robots"]);
  world.erase("robots");
  world.erase("name");
  const std::string world_key = world.dump();
  cache_ = &cache;
  cache_keys_.assign(roadmaps_.size(), {});
  for (std::size_t r = 0; r < slot_.size(); ++r) {
    const auto slot = static_cast<std::size_t>(slot_[r]);
    if (!cache_keys_[slot].empty()) continue;
    nlohmann::json robot = robots.at(r);
    for (const char* f : {"start", "goal", "name"}) robot.erase(f);
    if (anywhere_[slot]) robot.erase("base");
    cache_keys_[slot] = world_key + "\n" + robot.dump() + "\n" + std::to_string(initialSamples(static_cast<int>(r))) +
                        " samples, " + std::to_string(neighbors_) + " neighbours, seed " +
                        std::to_string(splitSeed(seed_, slot));
  }
}

int RoadmapSet::initialSamples(int robot) const {
  if (samples_ > 0) return samples_;
  const RobotModel& m = *models_[static_cast<std::size_t>(robot)];
  // An arm's joint space: 1,000 vertices. With 1,500 (up to 2c3754d) ARC
  // solved the same scenarios (4 to 16 arms, with and without obstacles)
  // and took 1.2 to 1.7 times as long: connecting the roadmap, mostly its
  // k-nearest search, is much of a small plan's time. Median sums of
  // costs stayed within 1%; with obstacles in reach (a roadmap per arm)
  // makespans came out 3-4% longer on average at 16 arms, none longer
  // without. 700 was faster still, with 3% longer makespans.
  if (!m.isMobile()) return kArmRoadmapSamples;
  // About three vertices per square of the robot's size: dense enough for
  // local regions a few robot lengths wide to hold several vertices.
  const geo::Aabb& ws = world_.workspace();
  const double area = (ws.hi.x - ws.lo.x) * (ws.hi.y - ws.lo.y);
  const double cell = std::max(0.25, 2.0 * m.boundingRadius());
  return std::clamp(static_cast<int>(3.0 * area / (cell * cell)), 400, 20000);
}

Roadmap& RoadmapSet::forRobot(int robot) {
  const int slot = slot_[static_cast<std::size_t>(robot)];
  auto& rm = roadmaps_[static_cast<std::size_t>(slot)];
  if (!rm) {
    Stopwatch sw;
    const RobotModel& model = *models_[static_cast<std::size_t>(robot)];
    const std::string* key = cache_ ? &cache_keys_[static_cast<std::size_t>(slot)] : nullptr;
    if (auto kept = key ? cache_->find(*key) : nullptr) {
      rm = std::make_unique<Roadmap>(world_, model, kept->snapshot, deadline_);
      // The work building did, as if done again: a solver's work budget
      // that building fell into ends where it would have.
      countWork(kept->work);
      ++reused_;
    } else {
      const std::uint64_t work_before = t_work_done;
      rm = std::make_unique<Roadmap>(world_, model, neighbors_, splitSeed(seed_, static_cast<std::uint64_t>(slot)),
                                     deadline_);
      rm->grow(initialSamples(robot));
      if (key && !rm->deadlineSeen()) cache_->put(*key, rm->snapshot(), t_work_done - work_before);
    }
    build_seconds_ += sw.seconds();
  }
  return *rm;
}

void RoadmapSet::growWithin(int robot, const ConfigBox& box) {
  Stopwatch sw;
  forRobot(robot).growWithin(box);
  build_seconds_ += sw.seconds();
}

std::size_t RoadmapSet::built() const {
  return static_cast<std::size_t>(std::count_if(roadmaps_.begin(), roadmaps_.end(), [](const auto& rm) { return rm != nullptr; }));
}

std::size_t RoadmapSet::edgeChecks() const {
  std::size_t n = 0;
  for (const auto& rm : roadmaps_)
    if (rm) n += rm->edgeChecks();
  return n;
}

std::size_t RoadmapSet::vertices() const {
  std::size_t n = 0;
  for (const auto& rm : roadmaps_)
    if (rm) n += static_cast<std::size_t>(rm->size());
  return n;
}

}  // namespace earc
