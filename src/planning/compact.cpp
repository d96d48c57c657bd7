#include "earc/planning/compact.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <random>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/util/random.hpp"
#include "compact_states.hpp"

namespace earc {

namespace {

// Instants whose states are kept: a search goes forward in time and seldom
// backs up far.
constexpr std::size_t kSlots = 2048;
// Steps a chunk spans: each robot's disc is boxed per chunk, and a state is
// tested only against the robots whose box then meets the searched robot's
// reach then.
constexpr std::size_t kBoxSteps = 16;
constexpr std::size_t kBoxInstants = 2 * kBoxSteps;

class Compactor {
 public:
  Compactor(const std::vector<const RobotModel*>& models, std::vector<Path>& paths, const CollisionWorld* world,
            const Deadline& deadline, std::size_t states_per_position)
      : models_(models), paths_(paths), world_(world), deadline_(deadline), poll_(deadline, kWorkPerClockRead),
        states_per_position_(states_per_position) {
    std::vector<TimedSource> sources;
    std::size_t longest = 0;
    for (std::size_t o = 0; o < paths_.size(); ++o) {
      sources.push_back({models_[o], &paths_[o]});
      longest = std::max(longest, paths_[o].size());
    }
    // No more slots than the plan has instants.
    states_.assign(std::move(sources), std::min(kSlots, 2 * longest + 1));
    for (std::size_t o = 0; o < paths_.size(); ++o) reach_.push_back(reach(o));
    chunks_.resize(paths_.size());
    for (std::size_t o = 0; o < paths_.size(); ++o) boxChunks(o);
    changed_at_.assign(paths_.size(), 0);
    failed_at_.assign(paths_.size(), static_cast<std::size_t>(-1));
  }

  bool expired() { return poll_.expired(0); }
  std::size_t states() const { return tried_; }

  // Robot r's route shortcut by straight motions, `tries` drawn at random,
  // each kept when a timing of it arrives earlier; the steps saved.
  std::int64_t shortcut(std::size_t r, int tries, std::uint64_t seed);

  // Retimes robot r; the steps its arrival moved earlier (0: kept as it was).
  std::int64_t retime(std::size_t r) {
    const std::int64_t saved = search(r);
    if (saved == 0 && !poll_.seenExpired()) {
      failed_at_[r] = changes_;
    }
    return saved;
  }

 private:
  // The box that robot o's bounding disc stays in along its path (a
  // midpoint's centre lies between its steps' centres).
  geo::Aabb reach(std::size_t o) const { return pathReach(*models_[o], paths_[o]); }
  // chunks_[o]: robot o's disc boxed over steps [c, c + 1] * kBoxSteps of
  // its path, the last standing for every later chunk.
  void boxChunks(std::size_t o) {
    chunks_[o].clear();
    const Path& p = paths_[o];
    if (p.empty()) return;
    const std::size_t last = p.size() - 1;
    for (std::size_t c = 0; c * kBoxSteps < last; ++c)
      chunks_[o].push_back(pathReach(*models_[o], p, c * kBoxSteps, std::min(last, (c + 1) * kBoxSteps) + 1));
    chunks_[o].push_back(pathReach(*models_[o], p, last));
  }
  const geo::Aabb& chunkBox(std::size_t o, std::size_t c) const {
    return chunks_[o][std::min(c, chunks_[o].size() - 1)];
  }
  // The robots of near_ that may meet robot r during chunk c of `route`'s
  // timing with `slack` waits (window_ holds r's reach per chunk).
  const std::vector<std::size_t>& nearIn(std::size_t c);

  std::int64_t search(std::size_t r);
  void gatherNear(std::size_t r);  // near_ := the robots whose reach meets r's
  // The last instant at which a robot of near_ touches r standing at `goal`
  // (-1: none).
  long long lastBlock(std::size_t r, const double* goal);
  // Robot r's path replaced by `timed`; the steps its arrival moved earlier.
  std::int64_t keep(std::size_t r, Path timed);
  // The route timed to arrive before `arrival`, staying at its goal after
  // instant last_block: nothing when no such timing was found.
  std::optional<Path> timing(std::size_t r, const Path& route, long long last_block, std::size_t arrival);

  // Robot r at configuration q touches none of `robots` at instant k.
  bool free(std::size_t r, const double* q, std::size_t k, const std::vector<std::size_t>& robots) {
    if (poll_.expired(robots.size() + 1)) return false;
    against_.set(*models_[r], q);
    for (std::size_t o : robots)
      if (against_.check(*models_[o], states_.at(o, k)) == RobotAgainst::Result::Touch) return false;
    return true;
  }

