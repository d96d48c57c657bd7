// Static-world and robot-robot collision checking with the contract's rules.
//
// Broad phase: below kTreeMinObstacles obstacles a plain loop over their
// AABBs; from there on FCL's dynamic AABB tree, walked read-only with the
// body's AABB. Either way the broad phase only proposes candidates: every
// candidate is decided by geo::touches (exact signed distance, overlap >
// kContactTolerance), never by FCL's own contact rule.
#include "earc/collision/collision_world.hpp"

#include "obstacle_cells.hpp"

#include <algorithm>
#include <cstdint>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>

namespace earc {
namespace {

// Below this many obstacles a plain loop over their AABBs beats FCL's tree
// (`earc-bench micro`; the figures are in docs/performance-log.md). FCL's
// own manager.collide() needs a heap-allocated query object, so the tree is
// walked directly instead.
constexpr std::size_t kTreeMinObstacles = 32;

// Thickness of the 3-D stand-ins for planar obstacles in FCL; any positive
// value works since only the x-y extents of their AABBs are ever read.
constexpr double kSlabThickness = 1.0;

// Cells of the obstacle-bounds table beside the tree: about 4 MB, fine
// enough (0.1 on a 161 x 63 map) to tell a robot in a one-cell aisle from
// the walls beside it.
constexpr std::size_t kObstacleCells = std::size_t{1} << 20;

}  // namespace

// FCL's dynamic AABB tree over the obstacles. The manager stores raw
// pointers to the collision objects, which this struct owns. Queries read
// the tree only, so concurrent queries are safe.
struct CollisionWorld::Broadphase {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  fcl::DynamicAABBTreeCollisionManagerd manager;

  explicit Broadphase(const std::vector<Obstacle>& obstacles) {
    objects.reserve(obstacles.size());
    std::vector<fcl::CollisionObjectd*> raw;
    for (std::size_t i = 0; i < obstacles.size(); ++i) {
      const Obstacle& o = obstacles[i];
      fcl::Transform3d tf = fcl::Transform3d::Identity();
      tf.translation() = fcl::Vector3d(o.center.x, o.center.y, 0.0);
      std::shared_ptr<fcl::CollisionGeometryd> shape;
      if (o.type == Obstacle::Type::Circle) {
        shape = std::make_shared<fcl::Cylinderd>(o.radius, kSlabThickness);
      } else {
        shape = std::make_shared<fcl::Boxd>(o.size.x, o.size.y, kSlabThickness);
        tf.linear() = fcl::AngleAxisd(o.angle, fcl::Vector3d::UnitZ()).toRotationMatrix();
      }
      auto obj = std::make_unique<fcl::CollisionObjectd>(shape, tf);
      obj->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
      raw.push_back(obj.get());
      objects.push_back(std::move(obj));
    }
    manager.registerObjects(raw);
    manager.setup();
  }

