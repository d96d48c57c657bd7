// Prioritized planning in space-time over roadmaps (ARC's first solver).
#include <algorithm>
#include <limits>
#include <numeric>
#include <queue>
#include <unordered_map>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/planning/solver.hpp"
#include "earc/util/random.hpp"

namespace earc {

namespace {

// Units of work (Deadline::withWorkBudgets) of one expansion of the
// space-time search, beside its collision checks: about its time.
constexpr std::size_t kWorkPerExpansion = 4;

// The box spanned by two points: where a bounding centre moving straight
// from a to b passes.
geo::Aabb spanOf(geo::Vec2 a, geo::Vec2 b) {
  return {{std::min(a.x, b.x), std::min(a.y, b.y)}, {std::max(a.x, b.x), std::max(a.y, b.y)}};
}

// Checks a robot against moving obstacles at local instants. Each
// obstacle's bounding-disc centre is tabulated once per search, with boxes
// over chunks of instants, so that a motion far from an obstacle costs a
// few box tests instead of one interpolation and test per instant. Where
// an arm takes part, whose bounding disc is centred on its fixed base and
// so always meets a neighbour's, the obstacle's bodies are also bounded
// over each chunk (RobotModel::boundsWithin), and tested against the
// robot's bodies over the part of its motion in that chunk.
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
  // centred in `where` moves any more: from then on the world the robot
  // searches in stands still. An obstacle may still move far from
  // `where` (every motion between its steps stays out of reach).
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
  // motion (the search's directed pair of vertices): its states and bodies
  // are the same whatever tau, and the search tries one edge at many
  // (ARC at 32 mobile robots with obstacles: 17 million states made for
  // 0.7 million distinct ones), so they are kept for the whole search, up
  // to kKeptInstants of them. kOnce: a motion met once.
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
  // bodies at an instant are placed once per search: the search meets
  // each instant again and again.
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
  // Kept motions' instants at most, per search (about 30 MB for a box
  // robot, 90 MB for a 5-link arm): a search over a whole large map (the
  // prioritized baseline on den520d) would otherwise keep hundreds of
  // megabytes. ARC's searches on 20 plans of 32 mobile robots with
  // obstacles kept 56,000 at most.
  static constexpr std::size_t kKeptInstants = std::size_t{1} << 17;
  Motion once_;
  std::unordered_map<std::uint64_t, Motion> motions_;
  std::size_t kept_ = 0;
};

// Two 32-bit values in one 64-bit key, the first in the high half.
std::uint64_t packPair(std::uint32_t hi, std::uint32_t lo) { return (static_cast<std::uint64_t>(hi) << 32) | lo; }

std::uint64_t nodeKey(int v, std::size_t tau) {
  return packPair(static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(tau));
}

std::uint64_t motionKey(int from, int to) {
  return packPair(static_cast<std::uint32_t>(from), static_cast<std::uint32_t>(to));
}

}  // namespace

const char* searchEndName(SearchEnd end) {
  switch (end) {
    case SearchEnd::Found: return "found";
    case SearchEnd::NoWay: return "no way";
    case SearchEnd::Capped: return "expansion cap";
    case SearchEnd::OutOfTime: return "out of time";
  }
  return "?";
}

