#include "earc/planning/composite.hpp"

#include <algorithm>

#include "earc/util/random.hpp"

namespace earc {

CompositeState stateAt(const std::vector<Path>& paths, std::size_t t) {
  CompositeState q;
  for (const auto& p : paths) q.emplace_back(p.at(t), p.at(t) + p.dim());
  return q;
}

int compositeSteps(const std::vector<const RobotModel*>& robots, const CompositeState& a, const CompositeState& b) {
  int n = 0;
  for (std::size_t r = 0; r < robots.size(); ++r) n = std::max(n, robots[r]->stepsBetween(a[r].data(), b[r].data()));
  return n;
}

namespace {
// Above this many robots, pairs are found by sweeping bounding discs along
// x instead of testing all n(n-1)/2 of them: the coupled method on a whole
// scenario of thousands of robots spent minutes here.
constexpr std::size_t kSweepAbove = 8;

struct Extent {
  double lo, hi;
  std::size_t robot;
};
}  // namespace

bool CompositeChecker::outOfTime() const {
  if (!deadline_) return false;
  if (expired_.load(std::memory_order_relaxed)) return true;
  if (!deadline_->expired()) return false;
  expired_.store(true, std::memory_order_relaxed);
  return true;
}

// The clock is read every kWorkPerClockRead units (a state being the robots'
// summed dim()), inside motions and states alike: one motion of thousands of
// robots, or one state of arms of thousands of links, takes long, and OMPL's
// planners and simplifier check thousands more after their own termination
// condition. A read per motion would cost small problems some percent.
bool CompositeChecker::outOfTimeAfter(std::size_t work) const {
  if (!deadline_) return false;
  if (expired_.load(std::memory_order_relaxed)) return true;
  countWork(work);
  // A work budget is checked every time (no clock read), so that it ends
  // at the same work whatever the thread's checks did before.
  if (deadline_->workSpent()) {
    expired_.store(true, std::memory_order_relaxed);
    return true;
  }
  thread_local std::size_t owed = 0;  // shared by every checker on the thread: only the pace of reads
  owed += work;
  if (owed < kWorkPerClockRead) return false;
  owed = 0;
  return outOfTime();
}

bool CompositeChecker::stateValid(const CompositeState& q) const {
  return !outOfTimeAfter(work_per_instant_) && checkState(q);
}

bool CompositeChecker::checkState(const CompositeState& q) const {
  const std::size_t n = robots_.size();
  // Each robot's bodies are placed once, for the obstacles and for every
  // robot near it. Per-thread scratch, as the checker is shared.
  thread_local std::vector<PlacedBodies> placed;
  if (placed.size() < n) placed.resize(n);
  for (std::size_t r = 0; r < n; ++r)
    if (!world_.stateValid(*robots_[r], q[r].data(), placed[r])) return false;
  auto touch = [&](std::size_t a, std::size_t b) {
    return boundingDiscsMeet(*robots_[a], q[a].data(), *robots_[b], q[b].data()) && bodiesTouch(placed[a], placed[b]);
  };
  if (n <= kSweepAbove) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (touch(i, j)) return false;
    return true;
  }
  std::vector<Extent> ext(n);
  for (std::size_t r = 0; r < n; ++r) {
    const geo::Vec2 c = robots_[r]->boundingCenter(q[r].data());
    const double rad = robots_[r]->boundingRadius();
    ext[r] = {c.x - rad, c.x + rad, r};
  }
  std::sort(ext.begin(), ext.end(), [](const Extent& a, const Extent& b) { return a.lo < b.lo; });
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n && ext[j].lo <= ext[i].hi; ++j) {
      if (touch(ext[i].robot, ext[j].robot)) return false;
    }
  return true;
}

bool CompositeChecker::instantValid(const CompositeState& a, const CompositeState& b, double s,
                                    CompositeState& scratch) const {
  scratch.resize(robots_.size());
  for (std::size_t r = 0; r < robots_.size(); ++r) {
    scratch[r].resize(a[r].size());
    robots_[r]->interpolate(a[r].data(), b[r].data(), s, scratch[r].data());
  }
  return checkState(scratch);
}

bool CompositeChecker::motionValid(const CompositeState& a, const CompositeState& b, KnownValid known) const {
  return lastValidFraction(a, b, known, /*earliest=*/false) >= 1.0;
}

double CompositeChecker::lastValidFraction(const CompositeState& a, const CompositeState& b, KnownValid known) const {
  return lastValidFraction(a, b, known, /*earliest=*/true);
}

