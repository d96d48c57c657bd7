#include "earc/planning/ompl_composite.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>

#include <algorithm>
#include <atomic>
#include <numbers>
#include <optional>
#include <random>

#include "earc/geometry/shapes.hpp"
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

OmplComposite::OmplComposite(const CompositeChecker& checker, std::vector<ConfigBox> bounds)
    : checker_(checker), bounds_(std::move(bounds)) {
  const auto& robots = checker.robots();
  auto compound = std::make_shared<ob::CompoundStateSpace>();
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const RobotModel& m = *robots[r];
    const ConfigBox& b = bounds_[r];
    // OMPL refuses an empty interval: give a degenerate one some width.
    if (m.isMobile()) {
      auto se2 = std::make_shared<ob::SE2StateSpace>();
      ob::RealVectorBounds xy(2);
      for (unsigned j = 0; j < 2; ++j) {
        xy.setLow(j, b.lo[j]);
        xy.setHigh(j, std::max(b.hi[j], b.lo[j] + 1e-9));
      }
      se2->setBounds(xy);
      compound->addSubspace(se2, 1.0);
    } else {
      const auto dim = static_cast<unsigned>(m.dim());
      auto rv = std::make_shared<ob::RealVectorStateSpace>(dim);
      ob::RealVectorBounds joints(dim);
      for (unsigned j = 0; j < dim; ++j) {
        joints.setLow(j, b.lo[j]);
        joints.setHigh(j, std::max(b.hi[j], b.lo[j] + 1e-9));
      }
      rv->setBounds(joints);
      compound->addSubspace(rv, 1.0);
    }
  }
  compound->lock();
  space_ = compound;
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
  const auto* cs = s->as<ob::CompoundState>();
  const auto& robots = checker_.robots();
  out.resize(robots.size());
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const RobotModel& m = *robots[r];
    const auto index = static_cast<unsigned>(r);
    out[r].resize(static_cast<std::size_t>(m.dim()));
    if (m.isMobile()) {
      const auto* se2 = cs->as<ob::SE2StateSpace::StateType>(index);
      out[r] = {se2->getX(), se2->getY(), se2->getYaw()};
    } else {
      const auto* rv = cs->as<ob::RealVectorStateSpace::StateType>(index);
      std::copy(rv->values, rv->values + m.dim(), out[r].begin());
    }
  }
}

void OmplComposite::fromComposite(const CompositeState& q, ob::State* s) const {
  auto* cs = s->as<ob::CompoundState>();
  const auto& robots = checker_.robots();
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const auto index = static_cast<unsigned>(r);
    if (robots[r]->isMobile()) {
      auto* se2 = cs->as<ob::SE2StateSpace::StateType>(index);
      se2->setXY(q[r][0], q[r][1]);
      se2->setYaw(geo::wrapAngle(q[r][2]));
    } else {
      auto* rv = cs->as<ob::RealVectorStateSpace::StateType>(index);
      std::copy(q[r].begin(), q[r].end(), rv->values);
    }
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