// The heuristic is the straight-line distance to the goal in steps, or with
// graph_heuristic the steps of the shortest way over the graph's edges not
// known to be invalid (a Dijkstra search from the goal): as admissible, and
// far better informed on a maze-like map, where the straight line runs
// through walls.
std::optional<Path> spaceTimeSearch(QueryGraph& graph, int start, int goal,
                                    const std::vector<MovingObstacle>& obstacles, std::size_t horizon,
                                    std::size_t hold_until, const Deadline& deadline, std::size_t max_expansions,
                                    bool graph_heuristic, SearchEnd* end) {
  const RobotModel& model = graph.model();
  const int dim = model.dim();
  DeadlinePoll poll(deadline, kWorkPerClockRead);
  MotionGuard guard(model, obstacles, 2 * std::max(horizon, hold_until) + 2, &poll);
  bool capped = false;  // stopped at max_expansions
  auto fail = [&]() -> std::optional<Path> {
    if (end)
      *end = capped ? SearchEnd::Capped
             : poll.seenExpired() || graph.roadmap().poll().seenExpired() || deadline.expired() ? SearchEnd::OutOfTime
                                                                                                : SearchEnd::NoWay;
    return std::nullopt;
  };
  if (!guard.free(graph.config(start), 0)) return fail();
  // Unreachable in the region even with time ignored: say so now rather than
  // after enumerating every (vertex, time) pair up to the horizon.
  if (!shortestPath(graph, start, goal, deadline)) return fail();

  std::vector<double> h(static_cast<std::size_t>(graph.size()), -1.0);
  if (graph_heuristic) {
    // Steps to the goal over every edge not known invalid (unchecked ones
    // count as valid): no more than the robot needs, and consistent. A
    // vertex it does not reach cannot reach the goal.
    const double unreached = std::numeric_limits<double>::infinity();
    std::fill(h.begin(), h.end(), unreached);
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> frontier;
    h[static_cast<std::size_t>(goal)] = 0;
    frontier.push({0.0, goal});
    // Polled as it works: a whole map's roadmap can have 80,000 vertices.
    while (!frontier.empty()) {
      if (poll.expired(kWorkPerGraphPop)) return fail();
      const auto [d, v] = frontier.top();
      frontier.pop();
      if (d > h[static_cast<std::size_t>(v)]) continue;
      graph.forEachEdge(v, [&](int u, int steps, int edge) {
        if (graph.knownInvalid(edge) || d + steps >= h[static_cast<std::size_t>(u)]) return;
        h[static_cast<std::size_t>(u)] = d + steps;
        frontier.push({d + steps, u});
      });
    }
  }
  auto heuristic = [&](int v) {
    double& x = h[static_cast<std::size_t>(v)];
    if (x < 0) x = model.distance(graph.config(v), graph.config(goal));
    return x;
  };
  // The earliest arrival from which the robot can wait at its goal through
  // hold_until. When the goal is taken at hold_until itself there is none,
  // and searching the whole space-time graph to find that out is the most
  // expensive way a subproblem fails.
  std::size_t earliest_hold = 0;
  for (std::size_t k = 2 * hold_until + 1; k-- > 0;) {
    if (!guard.free(graph.config(goal), k)) {
      earliest_hold = k / 2 + 1;
      break;
    }
  }
  if (earliest_hold > hold_until) return fail();
  // Arriving later than hold_until needs only the arrival instant free.
  auto holds = [&](int v, std::size_t tau) {
    return tau >= earliest_hold && (tau <= hold_until || guard.free(graph.config(v), 2 * tau));
  };
  auto priority = [&](int v, std::size_t tau) {
    return std::max(static_cast<double>(tau) + heuristic(v), static_cast<double>(earliest_hold));
  };
  // From step `still` on, nothing within reach of the robot's region
  // moves: being at a vertex earlier is as good as being there later (it
  // can wait), so a vertex reached again no sooner than before is not
  // searched again. Waits at the goal are kept: holding it may need a
  // later arrival. (A search that finds no way used to enumerate every
  // vertex at every step up to the horizon.)
  geo::Aabb where{{-1e300, -1e300}, {1e300, 1e300}};
  if (const ConfigBox* region = graph.region()) {
    where = spanOf(model.boundingCenter(region->lo.data()), model.boundingCenter(region->hi.data()));
    where.expand(spanOf(model.boundingCenter(graph.config(start)), model.boundingCenter(graph.config(goal))));
  }
  const std::size_t still = guard.stillFrom(where);
  // Steps pushed reach the horizon at most: a world still only later
  // needs no table.
  std::vector<std::size_t> still_since(still <= horizon ? static_cast<std::size_t>(graph.size()) : 0,
                                       std::numeric_limits<std::size_t>::max());

  struct Item {
    double f;
    std::size_t tau;
    int v;
    bool operator>(const Item& o) const { return f != o.f ? f > o.f : tau < o.tau; }  // deeper first on ties
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  // (v, tau) -> predecessor. A node enters the queue only with its first
  // parent, so it leaves it once: no closed set is needed.
  std::unordered_map<std::uint64_t, std::uint64_t> parent;
  const std::uint64_t root = nodeKey(start, 0);
  parent.emplace(root, root);
  open.push({priority(start, 0), 0, start});
  std::vector<double> q(static_cast<std::size_t>(dim));
  std::size_t expansions = 0;
  std::optional<std::uint64_t> found;

  while (!open.empty()) {
    Item it = open.top();
    open.pop();
    const std::uint64_t key = nodeKey(it.v, it.tau);
    if (it.v == goal && holds(it.v, it.tau)) {
      found = key;
      break;
    }
    // The heuristic never overestimates: once the least f in the queue
    // is past the horizon, no arrival by the horizon is left to find.
    // (Searches that fail used to go on to the horizon, the expansion cap
    // or the budget; a half step of margin covers the metric's rounding
    // slack in step counts.)
    if (it.f > static_cast<double>(horizon) + 0.5) break;
    if (++expansions > max_expansions) {
      capped = true;
      break;
    }
    // The queue and the table of states reached count as work (see
    // MotionGuard). The poll is also read where the work is (MotionGuard
    // and Roadmap::edgeValid): an expansion on arms of thousands of links
    // can take a second.
    if (poll.expired(kWorkPerExpansion) || graph.roadmap().poll().seenExpired()) break;
    if (it.tau >= horizon) continue;
    auto push = [&](int u, std::size_t tau) {
      const double f = priority(u, tau);
      if (f == std::numeric_limits<double>::infinity()) return;  // no way on to the goal
      if (tau >= still && u != goal) {
        std::size_t& since = still_since[static_cast<std::size_t>(u)];
        if (since <= tau) return;
        since = tau;
      }
      if (parent.try_emplace(nodeKey(u, tau), key).second) open.push({f, tau, u});
    };
    // Wait one step.
    const double* here = graph.config(it.v);
    if (guard.free(here, 2 * it.tau + 1) && guard.free(here, 2 * it.tau + 2)) push(it.v, it.tau + 1);
    // Move along an edge.
    graph.forEachEdge(it.v, [&](int u, int steps, int edge) {
      const std::size_t arrive = it.tau + static_cast<std::size_t>(steps);
      if (arrive > horizon || parent.count(nodeKey(u, arrive))) return;
      if (!graph.edgeValid(edge)) return;
      if (steps > 0 && !guard.motionFree(here, graph.config(u), steps, it.tau, motionKey(it.v, u))) return;
      push(u, arrive);
    });
  }
  if (!found) return fail();
  if (end) *end = SearchEnd::Found;

  std::vector<std::pair<int, std::size_t>> nodes;
  for (std::uint64_t k = *found;; k = parent.at(k)) {
    nodes.emplace_back(static_cast<int>(k >> 32), static_cast<std::size_t>(k & 0xffffffffu));
    if (k == root) break;
  }
  std::reverse(nodes.begin(), nodes.end());
  Path path(dim);
  path.push(graph.config(nodes.front().first));
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const double* a = graph.config(nodes[i - 1].first);
    const double* b = graph.config(nodes[i].first);
    const std::size_t steps = nodes[i].second - nodes[i - 1].second;
    for (std::size_t k = 1; k <= steps; ++k) {
      if (k == steps) {
        path.push(b);
      } else {
        model.interpolate(a, b, static_cast<double>(k) / static_cast<double>(steps), q.data());
        path.push(q.data());
      }
    }
  }
  return path;
}

