// MotionGuard: one robot checked against moving obstacles at local instants,
// for the space-time search (space_time_search.cpp). Internal to src/planning.
//
// Each obstacle's bounding-disc centre is tabulated once per search, with
// boxes over chunks of instants, so that a motion far from an obstacle
// costs a few box tests instead of one interpolation and test per instant.
// Where an arm takes part, whose bounding disc is centred on its fixed base
// and so always meets a neighbour's, the obstacle's bodies are also bounded
// over each chunk (RobotModel::boundsWithin), and tested against the
// robot's bodies over the part of its motion in that chunk. A search tries
// one edge at many start steps, and a motion's states and bodies are the
// same whatever the step: they are kept for the whole search (motionFree's
// `edge`), as are the obstacles' bodies at each instant (freeOf), which the
// search meets again and again.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/geometry/shapes.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/solver.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc::spacetime {

// The box spanned by two points: where a bounding centre moving straight
// from a to b passes.
inline geo::Aabb spanOf(geo::Vec2 a, geo::Vec2 b) {
  return {{std::min(a.x, b.x), std::min(a.y, b.y)}, {std::max(a.x, b.x), std::max(a.y, b.y)}};
}

// Checks a robot against moving obstacles at local instants, through boxes
// over chunks of instants (see the file's opening comment). Not thread-safe.
class MotionGuard {
 public:
  // With a poll, the robot is not free anywhere once its deadline has
  // expired: every check of it against an obstacle's bodies counts their
  // dimensions as work (an arm of thousands of links takes milliseconds).
  MotionGuard(const RobotModel& model, const std::vector<MovingObstacle>& obstacles, std::size_t last_instant,
              DeadlinePoll* poll = nullptr)
      : model_(model), obstacles_(obstacles), last_(last_instant), poll_(poll) {
    for (const auto& o : obstacles_) {
      Track tr;
      tr.work = static_cast<std::size_t>(model_.dim() + o.model->dim());
      tr.centers_decide = model_.isMobile() && o.model->isMobile();
      tr.centers.reserve(last_ + 1);
      // Centres at whole steps come from the path's states (past its end,
      // the last); a midpoint's is halfway between its neighbours' (see
      // RobotModel::boundingCenter), exact up to rounding, which a broad
      // phase with a contact tolerance below it cannot notice.
      auto centerAt = [&](std::size_t t) { return o.model->boundingCenter(o.path->at(t)); };
      geo::Vec2 here = centerAt(o.offset);
      for (std::size_t k = 0; k <= last_; ++k) {
        const std::size_t instant = 2 * o.offset + k;
        if (instant % 2 == 0) {
          here = centerAt(instant / 2);
          tr.centers.push_back(here);
        } else {
          const geo::Vec2 next = centerAt(instant / 2 + 1);
          tr.centers.push_back({0.5 * (here.x + next.x), 0.5 * (here.y + next.y)});
        }
      }
      for (std::size_t c = 0; c * kChunk <= last_; ++c) {
        geo::Aabb box;
        for (std::size_t k = c * kChunk; k < std::min(last_ + 1, (c + 1) * kChunk); ++k)
          box.expand({tr.centers[k], tr.centers[k]});
        tr.chunks.push_back(box);
      }
      only_mobile_ = only_mobile_ && tr.centers_decide;
      tracks_.push_back(std::move(tr));
    }
    countWork(obstacles_.size() * (last_ + 1) / kBroadTestsPerUnit);
  }

  // The robot at q is free of every obstacle at local instant k.
  bool free(const double* q, std::size_t k) {
    const geo::Vec2 c = model_.boundingCenter(q);
    // The search asks about the same vertex at consecutive instants (waits,
    // holding the goal): its bodies are placed once for all of them.
    auto own = [&]() -> const PlacedBodies& {
      if (vertex_.empty() || !std::equal(vertex_q_.begin(), vertex_q_.end(), q)) {
        vertex_q_.assign(q, q + model_.dim());
        vertex_.place(model_, q);
      }
      return vertex_;
    };
    countWork(obstacles_.size() / kBroadTestsPerUnit + 1);
    for (std::size_t i = 0; i < obstacles_.size(); ++i)
      if (!freeOf(i, c, k, own)) return false;
    return true;
  }

  static constexpr std::uint64_t kOnce = ~std::uint64_t{0};

  // The first local step from which no obstacle that could touch a robot
  // centred in `where` moves any more (one may still move out of reach):
  // from then on the world the robot searches in stands still.
  std::size_t stillFrom(const geo::Aabb& where) const {
    std::size_t from = 0;
    for (const MovingObstacle& o : obstacles_) {
      const geo::Aabb near = where.inflated(model_.boundingRadius() + o.model->boundingRadius());
      const std::size_t dim = static_cast<std::size_t>(o.model->dim());
      const std::size_t end = std::min(o.path->size() - 1, o.offset + last_ / 2 + 1);
      for (std::size_t s = end; s-- > o.offset;) {
        const double* a = o.path->at(s);
        const double* b = o.path->at(s + 1);
        if (std::equal(a, a + dim, b)) continue;
        if (!spanOf(o.model->boundingCenter(a), o.model->boundingCenter(b)).overlaps(near)) continue;
        from = std::max(from, s + 1 - o.offset);
        break;
      }
    }
    return from;
  }