  const std::vector<const RobotModel*>& models_;
  std::vector<Path>& paths_;
  const CollisionWorld* world_;
  Deadline deadline_;
  InstantStates states_;
  DeadlinePoll poll_;
  std::vector<geo::Aabb> reach_;  // per robot
  std::vector<std::vector<geo::Aabb>> chunks_;  // per robot, see boxChunks
  // Per chunk of the current timing search: the searched robot's reach
  // then, and the robots of near_ whose box meets it (made when first asked).
  std::vector<geo::Aabb> window_;
  std::vector<std::vector<std::size_t>> chunk_near_;
  std::vector<char> chunk_made_;
  std::vector<std::size_t> near_;  // the robots whose reach meets the retimed one's
  RobotAgainst against_;           // free()'s scratch
  // A robot's search that found nothing is not repeated until a robot
  // near it has changed: changes_ counts retimings kept; changed_at_ and
  // failed_at_ hold its value after a robot's last change and failure.
  std::size_t changes_ = 0;
  std::size_t tried_ = 0;
  std::vector<std::size_t> changed_at_, failed_at_;
  std::size_t states_per_position_;
};

void Compactor::gatherNear(std::size_t r) {
  near_.clear();
  for (std::size_t o = 0; o < paths_.size(); ++o)
    if (o != r && !paths_[o].empty() && reach_[o].overlaps(reach_[r])) near_.push_back(o);
}

std::int64_t Compactor::search(std::size_t r) {
  const Path& path = paths_[r];
  if (path.size() < 2) return 0;
  // Only robots that come near its route can touch it.
  gatherNear(r);
  if (failed_at_[r] != static_cast<std::size_t>(-1) &&
      std::none_of(near_.begin(), near_.end(), [&](std::size_t o) { return changed_at_[o] > failed_at_[r]; }))
    return 0;

  const RobotModel& model = *models_[r];
  const Path route = routeOf(path);
  const std::size_t arrival = path.size() - 1;
  std::optional<Path> faster;
  if (world_ != nullptr) {
    faster = routeAtFullSpeed(model, route, *world_, deadline_);
    if (!faster && deadline_.expired()) {
      poll_.expired(kWorkPerClockRead);  // so that the callers see it
      return 0;
    }
  }
  if (route.size() - 1 >= arrival && !faster) return 0;  // it moves on at every step, as fast as it can
  const long long last_block = lastBlock(r, route.back());
  if (poll_.seenExpired()) return 0;

  std::optional<Path> timed;
  if (faster) timed = timing(r, *faster, last_block, arrival);
  if (!timed && !poll_.seenExpired()) timed = timing(r, route, last_block, arrival);
  if (!timed) return 0;
  return keep(r, std::move(*timed));
}

std::int64_t Compactor::keep(std::size_t r, Path timed) {
  const auto saved = static_cast<std::int64_t>(paths_[r].size()) - static_cast<std::int64_t>(timed.size());
  paths_[r] = std::move(timed);
  changed_at_[r] = ++changes_;
  states_.forget(r);
  boxChunks(r);
  return saved;
}

long long Compactor::lastBlock(std::size_t r, const double* goal) {
  // The last instant at which another robot touches it standing at its
  // goal: it may arrive only after that, to stay there. Only robots whose
  // reach takes in the goal can.
  const RobotModel& model = *models_[r];
  const geo::Vec2 gc = model.boundingCenter(goal);
  const double gr = model.boundingRadius();
  const geo::Aabb at_goal{{gc.x - gr, gc.y - gr}, {gc.x + gr, gc.y + gr}};
  std::vector<std::size_t> near_goal;
  for (std::size_t o : near_)
    if (reach_[o].overlaps(at_goal)) near_goal.push_back(o);
  std::size_t horizon = 0;
  for (std::size_t o : near_goal) horizon = std::max(horizon, paths_[o].size() - 1);
  long long last_block = -1;
  std::vector<std::size_t> in_chunk;
  for (std::size_t c = (2 * horizon + 1) / kBoxInstants + 1; c-- > 0 && last_block < 0;) {
    in_chunk.clear();
    for (std::size_t o : near_goal)
      if (chunkBox(o, c).overlaps(at_goal)) in_chunk.push_back(o);
    if (in_chunk.empty()) continue;
    for (std::size_t k = std::min(2 * horizon + 1, c * kBoxInstants + kBoxInstants - 1) + 1; k-- > c * kBoxInstants;)
      if (!free(r, goal, k, in_chunk)) {
        last_block = static_cast<long long>(k);
        break;
      }
  }
  return last_block;
}

std::int64_t Compactor::shortcut(std::size_t r, int tries, std::uint64_t seed) {
  const Path& path = paths_[r];
  if (path.size() < 3 || world_ == nullptr) return 0;
  gatherNear(r);
  const RobotModel& model = *models_[r];
  const long long last_block = lastBlock(r, path.back());
  std::int64_t saved = 0;
  // Deterministic per robot, so that a plan does not depend on the others'
  // draws.
  std::mt19937_64 rng(splitSeed(seed, r));
  for (int k = 0; k < tries && !poll_.seenExpired(); ++k) {
    const Path route = routeOf(paths_[r]);
    const std::size_t last = route.size() - 1;
    if (last < 2) break;
    // Stretches drawn as refinement's shortcuts draw them.
    const auto [i0, i1] = drawStretch(rng, last);
    const std::size_t span = i1 - i0;
    const auto n = static_cast<std::size_t>(model.stepsBetween(route.at(i0), route.at(i1)));
    poll_.expired((n + 1) * static_cast<std::size_t>(model.dim()));
    if (n == 0 || n >= span || !world_->motionValid(model, route.at(i0), route.at(i1))) continue;
    Path cut(model.dim());
    for (std::size_t i = 0; i <= i0; ++i) cut.push(route.at(i));
    appendStraightMotion(model, route.at(i0), route.at(i1), cut);
    for (std::size_t i = i1 + 1; i <= last; ++i) cut.push(route.at(i));
    std::optional<Path> timed = timing(r, cut, last_block, paths_[r].size() - 1);
    if (timed) saved += keep(r, std::move(*timed));
  }
  return saved;
}

const std::vector<std::size_t>& Compactor::nearIn(std::size_t c) {
  c = std::min(c, window_.size() - 1);
  if (!chunk_made_[c]) {
    chunk_made_[c] = 1;
    for (std::size_t o : near_)
      if (chunkBox(o, c).overlaps(window_[c])) chunk_near_[c].push_back(o);
  }
  return chunk_near_[c];
}

std::optional<Path> Compactor::timing(std::size_t r, const Path& route, long long last_block, std::size_t arrival) {
  const RobotModel& model = *models_[r];
  const std::size_t last = route.size() - 1;  // route index of the goal
  const std::size_t earliest = std::max(last, static_cast<std::size_t>(last_block / 2 + 1));
  if (earliest >= arrival) return std::nullopt;
  // Depth-first over (route index i, step t), moving on before waiting,
  // among the pairs from which it could still arrive before `arrival`:
  // t - i waits so far, at most `slack`.
  const std::size_t slack = arrival - 1 - last;
  if (last + 1 > (std::size_t{1} << 30) / (slack + 1)) return std::nullopt;  // a table of 128 MiB or more
  std::vector<bool> seen((last + 1) * (slack + 1), false);
  countWork(seen.size() >> 12);  // the table's clearing, about a body per 4096 bits
  // Its reach per chunk: at step t it stands at a route position from
  // t - slack to t, and past the arrival it is not searched. Each chunk's
  // window is the union of the route's blocks of kBoxSteps states that
  // cover those positions (a sparse table of unions: two look-ups), a
  // box no smaller than the positions' own: with a long route and much
  // slack, boxing every position per chunk cost more than the search.
  const std::size_t blocks = last / kBoxSteps + 1;
  std::vector<std::vector<geo::Aabb>> unions(1);
  unions[0].reserve(blocks);
  for (std::size_t b = 0; b < blocks; ++b) unions[0].push_back(pathReach(model, route, b * kBoxSteps, (b + 1) * kBoxSteps));
  countWork(last + 1);
  for (std::size_t w = 1; (std::size_t{1} << w) <= blocks; ++w) {
    const std::vector<geo::Aabb>& below = unions[w - 1];
    std::vector<geo::Aabb> level(blocks + 1 - (std::size_t{1} << w));
    for (std::size_t b = 0; b < level.size(); ++b) {
      level[b] = below[b];
      level[b].expand(below[b + (std::size_t{1} << (w - 1))]);
    }
    unions.push_back(std::move(level));
  }
  auto blocksReach = [&](std::size_t b0, std::size_t b1) {  // blocks b0..b1, inclusive
    std::size_t w = 0;
    while ((std::size_t{2} << w) <= b1 - b0 + 1) ++w;
    geo::Aabb box = unions[w][b0];
    box.expand(unions[w][b1 + 1 - (std::size_t{1} << w)]);
    return box;
  };
  const std::size_t chunks = (2 * arrival) / kBoxInstants + 1;
  window_.assign(chunks, geo::Aabb{});
  chunk_near_.assign(chunks, {});
  chunk_made_.assign(chunks, 0);
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t hi = std::min(last, (c + 1) * kBoxSteps);
    const std::size_t lo = std::min(hi, c * kBoxSteps > slack ? c * kBoxSteps - slack : 0);
    window_[c] = blocksReach(lo / kBoxSteps, hi / kBoxSteps);
  }
  auto mark = [&](std::size_t i, std::size_t t) {
    const std::size_t at = i * (slack + 1) + (t - i);
    if (seen[at]) return false;
    seen[at] = true;
    return true;
  };
  struct Frame {
    std::size_t i, t;
    int next;  // 0: move on, 1: wait, 2: done
  };
  std::vector<Frame> stack{{0, 0, 0}};
  mark(0, 0);
  std::size_t visited = 1;
  std::vector<double> mid(static_cast<std::size_t>(model.dim()));
  bool found = false;
  while (!stack.empty()) {
    const Frame f = stack.back();
    if (f.i == last && 2 * static_cast<long long>(f.t) > last_block) {
      found = true;
      break;
    }
    if (f.next == 2) {
      stack.pop_back();
      continue;
    }
    stack.back().next = f.next + 1;
    const std::size_t ni = f.i + (f.next == 0 ? 1 : 0);
    const std::size_t nt = f.t + 1;
    if (ni > last || nt - ni > slack) continue;
    if (!mark(ni, nt)) continue;
    ++tried_;
    if (++visited > states_per_position_ * (last + 1) || poll_.seenExpired()) return std::nullopt;
    model.interpolate(route.at(f.i), route.at(ni), 0.5, mid.data());
    if (!free(r, mid.data(), 2 * f.t + 1, nearIn((2 * f.t + 1) / kBoxInstants)) ||
        !free(r, route.at(ni), 2 * nt, nearIn(2 * nt / kBoxInstants)))
      continue;
    stack.push_back({ni, nt, 0});
  }
  if (!found) return std::nullopt;
  Path timed(model.dim());
  timed.reserve(stack.size());
  for (const Frame& f : stack) timed.push(route.at(f.i));
  timed.dropTrailingWaits();
  return timed;
}

}  // namespace

