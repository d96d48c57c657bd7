// ARC's composite answers time-stamped robot by robot before the splice
// (restampLocalSolution, declared in arc.hpp).
#include <algorithm>
#include <numeric>

#include "earc/planning/arc.hpp"
#include "earc/planning/compact.hpp"
#include "earc/planning/conflict.hpp"

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
  // The others' states at local instant k, into states_ (one row each).
  void place(std::size_t k);
  bool freeAt(const RobotModel& model, const double* q) {
    if (poll_.expired(near_.size() + 1)) return false;
    against_.set(model, q);
    for (std::size_t o = 0; o < near_.size(); ++o)
      if (against_.check(*near_[o]->model, states_[o].data()) == RobotAgainst::Result::Touch) return false;
    return true;
  }

  DeadlinePoll poll_;
  RobotAgainst against_;
  std::vector<const TimedBody*> near_;
  std::vector<std::vector<double>> states_;
};

void RouteTimer::place(std::size_t k) {
  states_.resize(near_.size());
  for (std::size_t o = 0; o < near_.size(); ++o) {
    const TimedBody& b = *near_[o];
    states_[o].resize(static_cast<std::size_t>(b.model->dim()));
    stateAtInstant(*b.model, *b.path, 2 * b.offset + std::min(k, b.horizon), states_[o].data());
  }
}

std::optional<Path> RouteTimer::earliest(const RobotModel& model, const Path& route, std::size_t bound,
                                         const std::vector<const TimedBody*>& others) {
  const std::size_t m = route.size() - 1;  // route index of the end
  if (bound < m) return std::nullopt;
  const geo::Aabb mine = pathReach(model, route);
  near_.clear();
  for (const TimedBody* o : others)
    if (o->reach.overlaps(mine)) near_.push_back(o);
  // The last instant at which some other robot touches it standing at its
  // end: it may arrive only after that, to stay there.
  std::size_t horizon = 0;
  for (const TimedBody* o : near_) horizon = std::max(horizon, o->horizon);
  long long last_block = -1;
  for (std::size_t k = horizon + 1; k-- > 1;) {
    place(k);
    if (!freeAt(model, route.back())) {
      last_block = static_cast<long long>(k);
      break;
    }
  }
  if (expired()) return std::nullopt;
  const std::size_t slack = bound - m;  // waits it can afford
  if ((m + 1) * (bound + 1) > kMaxTimingStates) return std::nullopt;
  // Breadth-first by step: reach[i], route position i reachable at step t;
  // how[t][i] 1 when entered moving on, 2 waiting. Instant 0 is the
  // answer's own start, valid as it stands.
  std::vector<char> reach(m + 1, 0), next(m + 1, 0);
  std::vector<char> how((bound + 1) * (m + 1), 0);
  reach[0] = 1;
  std::vector<double> mid(static_cast<std::size_t>(model.dim()));
  std::vector<signed char> end_free(m + 1);
  std::size_t arrival = 0;
  bool found = m == 0 && last_block < 0;
  for (std::size_t t = 0; !found && t < bound; ++t) {
    std::fill(next.begin(), next.end(), 0);
    const std::size_t lo = t > slack ? t - slack : 0;  // fewer positions cannot arrive by the bound
    const std::size_t hi = std::min(t, m);
    // Midpoints first (instant 2t + 1), then the states at step t + 1.
    place(2 * t + 1);
    std::vector<char> move_ok(m + 1, 0), wait_ok(m + 1, 0);
    for (std::size_t i = lo; i <= hi; ++i) {
      if (!reach[i]) continue;
      if (i < m) {
        model.interpolate(route.at(i), route.at(i + 1), 0.5, mid.data());
        move_ok[i] = freeAt(model, mid.data());
      }
      wait_ok[i] = freeAt(model, route.at(i));
    }
    place(2 * t + 2);
    std::fill(end_free.begin(), end_free.end(), -1);
    auto endFree = [&](std::size_t j) {
      if (end_free[j] < 0) end_free[j] = freeAt(model, route.at(j)) ? 1 : 0;
      return end_free[j] == 1;
    };
    bool any = false;
    for (std::size_t i = lo; i <= hi; ++i) {
      if (!reach[i]) continue;
      if (move_ok[i] && endFree(i + 1)) {
        next[i + 1] = 1;
        how[(t + 1) * (m + 1) + i + 1] = 1;
        any = true;
      }
      if (wait_ok[i] && t + 1 - i <= slack && endFree(i)) {
        next[i] = 1;
        if (!how[(t + 1) * (m + 1) + i]) how[(t + 1) * (m + 1) + i] = 2;
        any = true;
      }
    }
    if (expired() || !any) return std::nullopt;
    reach.swap(next);
    if (reach[m] && 2 * static_cast<long long>(t + 1) > last_block) {
      found = true;
      arrival = t + 1;
    }
  }
  if (!found) return std::nullopt;
  std::vector<std::size_t> at(arrival + 1);
  at[arrival] = m;
  for (std::size_t t = arrival; t > 0; --t) at[t - 1] = how[t * (m + 1) + at[t]] == 1 ? at[t] - 1 : at[t];
  Path timed(model.dim());
  timed.reserve(arrival + 1);
  for (std::size_t i : at) timed.push(route.at(i));
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