  // Calls visit(obstacle index) for every obstacle whose AABB overlaps q
  // until visit returns true; returns whether it did.
  template <class Visit>
  bool query(const geo::Aabb& q, Visit&& visit) const {
    using Node = fcl::DynamicAABBTreeCollisionManagerd::DynamicAABBNode;
    const Node* root = manager.getTree().getRoot();
    if (root == nullptr) return false;
    // Explicit stack: the tree is balanced, so 64 levels hold any real
    // obstacle count; deeper trees spill to the heap.
    const Node* fixed[64];
    std::vector<const Node*> spill;
    int top = 0;
    auto push = [&](const Node* n) {
      if (top < 64) fixed[top++] = n;
      else spill.push_back(n);
    };
    auto pop = [&] {
      if (spill.empty()) return fixed[--top];
      const Node* n = spill.back();
      spill.pop_back();
      return n;
    };
    push(root);
    while (top > 0 || !spill.empty()) {
      const Node* n = pop();
      const auto& lo = n->bv.min_;
      const auto& hi = n->bv.max_;
      if (lo[0] > q.hi.x || hi[0] < q.lo.x || lo[1] > q.hi.y || hi[1] < q.lo.y) continue;
      if (!n->isLeaf()) {
        push(n->children[0]);
        push(n->children[1]);
        continue;
      }
      auto* obj = static_cast<const fcl::CollisionObjectd*>(n->data);
      if (visit(static_cast<std::size_t>(reinterpret_cast<std::uintptr_t>(obj->getUserData())))) return true;
    }
    return false;
  }
};

CollisionWorld::CollisionWorld(const Scenario& scenario) : CollisionWorld(scenario, BroadphaseMode::Auto) {}

CollisionWorld::CollisionWorld(const Scenario& scenario, BroadphaseMode mode) : workspace_(scenario.workspace) {
  obstacles_.reserve(scenario.obstacles.size());
  for (const Obstacle& o : scenario.obstacles) {
    obstacles_.push_back(o.body());
    obstacle_bounds_.push_back(geo::bounds(obstacles_.back()));
  }
  const bool tree = mode == BroadphaseMode::Tree ||
                    (mode == BroadphaseMode::Auto && obstacles_.size() >= kTreeMinObstacles);
  if (tree) {
    broadphase_ = std::make_unique<Broadphase>(scenario.obstacles);
    cells_ = std::make_unique<ObstacleCells>(obstacle_bounds_, kObstacleCells);
  }
}

CollisionWorld::~CollisionWorld() = default;

template <class Visit>
bool CollisionWorld::forEachCandidate(const geo::Aabb& box, Visit&& visit) const {
  // Most boxes in a large world are far from every obstacle: four look-ups
  // say so without walking the tree.
  if (broadphase_) return cells_->mayMeet(box) && broadphase_->query(box, visit);
  for (std::size_t i = 0; i < obstacles_.size(); ++i)
    if (obstacle_bounds_[i].overlaps(box) && visit(i)) return true;
  return false;
}

bool CollisionWorld::bodyFree(const geo::Body& body) const { return bodyFree(body, geo::bounds(body)); }

bool CollisionWorld::bodyFree(const geo::Body& body, const geo::Aabb& bb) const {
  // Negated so that a non-finite body (NaN extents) is never inside.
  if (!(geo::excessOutside(bb, workspace_) <= geo::kContactTolerance)) return false;
  return !forEachCandidate(bb, [&](std::size_t i) { return geo::touches(body, obstacles_[i]); });
}

void CollisionWorld::touchedObstacles(const geo::Body& body, std::vector<int>& out) const {
  const std::size_t first = out.size();
  forEachCandidate(geo::bounds(body), [&](std::size_t i) {
    if (geo::touches(body, obstacles_[i])) out.push_back(static_cast<int>(i));
    return false;
  });
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
}

bool CollisionWorld::stateValid(const RobotModel& robot, const double* q) const {
  // Per-thread scratch: no allocation per query, nothing shared between threads.
  thread_local PlacedBodies placed;
  return stateValid(robot, q, placed);
}

bool CollisionWorld::stateValid(const RobotModel& robot, const double* q, PlacedBodies& placed) const {
  if (!robot.withinLimits(q)) return false;
  placed.place(robot, q);
  if (robot.selfCollides(placed.bodies, placed.bounds)) return false;
  for (std::size_t i = 0; i < placed.bodies.size(); ++i)
    if (!bodyFree(placed.bodies[i], placed.bounds[i])) return false;
  return true;
}

namespace {

// Calls visit(q) with the configuration at each instant k / (2n), k = 0..2n,
// n = stepsBetween(a, b), of the straight motion a -> b, until visit returns
// false. Order: the ends, then halves, quarters, ... so that a blocked
// motion is usually rejected early; every instant is visited once.
template <class Visit>
void forEachInstant(const RobotModel& robot, const double* a, const double* b, Visit&& visit) {
  const long long last = 2LL * robot.stepsBetween(a, b);
  std::vector<double> q(static_cast<std::size_t>(robot.dim()));
  auto at = [&](long long k) {
    robot.interpolate(a, b, last == 0 ? 0.0 : static_cast<double>(k) / static_cast<double>(last), q.data());
    return visit(static_cast<const double*>(q.data()));
  };
  if (!at(0) || last == 0 || !at(last)) return;
  long long stride = 1;
  while (stride * 2 <= last) stride *= 2;
  for (; stride >= 1; stride /= 2)
    for (long long k = stride; k < last; k += 2 * stride)
      if (!at(k)) return;
}

}  // namespace

// A straight motion a -> b is valid when the configuration at every
// instant k / (2 n), k = 0..2n, n = robot.stepsBetween(a, b), is valid:
// exactly the instants (steps and midpoints) at which a time-stamped
// solution of that motion is validated. Thread-safe.
bool CollisionWorld::motionValid(const RobotModel& robot, const double* a, const double* b) const {
  bool valid = true;
  forEachInstant(robot, a, b, [&](const double* q) {
    valid = stateValid(robot, q);
    return valid;
  });
  return valid;
}

std::optional<bool> CollisionWorld::motionValid(const RobotModel& robot, const double* a, const double* b,
                                                DeadlinePoll& poll) const {
  const auto work = static_cast<std::size_t>(robot.dim());
  bool valid = true;
  bool out_of_time = false;
  forEachInstant(robot, a, b, [&](const double* q) {
    if (poll.expired(work)) {
      out_of_time = true;
      return false;
    }
    valid = stateValid(robot, q);
    return valid;
  });
  if (out_of_time) return std::nullopt;
  return valid;
}

int CollisionWorld::countInvalidInstants(const RobotModel& robot, const double* a, const double* b) const {
  int invalid = 0;
  forEachInstant(robot, a, b, [&](const double* q) {
    invalid += !stateValid(robot, q);
    return true;
  });
  return invalid;
}

void PlacedBodies::place(const RobotModel& model, const double* q) {
  model.bodies(q, bodies);
  bounds.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) bounds[i] = geo::bounds(bodies[i]);
}