// Every robot of the plan retimed.
CompactReport compactPlan(const std::vector<const RobotModel*>& models, std::vector<Path>& paths,
                          const CollisionWorld* world, const Deadline& deadline, int max_passes,
                          std::size_t states_per_position) {
  std::vector<std::size_t> all(paths.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  return compactRobots(models, paths, all, world, deadline, max_passes, states_per_position);
}

// Retimes `paths` (one per robot, each ending at its goal, trailing waits
// dropped) in place. Each pass takes the listed robots latest arrival first; a
// pass that saves nothing ends it, as does `max_passes`. A robot's search
// tries at most `states_per_position` (route position, step) pairs per
// position of its route: a search that finds nothing tries every pair in
// reach, and a lower cap loses much of the gain (docs/performance-log.md).
// With a world, a robot's route also goes at full speed where it went
// slower along a straight motion, the new steps checked against the world;
// without one, only waits are left out.
CompactReport compactRobots(const std::vector<const RobotModel*>& models, std::vector<Path>& paths,
                            const std::vector<std::size_t>& which, const CollisionWorld* world,
                            const Deadline& deadline, int max_passes, std::size_t states_per_position) {
  CompactReport rep;
  Compactor compactor(models, paths, world, deadline, states_per_position);
  for (int pass = 0; pass < max_passes; ++pass) {
    if (compactor.expired()) break;
    ++rep.passes;
    std::vector<std::size_t> order = which;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return paths[a].size() > paths[b].size(); });
    std::int64_t saved = 0;
    for (std::size_t r : order) {
      const std::int64_t s = compactor.retime(r);
      if (s > 0) {
        ++rep.robots_retimed;
        saved += s;
      }
      if (compactor.expired()) break;
    }
    rep.steps_saved += saved;
    if (saved == 0) break;
  }
  rep.interrupted = compactor.expired();
  rep.states = compactor.states();
  return rep;
}

