// ARC's composite answers time-stamped robot by robot before the splice
// (restampLocalSolution, declared in arc.hpp).
#include <algorithm>
#include <numeric>
#include <queue>

#include "earc/planning/arc.hpp"
#include "earc/planning/compact.hpp"
#include "earc/planning/conflict.hpp"
#include "compact_states.hpp"

namespace earc {

namespace {

// Another robot's timed path seen from the window: its state at local
// instant k is its path's at instant 2 * offset + k; `horizon` is the last
// local instant at which it matters.
struct TimedBody {
  const RobotModel* model = nullptr;
  const Path* path = nullptr;
  std::size_t offset = 0;
  std::size_t horizon = 0;
  geo::Aabb reach;
};

// Above this many (route position, step) pairs a robot's timing is not
// searched: the answer keeps its lockstep stamping.
constexpr std::size_t kMaxTimingStates = std::size_t{1} << 22;

// The earliest timing of one robot's route among timed bodies. Not
// thread-safe.
class RouteTimer {
 public:
  explicit RouteTimer(const Deadline& deadline) : poll_(deadline, kWorkPerClockRead) {}
  bool expired() const { return poll_.seenExpired(); }

  // `route` time-stamped to arrive by step `bound`, waiting where it must:
  // touching none of `others` at any step or midpoint, and staying at its
  // last state from its arrival on. Nothing when no such timing exists.
  std::optional<Path> earliest(const RobotModel& model, const Path& route, std::size_t bound,
                               const std::vector<const TimedBody*>& others);

 private:
  bool freeAt(const RobotModel& model, const double* q, std::size_t k) {
    if (poll_.expired(near_.size() + 1)) return false;
    against_.set(model, q);
    for (std::size_t o = 0; o < near_.size(); ++o)
      if (against_.check(*near_[o]->model, states_.at(o, k)) == RobotAgainst::Result::Touch) return false;
    return true;
  }

