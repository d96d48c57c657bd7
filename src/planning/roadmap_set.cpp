#include <algorithm>
#include <map>
#include <string>

#include "earc/planning/solver.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/random.hpp"

namespace earc {

namespace {
constexpr int kArmRoadmapSamples = 1000;

// A cache key's fields, each written as its exact bytes: equal keys only
// for equal values, with no formatting in between.
class CacheKeyWriter {
 public:
  CacheKeyWriter& operator<<(double v) { return raw(&v, sizeof v); }
  CacheKeyWriter& operator<<(std::uint64_t v) { return raw(&v, sizeof v); }
  CacheKeyWriter& operator<<(geo::Vec2 v) { return *this << v.x << v.y; }
  CacheKeyWriter& operator<<(const std::vector<double>& v) {
    *this << static_cast<std::uint64_t>(v.size());
    for (double x : v) *this << x;
    return *this;
  }
  std::string take() { return std::move(key_); }

 private:
  CacheKeyWriter& raw(const void* p, std::size_t n) {
    key_.append(static_cast<const char*>(p), n);
    return *this;
  }
  std::string key_;
};

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
  // An arm with something in reach had a roadmap sampled and joined for
  // it alone: at 16 arms among obstacles, building them was two thirds of
  // ARC's plan. Its joint space is the same as with nothing in reach, less
  // what the obstacles and the workspace's edge take: its roadmap is now a
  // copy of that free space's roadmap, built once per geometry, less the
  // vertices its surroundings take, with the vertices that lost neighbours
  // joined to their nearest of the rest (Roadmap::dropInvalidVertices).
  // The geometry's shared roadmap, where arms have nothing in reach, is
  // the same roadmap (same seed, same valid configurations), so their
  // plans do not change.
  for (std::size_t r = 0; r < models_.size(); ++r)
    if (!models_[r]->isMobile() && !anywhere_[static_cast<std::size_t>(slot_[r])]) {
      FreeSpace& f = free_[models_[r]->geometrySignature()];
      if (f.seed_slot < 0) f.seed_slot = slot_[r];
    }
  for (std::size_t r = 0; r < models_.size(); ++r)
    if (!models_[r]->isMobile() && anywhere_[static_cast<std::size_t>(slot_[r])])
      if (auto it = free_.find(models_[r]->geometrySignature()); it != free_.end()) it->second.seed_slot = slot_[r];
}

int RoadmapSet::seedSlot(int robot) const {
  const RobotModel& model = *models_[static_cast<std::size_t>(robot)];
  if (!model.isMobile())
    if (auto it = free_.find(model.geometrySignature()); it != free_.end()) return it->second.seed_slot;
  return slot_[static_cast<std::size_t>(robot)];
}

std::unique_ptr<Roadmap> RoadmapSet::buildRoadmap(int robot, int slot, bool& cut_short) {
  const RobotModel& model = *models_[static_cast<std::size_t>(robot)];
  auto free = model.isMobile() ? free_.end() : free_.find(model.geometrySignature());
  if (free == free_.end()) {
    auto rm = std::make_unique<Roadmap>(world_, model, neighbors_,
                                        splitSeed(seed_, static_cast<std::uint64_t>(seedSlot(robot))), deadline_);
    rm->grow(initialSamples(robot));
    cut_short = rm->deadlineSeen();
    return rm;
  }
  FreeSpace& f = free->second;
  if (!f.snapshot) {
    // A world of nothing but a workspace that holds the arm's reach.
    Scenario nothing;
    const geo::Vec2 base = model.spec().base_position;
    const double reach = model.boundingRadius() + 1.0;
    nothing.workspace = {{base.x - reach, base.y - reach}, {base.x + reach, base.y + reach}};
    const CollisionWorld empty(nothing);
    Roadmap rm(empty, model, neighbors_, splitSeed(seed_, static_cast<std::uint64_t>(seedSlot(robot))), deadline_);
    rm.keepCandidates();
    rm.grow(initialSamples(robot));
    f.snapshot = rm.snapshot();
    f.cut_short = rm.deadlineSeen();
  }
  auto rm = std::make_unique<Roadmap>(world_, model, *f.snapshot, deadline_);
  // Where the arm has something in reach: the free space's vertices that
  // its surroundings take are left out at once (one configuration each)
  // and their neighbours joined anew: left for the edge checks to find,
  // they cost many more edge checks, and left out without rejoining,
  // longer plans (docs/performance-log.md).
  if (!anywhere_[static_cast<std::size_t>(slot)]) rm->dropInvalidVertices();
  cut_short = f.cut_short || rm->deadlineSeen();
  return rm;
}

void RoadmapSet::useCache(RoadmapCache& cache, const Scenario& scenario) {
  // Everything building depends on, numbers written exactly: the scenario
  // but its robots and name, the robot's description but where it starts
  // and ends (and for an arm with nothing in reach, its base), the sample
  // count, the neighbours and the roadmap's own seed. Equal keys build
  // equal roadmaps.
  CacheKeyWriter world;
  world << scenario.workspace.lo << scenario.workspace.hi << scenario.resolution.translation
        << scenario.resolution.rotation << scenario.resolution.joint
        << static_cast<std::uint64_t>(scenario.obstacles.size());
  for (const Obstacle& o : scenario.obstacles) {
    if (o.type == Obstacle::Type::Box) world << std::uint64_t{0} << o.center << o.size << o.angle;
    else world << std::uint64_t{1} << o.center << o.radius;
  }
  const std::string world_key = world.take();
  cache_ = &cache;
  cache_keys_.assign(roadmaps_.size(), {});
  for (std::size_t r = 0; r < slot_.size(); ++r) {
    const auto slot = static_cast<std::size_t>(slot_[r]);
    if (!cache_keys_[slot].empty()) continue;
    const RobotSpec& spec = scenario.robots.at(r);
    CacheKeyWriter robot;
    if (spec.kind == RobotKind::Mobile) {
      if (spec.shape == MobileShape::Disc) robot << std::uint64_t{0} << spec.radius;
      else robot << std::uint64_t{1} << spec.box_size;
    } else {
      robot << std::uint64_t{2};
      if (!anywhere_[slot]) robot << spec.base_position << spec.base_angle;
      robot << spec.links << spec.link_radius << static_cast<std::uint64_t>(spec.joint_limits.size());
      for (const auto& [lo, hi] : spec.joint_limits) robot << lo << hi;
    }
    robot << static_cast<std::uint64_t>(initialSamples(static_cast<int>(r)))
          << static_cast<std::uint64_t>(neighbors_)
          << splitSeed(seed_, static_cast<std::uint64_t>(seedSlot(static_cast<int>(r))));
    cache_keys_[slot] = world_key + robot.take();
  }
}

int RoadmapSet::initialSamples(int robot) const {
  if (samples_ > 0) return samples_;
  const RobotModel& m = *models_[static_cast<std::size_t>(robot)];
  // An arm's joint space: 1,000 vertices, a balance between the time of
  // connecting the roadmap (its k-nearest search, much of a small plan's
  // time) and plan length (docs/performance-log.md).
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
      bool cut_short = false;
      rm = buildRoadmap(robot, slot, cut_short);
      if (key && !cut_short) cache_->put(*key, rm->snapshot(), t_work_done - work_before);
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
