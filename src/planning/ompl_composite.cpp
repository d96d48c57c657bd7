#include "earc/planning/ompl_composite.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "earc/geometry/shapes.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/random.hpp"

namespace ob = ompl::base;

namespace earc {

namespace {

// The sampler stream of the planner running on this thread (see
// SeededPlanningStream), if any.
thread_local std::optional<std::uint64_t> t_stream;

// Streams handed to samplers allocated outside any SeededPlanningStream
// start here, far from the planners' small stream numbers.
constexpr std::uint64_t kFallbackStreamBase = 1ULL << 32;

class StateChecker : public ob::StateValidityChecker {
 public:
  StateChecker(const ob::SpaceInformationPtr& si, const OmplComposite& c) : ob::StateValidityChecker(si), c_(c) {}
  bool isValid(const ob::State* s) const override {
    thread_local CompositeState q;
    c_.toComposite(s, q);
    return c_.checker().stateValid(q);
  }

 private:
  const OmplComposite& c_;
};

// Motion checks at the instants of the time-stamped motion. OMPL's
// valid/invalid motion counters are left alone: planners call this from
// several threads and those counters are plain integers.
class MotionChecker : public ob::MotionValidator {
 public:
  MotionChecker(const ob::SpaceInformationPtr& si, const OmplComposite& c) : ob::MotionValidator(si), c_(c) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    thread_local CompositeState a, b;
    c_.toComposite(s1, a);
    c_.toComposite(s2, b);
    return c_.checker().motionValid(a, b);
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& last_valid) const override {
    thread_local CompositeState a, b;
    c_.toComposite(s1, a);
    c_.toComposite(s2, b);
    const double fraction = c_.checker().lastValidFraction(a, b);
    if (fraction >= 1.0) return true;
    if (last_valid.first != nullptr) si_->getStateSpace()->interpolate(s1, s2, fraction, last_valid.first);
    last_valid.second = fraction;
    return false;
  }

 private:
  const OmplComposite& c_;
};

}  // namespace

// Uniform sampling inside the per-robot bounds from our own engine.
class CompositeSampler : public ob::StateSampler {
 public:
  CompositeSampler(const ob::StateSpace* space, const OmplComposite& c, std::uint64_t seed)
      : ob::StateSampler(space), c_(c), rng_(seed) {}
  void sampleUniform(ob::State* state) override {
    q_.resize(c_.bounds_.size());
    for (std::size_t r = 0; r < q_.size(); ++r) {
      const auto& b = c_.bounds_[r];
      q_[r].resize(b.lo.size());
      for (std::size_t j = 0; j < b.lo.size(); ++j) q_[r][j] = uniform(rng_, b.lo[j], b.hi[j]);
    }
    c_.fromComposite(q_, state);
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    c_.toComposite(near, q_);
    for (std::size_t r = 0; r < q_.size(); ++r) {
      const auto& b = c_.bounds_[r];
      for (std::size_t j = 0; j < b.lo.size(); ++j)
        q_[r][j] = std::clamp(q_[r][j] + uniform(rng_, -distance, distance), b.lo[j], b.hi[j]);
    }
    c_.fromComposite(q_, state);
  }
  // A box around the mean is enough for the planners used here (none of
  // them relies on Gaussian sampling).
  void sampleGaussian(ob::State* state, const ob::State* mean, double std_dev) override {
    sampleUniformNear(state, mean, 2.0 * std_dev);
  }

 private:
  const OmplComposite& c_;
  std::mt19937_64 rng_;
  CompositeState q_;
};

std::vector<ConfigBox> compositeBounds(const CollisionWorld& world, const std::vector<const RobotModel*>& robots,
                                       const std::vector<ConfigBox>& region,
                                       const std::vector<CompositeState>& must_contain) {
  std::vector<ConfigBox> boxes(robots.size());
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const RobotModel& m = *robots[r];
    ConfigBox& b = boxes[r];
    if (r < region.size() && !region[r].lo.empty())
      b = region[r];
    else
      m.samplingBounds(world.workspace(), b.lo, b.hi);
    for (std::size_t j = 0; j < b.lo.size(); ++j) {
      if (m.isMobile() && j == 2) {  // headings: always the whole circle
        b.lo[j] = -std::numbers::pi;
        b.hi[j] = std::numbers::pi;
        continue;
      }
      for (const CompositeState& q : must_contain) {
        b.lo[j] = std::min(b.lo[j], q[r][j]);
        b.hi[j] = std::max(b.hi[j], q[r][j]);
      }
    }
  }
  return boxes;
}