  DeadlinePoll poll_;
  RobotAgainst against_;
  std::vector<const TimedBody*> near_;
  InstantStates states_;  // near_'s, in their order
  std::vector<unsigned char> how_;
};

std::optional<Path> RouteTimer::earliest(const RobotModel& model, const Path& route, std::size_t bound,
                                         const std::vector<const TimedBody*>& others) {
  const std::size_t m = route.size() - 1;  // route index of the end
  if (bound < m) return std::nullopt;
  const geo::Aabb mine = pathReach(model, route);
  near_.clear();
  std::vector<TimedSource> sources;
  for (const TimedBody* o : others)
    if (o->reach.overlaps(mine)) {
      near_.push_back(o);
      sources.push_back({o->model, o->path, o->offset, o->horizon});
    }
  states_.assign(std::move(sources), 2 * bound + 3);
  // The last instant at which some other robot touches it standing at its
  // end: it may arrive only after that, to stay there.
  std::size_t horizon = 0;
  for (const TimedBody* o : near_) horizon = std::max(horizon, o->horizon);
  long long last_block = -1;
  for (std::size_t k = horizon + 1; k-- > 1;) {
    if (!freeAt(model, route.back(), k)) {
      last_block = static_cast<long long>(k);
      break;
    }
  }
  if (expired()) return std::nullopt;
  const std::size_t slack = bound - m;  // waits it can afford
  if ((m + 1) * (slack + 1) > kMaxTimingStates) return std::nullopt;
  // Best first over (waits so far w, route position i), the robot at step
  // i + w: fewest waits first, so the first arrival found is the earliest,
  // and among equally many the furthest on. how_[i * (slack + 1) + w]: 1
  // entered moving on, 2 waiting. Step 0 is the answer's own start.
  how_.assign((m + 1) * (slack + 1), 0);
  struct Open {
    std::size_t w, back;  // waits, m - i
    unsigned char by;
    bool operator>(const Open& o) const { return w != o.w ? w > o.w : back > o.back; }
  };
  std::priority_queue<Open, std::vector<Open>, std::greater<>> open;
  open.push({0, m, 1});
  std::vector<double> mid(static_cast<std::size_t>(model.dim()));
  std::size_t at_i = 0, at_w = 0;
  bool found = false;
  while (!open.empty() && !found) {
    const Open e = open.top();
    open.pop();
    const std::size_t i = m - e.back, w = e.w, t = i + w;
    unsigned char& seen = how_[i * (slack + 1) + w];
    if (seen) continue;
    if (t > 0) {
      const double* from = e.by == 1 ? route.at(i - 1) : route.at(i);
      model.interpolate(from, route.at(i), 0.5, mid.data());
      if (!freeAt(model, mid.data(), 2 * t - 1) || !freeAt(model, route.at(i), 2 * t)) {
        if (expired()) return std::nullopt;
        continue;
      }
    }
    seen = e.by;
    if (i == m && 2 * static_cast<long long>(t) > last_block) {
      found = true;
      at_i = i;
      at_w = w;
      break;
    }
    if (w < slack) open.push({w + 1, m - i, 2});
    if (i < m) open.push({w, m - i - 1, 1});
  }
  if (!found) return std::nullopt;
  std::vector<std::size_t> at;
  for (std::size_t i = at_i, w = at_w;;) {
    at.push_back(i);
    if (i == 0 && w == 0) break;
    if (how_[i * (slack + 1) + w] == 1) {
      --i;
    } else {
      --w;
    }
  }
  Path timed(model.dim());
  timed.reserve(at.size());
  for (std::size_t k = at.size(); k-- > 0;) timed.push(route.at(at[k]));
  return timed;
}

// The path without the states that differ from the one before only by
// rounding (interpolating between equal states), ending where it ends.
Path routeWithoutRounding(const RobotModel& model, const Path& path) {
  constexpr double kRounding = 1e-9;
  Path route(model.dim());
  route.push(path.at(0));
  for (std::size_t t = 1; t < path.size(); ++t)
    if (model.distance(route.back(), path.at(t)) > kRounding) route.push(path.at(t));
  std::copy(path.back(), path.back() + model.dim(), route.mutableAt(route.size() - 1));
  return route;
}

// The group's robots stamped in `order`; false when one finds no timing.
bool stampInOrder(RouteTimer& timer, const std::vector<const RobotModel*>& group, const std::vector<Path>& routes,
                  const std::vector<std::size_t>& bounds, const std::vector<std::size_t>& order,
                  const std::vector<TimedBody>& outside, std::vector<Path>& out, std::size_t& failed) {
  std::vector<TimedBody> stamped(group.size());
  std::vector<const TimedBody*> others;
  for (const TimedBody& o : outside) others.push_back(&o);
  for (std::size_t i : order) {
    auto p = timer.earliest(*group[i], routes[i], bounds[i], others);
    if (!p) {
      failed = i;
      return false;
    }
    out[i] = std::move(*p);
    stamped[i] = {group[i], &out[i], 0, 2 * (out[i].size() - 1), pathReach(*group[i], out[i])};
    others.push_back(&stamped[i]);
  }
  return true;
}

}  // namespace

RestampReport restampLocalSolution(const Subproblem& sub, LocalSolution& local,
                                   const std::vector<const RobotModel*>& models, const std::vector<Path>& paths,
                                   const CollisionWorld& world, const Deadline& deadline) {
  // A composite answer moves its robots in lockstep, each held back by the
  // slowest robot of every composite motion. Here each robot keeps its
  // route and goes at full speed where the world allows, in turn: the
  // first ignoring the robots after it, each next at its earliest timing
  // behind those before it. Robots outside the group are avoided too when
  // that can be done (the lockstep answer ignores them; ARC meets them as
  // later conflicts otherwise). No robot arrives later than in lockstep;
  // when one cannot, in any of the orders tried, the answer stays as it is.
  RestampReport rep;
  const std::size_t n = sub.robots.size();
  const std::size_t len = local.length();
  if (n < 2 || len < 3) return rep;
  // Arms' answers are left as they are: on the paper's arm suites the
  // searches cost more time than the few steps they save.
  for (int r : sub.robots)
    if (!models[static_cast<std::size_t>(r)]->isMobile()) return rep;
  std::vector<const RobotModel*> group;
  std::vector<Path> routes;
  std::vector<std::size_t> bounds;  // each robot's lockstep arrival
  geo::Aabb group_box;
  for (std::size_t i = 0; i < n; ++i) {
    const RobotModel& m = *models[static_cast<std::size_t>(sub.robots[i])];
    Path arrived = local.paths[i];
    arrived.dropTrailingWaits();
    bounds.push_back(arrived.size() - 1);
    Path route = routeWithoutRounding(m, arrived);
    if (auto fast = routeAtFullSpeed(m, route, world, deadline)) route = std::move(*fast);
    group.push_back(&m);
    routes.push_back(std::move(route));
    group_box.expand(pathReach(m, local.paths[i]));
  }
  if (deadline.expired()) return rep;
  std::vector<TimedBody> outside;
  for (std::size_t r = 0; r < paths.size(); ++r) {
    if (std::binary_search(sub.robots.begin(), sub.robots.end(), static_cast<int>(r)) || paths[r].empty()) continue;
    const geo::Aabb reach = pathReach(*models[r], paths[r], sub.t_start, sub.t_start + len);
    if (paths[r].size() <= sub.t_start) {
      const geo::Aabb parked = pathReach(*models[r], paths[r], paths[r].size() - 1);
      if (!parked.overlaps(group_box)) continue;
      outside.push_back({models[r], &paths[r], sub.t_start, 0, parked});
      continue;
    }
    if (!reach.overlaps(group_box)) continue;
    outside.push_back({models[r], &paths[r], sub.t_start, 2 * (len - 1), reach});
  }
  // Longest lockstep arrival first; a robot that finds no timing goes
  // first in the next order, each order tried once.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return bounds[a] > bounds[b]; });
  RouteTimer timer(deadline);
  std::vector<Path> out(n, Path(0));
  bool done = false;
  for (int pass = 0; pass < 2 && !done; ++pass) {
    const std::vector<TimedBody> around = pass == 0 ? outside : std::vector<TimedBody>{};
    std::vector<std::vector<std::size_t>> tried;
    std::vector<std::size_t> ord = order;
    while (!done && tried.size() < n && !timer.expired()) {
      if (std::find(tried.begin(), tried.end(), ord) != tried.end()) break;
      tried.push_back(ord);
      std::size_t failed = 0;
      done = stampInOrder(timer, group, routes, bounds, ord, around, out, failed);
      if (done) break;
      const auto at = std::find(ord.begin(), ord.end(), failed);
      std::rotate(ord.begin(), at, at + 1);
    }
    if (done) rep.around_outside = pass == 0;
  }
  if (!done) return rep;
  std::size_t new_len = sub.t_end - sub.t_start + 1;
  for (std::size_t i = 0; i < n; ++i) {
    rep.steps_saved += static_cast<std::int64_t>(bounds[i]) - static_cast<std::int64_t>(out[i].size() - 1);
    new_len = std::max(new_len, out[i].size());
  }
  new_len = std::min(new_len, len);
  for (std::size_t i = 0; i < n; ++i) {
    while (out[i].size() < new_len) out[i].push(out[i].back());
    local.paths[i] = std::move(out[i]);
  }
  rep.restamped = true;
  return rep;
}

}  // namespace earc