double CompositeChecker::lastValidFraction(const CompositeState& a, const CompositeState& b, KnownValid known,
                                           bool earliest) const {
  int n = compositeSteps(robots_, a, b);
  CompositeState scratch;
  if (n == 0) return known.start || known.end || stateValid(a) ? 1.0 : 0.0;
  // Coarse to fine: most invalid motions are caught by the first few
  // samples, so test the instants in bisection order, then, when the
  // earliest invalid one is asked for, every instant before the first
  // found. (motionValid's yes or no stops at the first: the shortcuts of
  // a robot's own path across den520d spent more than half their checks
  // looking for where a motion already known to fail first failed.)
  const int instants = 2 * n;
  int first_bad = instants + 1;
  std::vector<char> tested(static_cast<std::size_t>(instants + 1), 0);
  tested.front() = known.start;
  tested.back() = known.end;
  for (int stride = instants; stride >= 1; stride /= 2) {
    for (int k = 0; k <= instants; k += stride) {
      if (tested[static_cast<std::size_t>(k)]) continue;
      tested[static_cast<std::size_t>(k)] = 1;
      if (k >= first_bad) continue;
      if (outOfTimeAfter(work_per_instant_)) return 0.0;
      if (!instantValid(a, b, static_cast<double>(k) / instants, scratch)) {
        first_bad = k;
        if (!earliest) return 0.0;
      }
    }
    if (stride == 1) break;  // every instant below first_bad has now been tested
  }
  if (first_bad > instants) return 1.0;
  return std::max(0.0, static_cast<double>(first_bad - 1) / instants);
}

const PlacedBodies& BodiesAlongPaths::at(std::size_t w, std::size_t t, int k) {
  const std::size_t i = 2 * t + static_cast<std::size_t>(k);
  auto& placed = placed_[w];
  if (placed.size() <= i) placed.resize(i + 1);
  if (placed[i].empty()) {
    const RobotModel& m = *robots_[w];
    q_.resize(static_cast<std::size_t>(m.dim()));
    m.interpolate(paths_[w].at(t), paths_[w].at(t + 1), static_cast<double>(k) / 2, q_.data());
    placed[i].place(m, q_.data());
  }
  return placed[i];
}

void BodiesAlongPaths::forget(std::size_t w, std::size_t t) {
  auto& placed = placed_[w];
  for (std::size_t i = 2 * t; i < placed.size(); ++i) placed[i].bodies.clear();  // placed again when asked
}

bool CompositeChecker::robotMotionValid(std::size_t r, const std::vector<const double*>& a,
                                        const std::vector<const double*>& b, KnownValid known) const {
  return robotMotionValid(r, a, b, known, nullptr, 0);
}

bool CompositeChecker::robotStepValid(std::size_t r, const std::vector<const double*>& a,
                                      const std::vector<const double*>& b, KnownValid known, BodiesAlongPaths& along,
                                      std::size_t t) const {
  return robotMotionValid(r, a, b, known, &along, t);
}

bool CompositeChecker::robotMotionValid(std::size_t r, const std::vector<const double*>& a,
                                        const std::vector<const double*>& b, KnownValid known,
                                        BodiesAlongPaths* along, std::size_t t) const {
  const std::size_t n = robots_.size();
  int steps = 0;
  for (std::size_t w = 0; w < n; ++w) steps = std::max(steps, robots_[w]->stepsBetween(a[w], b[w]));
  // stepsBetween allows up to INT_MAX steps: twice that needs 64 bits.
  const long long instants = 2LL * steps;
  if (instants != 2) along = nullptr;  // entries hold the instants of one resolution step
  thread_local std::vector<std::vector<double>> q;
  thread_local std::vector<const double*> at;
  thread_local PlacedBodies mine, theirs;
  q.resize(n);
  at.resize(n);
  for (long long k = known.start ? 1 : 0; k <= instants - (known.end && instants > 0 ? 1 : 0); ++k) {
    if (outOfTimeAfter(work_per_instant_)) return false;
    for (std::size_t w = 0; w < n; ++w) {
      if (instants == 0) {  // as motionValid: the state itself, not interpolated
        at[w] = a[w];
        continue;
      }
      q[w].resize(static_cast<std::size_t>(robots_[w]->dim()));
      robots_[w]->interpolate(a[w], b[w], static_cast<double>(k) / instants, q[w].data());
      at[w] = q[w].data();
    }
    bool placed = !known.world;
    if (placed && !world_.stateValid(*robots_[r], at[r], mine)) return false;
    for (std::size_t w = 0; w < n; ++w) {
      if (w == r || !boundingDiscsMeet(*robots_[r], at[r], *robots_[w], at[w])) continue;
      if (!placed) {
        mine.place(*robots_[r], at[r]);
        placed = true;
      }
      if (along) {
        if (bodiesTouch(mine, along->at(w, t, static_cast<int>(k)))) return false;  // k <= 2 here
        continue;
      }
      theirs.place(*robots_[w], at[w]);
      if (bodiesTouch(mine, theirs)) return false;
    }
  }
  return true;
}