bool clearOfMoving(const RobotModel& model, const Path& local, const std::vector<MovingObstacle>& obstacles) {
  if (local.empty() || obstacles.empty()) return true;
  const std::size_t last_step = local.size() - 1;
  MotionGuard guard(model, obstacles, 2 * last_step + 2);
  if (!guard.free(local.at(0), 0)) return false;
  for (std::size_t t = 0; t < last_step; ++t)
    if (!guard.motionFree(local.at(t), local.at(t + 1), 1, t)) return false;
  return true;
}

std::vector<MovingObstacle> nearbyRobots(const SolverContext& ctx, std::size_t span) {
  std::vector<MovingObstacle> out;
  if (ctx.ignore_others) return out;
  const Subproblem& sub = ctx.sub;
  std::vector<geo::Body> bodies;
  for (std::size_t r = 0; r < ctx.models.size(); ++r) {
    if (std::find(sub.robots.begin(), sub.robots.end(), static_cast<int>(r)) != sub.robots.end()) continue;
    const Path& p = ctx.paths[r];
    if (p.empty()) continue;
    const RobotModel& m = *ctx.models[r];
    geo::Aabb swept;
    const std::size_t last = std::min(p.size() - 1, sub.t_start + span);
    const std::size_t first = std::min(sub.t_start, p.size() - 1);
    for (std::size_t t = first; t <= last; ++t) {
      geo::Vec2 c = m.boundingCenter(p.at(t));
      swept.expand({c, c});
    }
    if (swept.inflated(m.boundingRadius()).overlaps(sub.workspace_region))
      out.push_back({&m, &p, sub.t_start, static_cast<int>(r)});
  }
  return out;
}