namespace {

// All robots' coordinates in one flat vector: a single OMPL space and one
// allocation per state. A compound of one SE2StateSpace per robot made
// 3 OMPL spaces per robot, and OMPL unregisters each space from a global
// list on destruction, O(spaces) each: tearing down the space of the
// coupled method on 5,000 robots took longer than its time limit. The
// metric and interpolation are those of that compound, computed in the
// same order (so planners take the same steps): per robot, Euclidean in
// x, y plus half the shortest arc of the heading for a mobile robot,
// Euclidean in the joints for an arm; headings move along the shortest
// arc and stay in [-pi, pi].
class FlatCompositeSpace : public ob::RealVectorStateSpace {
 public:
  struct Block {
    unsigned offset, dim;
    bool mobile;  // x, y, heading
  };

  FlatCompositeSpace(std::vector<Block> blocks, unsigned dim)
      : ob::RealVectorStateSpace(dim), blocks_(std::move(blocks)) {
    setName("earc-composite" + getName());
  }

  double distance(const ob::State* s1, const ob::State* s2) const override {
    // A unit of work (Deadline::withWorkBudgets): on a tree of thousands
    // of states, a coupled search's nearest-neighbour lookups are most of
    // its time, more than its collision checks.
    countWork(1);
    const double* a = s1->as<StateType>()->values;
    const double* b = s2->as<StateType>()->values;
    double total = 0.0;
    for (const Block& k : blocks_) {
      const unsigned euclidean = k.mobile ? 2 : k.dim;
      double sq = 0.0;
      for (unsigned j = k.offset; j < k.offset + euclidean; ++j) {
        const double d = a[j] - b[j];
        sq += d * d;
      }
      double dist = std::sqrt(sq);
      if (k.mobile) dist += kHeadingWeight * arc(a[k.offset + 2], b[k.offset + 2]);
      total += dist;
    }
    return total;
  }

  void interpolate(const ob::State* from, const ob::State* to, double t, ob::State* state) const override {
    const double* a = from->as<StateType>()->values;
    const double* b = to->as<StateType>()->values;
    double* out = state->as<StateType>()->values;
    for (const Block& k : blocks_)
      for (unsigned j = k.offset; j < k.offset + k.dim; ++j)
        out[j] = isHeading(k, j) ? headingBetween(a[j], b[j], t) : a[j] + (b[j] - a[j]) * t;
  }

  void enforceBounds(ob::State* state) const override {
    double* v = state->as<StateType>()->values;
    for (const Block& k : blocks_)
      for (unsigned j = k.offset; j < k.offset + k.dim; ++j)
        v[j] = isHeading(k, j) ? geo::wrapAngle(v[j]) : std::clamp(v[j], bounds_.low[j], bounds_.high[j]);
  }

  bool satisfiesBounds(const ob::State* state) const override {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const double* v = state->as<StateType>()->values;
    for (unsigned j = 0; j < dimension_; ++j)
      if (v[j] - eps > bounds_.high[j] || v[j] + eps < bounds_.low[j]) return false;
    return true;
  }

  double getMaximumExtent() const override {
    double total = 0.0;
    for (const Block& k : blocks_) {
      const unsigned euclidean = k.mobile ? 2 : k.dim;
      double sq = 0.0;
      for (unsigned j = k.offset; j < k.offset + euclidean; ++j) {
        const double d = bounds_.high[j] - bounds_.low[j];
        sq += d * d;
      }
      double extent = std::sqrt(sq);
      if (k.mobile) extent += kHeadingWeight * std::numbers::pi;
      total += extent;
    }
    return total;
  }