void shortcutComposite(const CompositeChecker& checker, std::vector<CompositeState>& waypoints, int iterations,
                       std::mt19937_64& rng, const Deadline& deadline) {
  for (int it = 0; it < iterations && waypoints.size() > 2 && !deadline.expired(); ++it) {
    std::size_t n = waypoints.size();
    std::size_t i = uniformIndex(rng, n - 2);
    std::size_t j = i + 2 + uniformIndex(rng, n - i - 2);
    if (checker.motionValid(waypoints[i], waypoints[j], {.start = true, .end = true}))
      waypoints.erase(waypoints.begin() + static_cast<std::ptrdiff_t>(i + 1), waypoints.begin() + static_cast<std::ptrdiff_t>(j));
  }
}

// Tried at waypoints geometrically nearer the end (last, 3/4, 9/16, ... of
// the way), the first valid motion kept: a few checks each. For a path
// joined to a start and a goal it was not made for, where the detours are.
std::size_t shortcutEnds(const CompositeChecker& checker, std::vector<CompositeState>& waypoints) {
  const std::size_t before = waypoints.size();
  auto erase = [&](std::size_t from, std::size_t to) {  // waypoints [from, to)
    waypoints.erase(waypoints.begin() + static_cast<std::ptrdiff_t>(from),
                    waypoints.begin() + static_cast<std::ptrdiff_t>(to));
  };
  // Offsets from the end shrink by a quarter (rounded down) until 1: two
  // neighbouring waypoints, already joined.
  for (std::size_t k = waypoints.size() - 1; k >= 2 && waypoints.size() > 2; k = k * 3 / 4)
    if (checker.motionValid(waypoints.front(), waypoints[k], {.start = true, .end = true})) {
      erase(1, k);
      break;
    }
  const std::size_t last = waypoints.size() - 1;
  for (std::size_t d = last; d >= 2 && waypoints.size() > 2; d = d * 3 / 4)
    if (checker.motionValid(waypoints[last - d], waypoints.back(), {.start = true, .end = true})) {
      erase(last - d + 1, last);
      break;
    }
  return before - waypoints.size();
}

// Composite shortcutting moves all robots together, so one robot's detour
// holds up the others; this lets each arrive when it can. Only the changed
// robot's part of each motion is checked.
void retimeShortcut(const CompositeChecker& checker, std::vector<Path>& paths, int iterations, std::mt19937_64& rng,
                    const Deadline& deadline) {
  const auto& robots = checker.robots();
  const std::size_t n = paths.size();
  if (n == 0) return;
  std::vector<double> q;
  std::vector<const double*> from(n), to(n);
  BodiesAlongPaths along(robots, paths);
  for (int it = 0; it < iterations && !deadline.expired(); ++it) {
    const std::size_t r = uniformIndex(rng, n);
    const std::size_t len = paths[r].size();
    if (len < 3) continue;
    const std::size_t i = uniformIndex(rng, len - 2);
    const std::size_t j = i + 2 + uniformIndex(rng, len - i - 2);  // at most len - 1
    const RobotModel& m = *robots[r];
    const auto d = static_cast<std::size_t>(m.stepsBetween(paths[r].at(i), paths[r].at(j)));
    if (d >= j - i) continue;
    // i, the straight motion to j in d steps, then j onwards.
    Path shorter = paths[r].slice(0, i + 1);
    q.resize(static_cast<std::size_t>(m.dim()));
    for (std::size_t k = 1; k < d; ++k) {
      m.interpolate(paths[r].at(i), paths[r].at(j), static_cast<double>(k) / static_cast<double>(d), q.data());
      shorter.push(q.data());
    }
    shorter.append(paths[r], j);
    std::swap(paths[r], shorter);
    // From i on, robot r meets the others at different times: check every
    // step to the end of the longest path.
    std::size_t last = 0;
    for (const auto& p : paths) last = std::max(last, p.size() - 1);
    // Only robot r's part changed: the others' part was valid and stays so.
    // Against the world, only its new straight motion i -> i + d is new;
    // after it, it makes the motions it made before, later. Step i is as it
    // was, and each later step was checked as the end of the one before.
    bool valid = true;
    for (std::size_t t = i; t < last && valid; ++t) {
      for (std::size_t w = 0; w < n; ++w) {
        from[w] = paths[w].at(t);
        to[w] = paths[w].at(t + 1);
      }
      valid = checker.robotStepValid(r, from, to, {.start = true, .world = t >= i + d}, along, t);
    }
    if (valid)
      along.forget(r, i);
    else
      std::swap(paths[r], shorter);
  }
}

}  // namespace earc