std::vector<std::size_t> nextPriorityOrder(const std::vector<std::vector<std::size_t>>& tried, std::size_t failed,
                                           std::mt19937_64& rng) {
  if (tried.empty()) return {};
  auto untried = [&](const std::vector<std::size_t>& o) { return std::find(tried.begin(), tried.end(), o) == tried.end(); };
  // The last order with the robot that failed moved to its front.
  std::vector<std::size_t> next = tried.back();
  const auto at = std::find(next.begin(), next.end(), failed);
  if (at != next.end()) std::rotate(next.begin(), at, at + 1);
  if (untried(next)) return next;
  // Else one not tried yet, drawn at random: by shuffling where there
  // are many orders (6 robots have 720), among all that are left where
  // there are few or shuffling keeps meeting tried ones. Past 8 robots
  // (40,320 orders) that is never needed: max_orders is at most 10,000.
  const std::size_t n = next.size();
  if (n > 5) {
    for (int k = 0; k < 64; ++k) {
      std::shuffle(next.begin(), next.end(), rng);
      if (untried(next)) return next;
    }
    if (n > 8) return {};
  }
  std::vector<std::vector<std::size_t>> left;
  std::sort(next.begin(), next.end());
  do {
    if (untried(next)) left.push_back(next);
  } while (std::next_permutation(next.begin(), next.end()));
  if (left.empty()) return {};
  return left[std::uniform_int_distribution<std::size_t>(0, left.size() - 1)(rng)];
}