 private:
  static constexpr double kHeadingWeight = 0.5;  // as in OMPL's SE2StateSpace
  static bool isHeading(const Block& k, unsigned j) { return k.mobile && j == k.offset + 2; }
  static double arc(double a, double b) {
    const double d = std::abs(a - b);
    return d > std::numbers::pi ? 2.0 * std::numbers::pi - d : d;
  }
  static double headingBetween(double from, double to, double t) {
    double diff = to - from;
    if (std::abs(diff) <= std::numbers::pi) return from + diff * t;
    diff = diff > 0.0 ? 2.0 * std::numbers::pi - diff : -2.0 * std::numbers::pi - diff;
    double v = from - diff * t;
    if (v > std::numbers::pi)
      v -= 2.0 * std::numbers::pi;
    else if (v < -std::numbers::pi)
      v += 2.0 * std::numbers::pi;
    return v;
  }

  std::vector<Block> blocks_;
};

}  // namespace

OmplComposite::OmplComposite(const CompositeChecker& checker, std::vector<ConfigBox> bounds)
    : checker_(checker), bounds_(std::move(bounds)) {
  const auto& robots = checker.robots();
  std::vector<FlatCompositeSpace::Block> blocks;
  unsigned dim = 0;
  for (const RobotModel* m : robots) {
    offsets_.push_back(dim);
    blocks.push_back({dim, static_cast<unsigned>(m->dim()), m->isMobile()});
    dim += static_cast<unsigned>(m->dim());
  }
  auto flat = std::make_shared<FlatCompositeSpace>(std::move(blocks), dim);
  ob::RealVectorBounds box(dim);
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const ConfigBox& b = bounds_[r];
    for (std::size_t j = 0; j < b.lo.size(); ++j) {
      const auto index = offsets_[r] + static_cast<unsigned>(j);
      if (robots[r]->isMobile() && j == 2) {
        box.setLow(index, -std::numbers::pi);
        box.setHigh(index, std::numbers::pi);
        continue;
      }
      // OMPL refuses an empty interval: give a degenerate one some width.
      box.setLow(index, b.lo[j]);
      box.setHigh(index, std::max(b.hi[j], b.lo[j] + 1e-9));
    }
  }
  flat->setBounds(box);
  space_ = flat;
  auto fallback = std::make_shared<std::atomic<std::uint64_t>>(kFallbackStreamBase);
  space_->setStateSamplerAllocator([this, fallback](const ob::StateSpace* s) -> ob::StateSamplerPtr {
    const std::uint64_t stream = t_stream ? *t_stream : fallback->fetch_add(1);
    return std::make_shared<CompositeSampler>(s, *this, splitSeed(seed_, stream));
  });
  si_ = std::make_shared<ob::SpaceInformation>(space_);
  si_->setStateValidityChecker(std::make_shared<StateChecker>(si_, *this));
  si_->setMotionValidator(std::make_shared<MotionChecker>(si_, *this));
  si_->setup();
}

void OmplComposite::toComposite(const ob::State* s, CompositeState& out) const {
  const double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
  const auto& robots = checker_.robots();
  out.resize(robots.size());
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const double* first = v + offsets_[r];
    out[r].assign(first, first + robots[r]->dim());
  }
}

void OmplComposite::fromComposite(const CompositeState& q, ob::State* s) const {
  double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
  const auto& robots = checker_.robots();
  for (std::size_t r = 0; r < robots.size(); ++r) {
    std::copy(q[r].begin(), q[r].end(), v + offsets_[r]);
    if (robots[r]->isMobile()) v[offsets_[r] + 2] = geo::wrapAngle(q[r][2]);
  }
}

SeededPlanningStream::SeededPlanningStream(std::uint64_t stream)
    : had_previous_(t_stream.has_value()), previous_(t_stream.value_or(0)) {
  t_stream = stream;
}

SeededPlanningStream::~SeededPlanningStream() {
  if (had_previous_)
    t_stream = previous_;
  else
    t_stream.reset();
}

}  // namespace earc