// The robots furthest behind their straight-line arrival first, each route
// shortcut where the world and the others allow.
CompactReport shortcutRobots(const std::vector<const RobotModel*>& models, std::vector<Path>& paths,
                             const std::vector<std::size_t>& which, const CollisionWorld& world,
                             const Deadline& deadline, std::size_t robots, int tries, std::uint64_t seed,
                             std::size_t states_per_position) {
  CompactReport rep;
  Compactor compactor(models, paths, &world, deadline, states_per_position);
  std::vector<std::pair<std::int64_t, std::size_t>> behind;
  for (std::size_t r : which) {
    const Path& p = paths[r];
    if (p.size() < 3) continue;
    const std::int64_t straight = models[r]->stepsBetween(p.at(0), p.back());
    const std::int64_t delay = static_cast<std::int64_t>(p.size() - 1) - straight;
    // A robot nearly on time has little to gain: without obstacles most
    // robots are, and their shortcuts would cost more than they save.
    if (4 * delay >= straight) behind.push_back({delay, r});
  }
  std::stable_sort(behind.begin(), behind.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (behind.size() > robots) behind.resize(robots);
  for (const auto& [delay, r] : behind) {
    if (compactor.expired()) break;
    const std::int64_t s = compactor.shortcut(r, tries, seed);
    if (s > 0) {
      ++rep.robots_shortcut;
      rep.steps_saved += s;
    }
  }
  rep.interrupted = compactor.expired();
  rep.states = compactor.states();
  return rep;
}

Path routeOf(const Path& path) {
  const auto dim = static_cast<std::size_t>(path.dim());
  Path route(path.dim());
  if (path.empty()) return route;
  route.push(path.at(0));
  for (std::size_t t = 1; t < path.size(); ++t)
    if (!std::equal(path.at(t), path.at(t) + dim, route.back())) route.push(path.at(t));
  return route;
}

namespace {

// Whether state c - 1 of `route` lies on the straight motion from state a
// to state c, strictly between them (to rounding): extended state by
// state, this keeps every state of a run on the run's one motion.
bool onMotion(const RobotModel& model, const Path& route, std::size_t a, std::size_t c, std::vector<double>& q) {
  const double whole = model.distance(route.at(a), route.at(c));
  const double part = model.distance(route.at(a), route.at(c - 1));
  if (!(part > 0 && part < whole)) return false;
  model.interpolate(route.at(a), route.at(c), part / whole, q.data());
  const double off = model.distance(q.data(), route.at(c - 1));
  return off <= 1e-9 * std::max(1.0, whole);
}

}  // namespace

// A robot held back by a composite motion's slowest robot moves along one
// straight motion in more steps than the resolution needs; each such run is
// made again in the fewest steps, checked against the world at those steps.
std::optional<Path> routeAtFullSpeed(const RobotModel& model, const Path& route, const CollisionWorld& world,
                                     const Deadline& deadline) {
  if (route.size() < 3) return std::nullopt;
  const std::size_t last = route.size() - 1;
  const CompositeChecker checker(world, {&model}, deadline);
  std::vector<double> q(static_cast<std::size_t>(model.dim()));
  Path out(model.dim());
  out.push(route.at(0));
  bool shorter = false;
  for (std::size_t a = 0; a < last;) {
    std::size_t b = a + 1;
    while (b < last && onMotion(model, route, a, b + 1, q)) ++b;
    const auto n = static_cast<std::size_t>(model.stepsBetween(route.at(a), route.at(b)));
    const auto state = [&](std::size_t i) { return std::vector<double>(route.at(i), route.at(i) + model.dim()); };
    if (n < b - a && checker.motionValid({state(a)}, {state(b)}, {.start = true, .end = true})) {
      appendStraightMotion(model, route.at(a), route.at(b), out);
      shorter = true;
    } else {
      for (std::size_t k = a + 1; k <= b; ++k) out.push(route.at(k));
    }
    if (checker.outOfTime()) return std::nullopt;
    a = b;
  }
  if (!shorter) return std::nullopt;
  return out;
}

geo::Aabb pathReach(const RobotModel& model, const Path& path, std::size_t from, std::size_t to) {
  geo::Aabb box;
  const double rad = model.boundingRadius();
  for (std::size_t t = from; t < to && t < path.size(); ++t) {
    const geo::Vec2 c = model.boundingCenter(path.at(t));
    box.expand(geo::Aabb{{c.x - rad, c.y - rad}, {c.x + rad, c.y + rad}});
  }
  return box;
}

}  // namespace earc