SolverOutcome DecoupledSolver::solve(SolverContext& ctx) {
  const Subproblem& sub = ctx.sub;
  const std::size_t n = sub.robots.size();
  const std::size_t window = sub.t_end - sub.t_start;  // steps in the replaced span
  // Roadmaps are built when a robot first needs one (see individualPath):
  // build this subproblem's before the search's budget starts, so that
  // building one does not take the search's time.
  for (int robot : sub.robots) ctx.roadmaps.forRobot(robot);
  const Deadline deadline = ctx.deadline.capped(settings_.time_budget_s * ctx.budget_scale);
  // Past ARC's last expansion level the hierarchy raises budget_scale
  // to retry the same subproblem: every limit grows with it, or the
  // retries repeat the same failed searches (a 4-robot corridor swap that
  // needs a fifth priority order never got it).
  const double scale = std::max(1.0, ctx.budget_scale);
  // The horizon grows with it too, up to the long horizon (not beyond:
  // each instant of it is tabulated for every robot around).
  const double w = static_cast<double>(window);
  const double base_horizon = settings_.horizon_windows * w + static_cast<double>(settings_.horizon_steps);
  const double long_horizon = DecoupledSettings::kLongHorizonWindows * w +
                              static_cast<double>(DecoupledSettings::kLongHorizonSteps);
  const std::size_t horizon =
      static_cast<std::size_t>(std::max(base_horizon, std::min(base_horizon * scale, long_horizon)));
  std::size_t max_expansions = static_cast<std::size_t>(std::min(1e9, static_cast<double>(settings_.max_expansions) * scale));
  const int max_orders = static_cast<int>(std::min(1e4, settings_.max_orders * scale));
  if (settings_.expansions_per_horizon_step > 0)
    max_expansions = std::min(max_expansions, static_cast<std::size_t>(static_cast<double>(
                                                  settings_.expansions_per_horizon_step * horizon) * ctx.budget_scale));
  std::vector<MovingObstacle> others;
  if (settings_.avoid_others) others = nearbyRobots(ctx, horizon);

  // The robots as listed first; after a failure, the next order comes
  // from nextPriorityOrder.
  std::vector<std::vector<std::size_t>> tried_orders;
  std::vector<std::size_t> ord(n);
  std::iota(ord.begin(), ord.end(), 0);
  std::mt19937_64 rng(splitSeed(ctx.seed, 0xdec0));

  // A robot planned first meets only the robots outside the group. If it
  // runs out of ways then (not out of expansions), it would find none in
  // any order, behind more robots and holding its goal no sooner: the
  // attempt ends there instead of trying the other orders.
  // The last failure (also for the trace): robot, its place in the
  // order, how its search ended.
  int last_robot = -1;
  std::size_t last_place = 0;
  SearchEnd last_end = SearchEnd::Found;
  auto hopeless = [&] { return last_end == SearchEnd::NoWay && last_place == 0; };
  while (static_cast<int>(tried_orders.size()) < max_orders && !ord.empty()) {
    if (deadline.expired() || hopeless()) break;
    tried_orders.push_back(ord);
    std::vector<Path> local(n);
    std::vector<MovingObstacle> obstacles = others;
    std::size_t hold = window;
    bool ok = true;
    for (std::size_t i : ord) {
      const int robot = sub.robots[i];
      QueryGraph graph(ctx.roadmaps.forRobot(robot), *ctx.models[static_cast<std::size_t>(robot)], &sub.region[i]);
      int s = graph.addVertex(sub.starts[i].data(), settings_.connect_neighbors);
      int g = graph.addVertex(sub.goals[i].data(), settings_.connect_neighbors);
      SearchEnd end = SearchEnd::Found;
      auto p = spaceTimeSearch(graph, s, g, obstacles, horizon, hold, deadline, max_expansions,
                               settings_.graph_heuristic, &end);
      if (!p) {
        last_robot = robot;
        last_place = obstacles.size() - others.size();
        last_end = end;
        ok = false;
        break;
      }
      local[i] = std::move(*p);
      hold = std::max(hold, local[i].size() - 1);
      obstacles.push_back({ctx.models[static_cast<std::size_t>(robot)], &local[i], 0, robot});
    }
    if (!ok) {
      ord = nextPriorityOrder(tried_orders, ord[last_place], rng);  // the robot that failed
      continue;
    }
    LocalSolution sol;
    sol.paths = std::move(local);
    std::size_t len = window + 1;
    for (const auto& p : sol.paths) len = std::max(len, p.size());
    for (auto& p : sol.paths)
      while (p.size() < len) p.push(p.back());
    return {std::move(sol), name(), -1};
  }
  SolverOutcome failed{std::nullopt, name(), -1};
  if (hopeless())
    failed.detail = "robot " + std::to_string(last_robot) + " has no way past the robots outside the group, in any order";
  else if (last_robot >= 0)
    failed.detail = std::to_string(tried_orders.size()) +
                    (tried_orders.size() == 1 ? " priority order" : " priority orders") +
                    " failed; in the last, robot " +
                    std::to_string(last_robot) + " (" + std::to_string(last_place + 1) + " of " +
                    std::to_string(n) + "): " + searchEndName(last_end);
  return failed;
}

SolverOutcome CoupledSubproblemSolver::solve(SolverContext& ctx) {
  const Subproblem& sub = ctx.sub;
  CoupledQuery q;
  for (int r : sub.robots) q.robots.push_back(ctx.models[static_cast<std::size_t>(r)]);
  q.starts = sub.starts;
  q.goals = sub.goals;
  q.region = sub.region;
  CoupledSettings cs;
  cs.time_limit_s = settings_.time_budget_s * ctx.budget_scale;
  cs.within = ctx.deadline;
  cs.polish = true;
  if (ctx.deadline.expired()) return {std::nullopt, name(), -1};
  auto sol = solveCoupled(ctx.world, q, cs, ctx.seed);
  if (!sol) return {std::nullopt, name(), -1};
  const std::size_t len = std::max(sol->length(), sub.t_end - sub.t_start + 1);
  for (auto& p : sol->paths)
    while (p.size() < len) p.push(p.back());
  return {std::move(sol), name(), -1};
}

}  // namespace earc