  // The robot moving straight a -> b over `steps` steps from local step tau
  // is free at instants 2 tau + 1 .. 2 tau + 2 steps. `edge` names the
  // motion (the search's directed vertex pair), kept for the search; kOnce: met once.
  bool motionFree(const double* a, const double* b, int steps, std::size_t tau, std::uint64_t edge = kOnce) {
    return only_mobile_ ? motionFreeOf<true>(a, b, steps, tau, edge) : motionFreeOf<false>(a, b, steps, tau, edge);
  }

 private:
  // motionFree, compiled apart for a world of mobile robots only (their
  // planning's innermost loop), where the centres' tests decide alone.
  template <bool kOnlyMobile>
  bool motionFreeOf(const double* a, const double* b, int steps, std::size_t tau, std::uint64_t edge) {
    const std::size_t k0 = 2 * tau + 1, k1 = 2 * tau + 2 * static_cast<std::size_t>(steps);
    const std::size_t dim = static_cast<std::size_t>(model_.dim());
    const geo::Aabb swept = spanOf(model_.boundingCenter(a), model_.boundingCenter(b));
    // The robot's bodies over the part of the motion in chunk c of
    // instants: interpolate moves each joint of an arm evenly between its
    // ends (and a mobile robot's position; boundsWithin leaves its heading
    // out). Made when first needed.
    const std::size_t first_chunk = k0 / kChunk;  // asked for chunks first_chunk .. min(k1, last_) / kChunk
    bool within_made = false;
    auto motionBox = [&](std::size_t c) -> const geo::Aabb& {
      if (!within_made) {
        within_.assign(std::min(k1, last_) / kChunk + 1 - first_chunk, geo::Aabb{});
        within_made = true;
      }
      geo::Aabb& box = within_[c - first_chunk];
      if (box.lo.x > box.hi.x) {
        const std::size_t from = std::max(k0, c * kChunk), to = std::min(k1, c * kChunk + kChunk - 1);
        lo_.resize(dim);
        hi_.resize(dim);
        model_.interpolate(a, b, static_cast<double>(from - 2 * tau) / (2 * steps), lo_.data());
        model_.interpolate(a, b, static_cast<double>(to - 2 * tau) / (2 * steps), hi_.data());
        for (std::size_t i = 0; i < dim; ++i)
          if (lo_[i] > hi_[i]) std::swap(lo_[i], hi_[i]);
        box = model_.boundsWithin(lo_.data(), hi_.data());
        countWork(dim);
      }
      return box;
    };
    // The robot's state and bodies at each instant of the motion, made when
    // first needed and shared by every obstacle it comes near. A motion is
    // kept only once it comes near an obstacle: most never do.
    const std::size_t n = k1 - k0 + 1;
    Motion* motion = nullptr;
    if (edge != kOnce)
      if (auto it = motions_.find(edge); it != motions_.end() && it->second.state.size() == n) motion = &it->second;
    auto stateAt = [&](std::size_t k) -> const double* {
      if (!motion) {
        const bool keep = edge != kOnce && kept_ + n <= kKeptInstants;
        motion = keep ? &motions_[edge] : &once_;
        if (keep) kept_ += n;
        motion->q.resize(n * dim);
        motion->state.assign(n, 0);
        if (motion->bodies.size() < n) motion->bodies.resize(n);
      }
      const std::size_t j = k - k0;
      double* q = motion->q.data() + j * dim;
      if (motion->state[j] == 0) {
        model_.interpolate(a, b, static_cast<double>(k - 2 * tau) / (2 * steps), q);
        motion->state[j] = 1;
      }
      return q;
    };
    // The broad phase's tests count as work too (a budget of work would
    // otherwise last several times its seconds where many robots pass
    // near), a few to a unit: they cost a few nanoseconds each.
    std::size_t tests = 0;
    struct Counted {
      std::size_t& tests;
      ~Counted() { countWork(tests / kBroadTestsPerUnit); }
    } counted{tests};
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
      const double reach = model_.boundingRadius() + obstacles_[i].model->boundingRadius();
      const geo::Aabb near = swept.inflated(reach);
      const bool centers_decide = kOnlyMobile || tracks_[i].centers_decide;
      for (std::size_t k = k0; k <= k1; ++tests) {
        const std::size_t kc = std::min(k, last_);
        const std::size_t chunk_end = (kc / kChunk + 1) * kChunk;  // first instant of the next chunk
        if (k <= last_ && (!tracks_[i].chunks[kc / kChunk].overlaps(near) ||
                           (!centers_decide && !bodiesWithin(i, kc / kChunk).overlaps(motionBox(kc / kChunk))))) {
          k = chunk_end;
          continue;
        }
        if (k > last_ && !geo::Aabb{tracks_[i].centers[last_], tracks_[i].centers[last_]}.overlaps(near)) break;
        const double* q = stateAt(k);
        const std::size_t j = k - k0;
        auto own = [&]() -> const PlacedBodies& {
          if (motion->state[j] < 2) {
            motion->bodies[j].place(model_, q);
            motion->state[j] = 2;
          }
          return motion->bodies[j];
        };
        if (!freeOf(i, model_.boundingCenter(q), k, own, centers_decide || k > last_ ? nullptr : &motionBox(kc / kChunk)))
          return false;
        ++k;
      }
    }
    return true;
  }

  static constexpr std::size_t kChunk = 16;
  static constexpr std::size_t kBroadTestsPerUnit = 8;
  struct Track {
    std::vector<geo::Vec2> centers;  // bounding centre per instant 0..last
    std::vector<geo::Aabb> chunks;   // box of the centres of each chunk of instants
    std::vector<geo::Aabb> bodies_within;  // of the bodies over each chunk, empty until needed
    bool centers_decide = false;  // both robots mobile: the centres' test is the bodies' already
    std::vector<PlacedBodies> placed;  // bodies per instant, placed when first needed
    std::size_t work = 0;              // of a check of the robot's bodies against these
  };

  // A box holding obstacle i's bodies over chunk c of instants.
  const geo::Aabb& bodiesWithin(std::size_t i, std::size_t c) {
    std::vector<geo::Aabb>& boxes = tracks_[i].bodies_within;
    if (boxes.empty()) boxes.resize(tracks_[i].chunks.size());
    geo::Aabb& box = boxes[c];
    if (box.lo.x > box.hi.x) {
      const MovingObstacle& o = obstacles_[i];
      const std::size_t k0 = c * kChunk, k1 = std::min(last_, k0 + kChunk - 1);
      box = boundsOverInstants(*o.model, *o.path, 2 * o.offset + k0, 2 * o.offset + k1, scratch_q_, lo_, hi_);
      countWork(tracks_[i].work);
    }
    return box;
  }

  // The robot, centred at c with bodies own() (which lie in `within` when
  // given), is free of obstacle i at local instant k. The obstacle's
  // bodies at an instant are placed once per search.
  template <class Own>
  bool freeOf(std::size_t i, geo::Vec2 c, std::size_t k, Own&& own, const geo::Aabb* within = nullptr) {
    const MovingObstacle& o = obstacles_[i];
    Track& tr = tracks_[i];
    const geo::Vec2 oc = tr.centers[std::min(k, last_)];
    const double reach = model_.boundingRadius() + o.model->boundingRadius();
    const geo::Vec2 d = c - oc;
    if (d.x * d.x + d.y * d.y > reach * reach) return true;
    PlacedBodies* theirs = &scratch_;
    if (k <= last_) {
      if (tr.placed.size() <= k) tr.placed.resize(std::max(k + 1, 2 * tr.placed.size()));
      theirs = &tr.placed[k];
    }
    if (theirs->empty() || theirs == &scratch_) {
      scratch_q_.resize(static_cast<std::size_t>(o.model->dim()));
      stateAtInstant(*o.model, *o.path, 2 * o.offset + k, scratch_q_.data());
      theirs->place(*o.model, scratch_q_.data());
    }
    // The robot's bounding disc against the obstacle's tight bounds decides
    // most near misses before the robot's own bodies are placed.
    const double r = model_.boundingRadius();
    geo::Aabb disc{{c.x - r, c.y - r}, {c.x + r, c.y + r}};
    if (within)
      disc = {{std::max(disc.lo.x, within->lo.x), std::max(disc.lo.y, within->lo.y)},
              {std::min(disc.hi.x, within->hi.x), std::min(disc.hi.y, within->hi.y)}};
    if (std::none_of(theirs->bounds.begin(), theirs->bounds.end(), [&](const geo::Aabb& b) { return b.overlaps(disc); }))
      return true;
    if (poll_ && poll_->expired(tr.work)) return false;
    return !bodiesTouch(own(), *theirs);
  }

  const RobotModel& model_;
  const std::vector<MovingObstacle>& obstacles_;
  std::size_t last_;
  DeadlinePoll* poll_;
  std::vector<Track> tracks_;
  PlacedBodies scratch_;  // an obstacle past the last tabulated instant
  std::vector<double> scratch_q_, lo_, hi_;
  std::vector<geo::Aabb> within_;  // see motionFreeOf
  bool only_mobile_ = true;        // the robot and every obstacle
  PlacedBodies vertex_;  // the robot at vertex_q_, see free()
  std::vector<double> vertex_q_;
  // The robot along a motion, per instant of it, see motionFree().
  struct Motion {
    std::vector<double> q;
    std::vector<unsigned char> state;  // 0 nothing, 1 state, 2 state and bodies
    std::vector<PlacedBodies> bodies;
  };
  // Kept motions' instants at most, per search: a search over a whole
  // large map (the prioritized baseline on den520d) would otherwise keep
  // hundreds of megabytes.
  static constexpr std::size_t kKeptInstants = std::size_t{1} << 17;
  Motion once_;
  std::unordered_map<std::uint64_t, Motion> motions_;
  std::size_t kept_ = 0;
};

}  // namespace earc::spacetime