bool bodiesTouch(const PlacedBodies& a, const PlacedBodies& b) {
  for (std::size_t i = 0; i < a.bodies.size(); ++i)
    for (std::size_t j = 0; j < b.bodies.size(); ++j)
      if (a.bounds[i].overlaps(b.bounds[j]) && geo::touches(a.bodies[i], b.bodies[j])) return true;
  return false;
}

bool boundingDiscsMeet(const RobotModel& a, const double* qa, const RobotModel& b, const double* qb) {
  // Compared squared (no square root). Rounding at the boundary cannot
  // matter, as touching needs an overlap of kContactTolerance.
  const double reach = a.boundingRadius() + b.boundingRadius();
  const geo::Vec2 gap = a.boundingCenter(qa) - b.boundingCenter(qb);
  return geo::dot(gap, gap) <= reach * reach;
}

void RobotAgainst::set(const RobotModel& model, const double* q) {
  model_ = &model;
  q_ = q;
  centre_ = model.boundingCenter(q);
  placed_ = false;
}

RobotAgainst::Result RobotAgainst::check(const RobotModel& other, const double* q_other) {
  // Most pairs fail the disc test, so the robot's bodies are placed only
  // at the first pair that passes it.
  const double reach = model_->boundingRadius() + other.boundingRadius();
  const geo::Vec2 gap = centre_ - other.boundingCenter(q_other);
  if (geo::dot(gap, gap) > reach * reach) return Result::Apart;
  if (!placed_) {
    mine_.place(*model_, q_);
    placed_ = true;
  }
  theirs_.place(other, q_other);
  return bodiesTouch(mine_, theirs_) ? Result::Touch : Result::Clear;
}

bool robotsTouch(const RobotModel& a, const double* qa, const RobotModel& b, const double* qb) {
  if (!boundingDiscsMeet(a, qa, b, qb)) return false;
  thread_local PlacedBodies pa;  // per-thread scratch, see stateValid
  thread_local PlacedBodies pb;
  pa.place(a, qa);
  pb.place(b, qb);
  return bodiesTouch(pa, pb);
}

double robotDistance(const RobotModel& a, const double* qa, const RobotModel& b, const double* qb) {
  std::vector<geo::Body> pa;
  std::vector<geo::Body> pb;
  a.bodies(qa, pa);
  b.bodies(qb, pb);
  double best = std::numeric_limits<double>::infinity();
  for (const geo::Body& x : pa)
    for (const geo::Body& y : pb) best = std::min(best, geo::signedDistance(x, y));
  return best;
}

}  // namespace earc
