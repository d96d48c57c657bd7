#include "earc/planning/conflict.hpp"

#include <algorithm>

#include "earc/collision/collision_world.hpp"

namespace earc {

void stateAtInstant(const RobotModel& model, const Path& path, std::size_t k, double* out) {
  const std::size_t t = k / 2;
  const double* a = path.at(t);
  if (k % 2 == 0 || t + 1 >= path.size()) {
    std::copy(a, a + model.dim(), out);
    return;
  }
  model.interpolate(a, path.at(t + 1), 0.5, out);
}

geo::Aabb boundsOverInstants(const RobotModel& model, const Path& path, std::size_t k0, std::size_t k1,
                             std::vector<double>& q, std::vector<double>& lo, std::vector<double>& hi) {
  const auto dim = static_cast<std::size_t>(model.dim());
  q.resize(dim);
  lo.assign(dim, 0.0);
  hi.assign(dim, 0.0);
  for (std::size_t k = k0; k <= k1; ++k) {
    stateAtInstant(model, path, k, q.data());
    for (std::size_t i = 0; i < dim; ++i) {
      lo[i] = k == k0 ? q[i] : std::min(lo[i], q[i]);
      hi[i] = k == k0 ? q[i] : std::max(hi[i], q[i]);
    }
  }
  return model.boundsWithin(lo.data(), hi.data());
}

std::vector<const Path*> pathPointers(const std::vector<Path>& paths) {
  std::vector<const Path*> out;
  out.reserve(paths.size());
  for (const auto& p : paths) out.push_back(&p);
  return out;
}

ConflictDetector::ConflictDetector(std::vector<const RobotModel*> models) : models_(std::move(models)) {
  const std::size_t n = models_.size();
  boxes_.resize(n);
  q_.resize(n);
  for (std::size_t r = 0; r < n; ++r) {
    q_[r].resize(static_cast<std::size_t>(models_[r]->dim()));
  }
}

ConflictDetector::ConflictDetector(std::vector<const RobotModel*> models, const Deadline& deadline)
    : ConflictDetector(std::move(models)) {
  deadline_ = &deadline;
}

// Earliest conflict among `paths` (one per robot; nullptr = robot absent)
// at instants from step `from` through step `to` (inclusive; clamped to
// the longest path). When `focus` is given, only pairs with at least one
// focused robot count. Instants go in chunks of kChunk: each robot is
// bounded over a chunk at once (RobotModel::boundsWithin), and only the
// robots whose chunk bounds meet another's that counts are placed at
// each instant, where a sort-and-sweep over the bodies' bounds
// (insertion sort: the order barely changes between instants) keeps
// this near linear in the number of robots. Nothing either when
// the deadline expired before the end: ask interrupted().
std::optional<Conflict> ConflictDetector::first(const std::vector<const Path*>& paths, std::size_t from,
                                                std::size_t to, const std::vector<char>* focus) {
  const std::size_t n = models_.size();
  interrupted_ = false;
  std::size_t horizon = 0;
  for (const Path* p : paths)
    if (p && !p->empty()) horizon = std::max(horizon, p->size() - 1);
  to = std::min(to, horizon);
  if (from > to) return std::nullopt;
  std::vector<int> active;
  for (std::size_t r = 0; r < n; ++r)
    if (paths[r] && !paths[r]->empty()) active.push_back(static_cast<int>(r));
  std::size_t work = 0;  // per instant
  for (int r : active) work += static_cast<std::size_t>(models_[static_cast<std::size_t>(r)]->dim());
  std::optional<DeadlinePoll> poll;
  if (deadline_) poll.emplace(*deadline_, kWorkPerClockRead);
  auto counts = [&](std::size_t ri, std::size_t rj) { return !focus || (*focus)[ri] || (*focus)[rj]; };
  // Every pair of robots in `order` (sorted by boxes_' min x) whose boxes
  // overlap and that counts, to visit.
  auto overlappingPairs = [&](const std::vector<int>& order, auto&& visit) {
    for (std::size_t i = 0; i < order.size(); ++i) {
      auto ri = static_cast<std::size_t>(order[i]);
      for (std::size_t j = i + 1; j < order.size(); ++j) {
        auto rj = static_cast<std::size_t>(order[j]);
        if (boxes_[rj].lo.x > boxes_[ri].hi.x) break;
        if (boxes_[ri].overlaps(boxes_[rj]) && counts(ri, rj)) visit(ri, rj);
      }
    }
  };

  // Instants go in chunks. Each robot's bodies over a chunk lie in one box
  // (RobotModel::boundsWithin over its configurations there, which takes
  // an arm's bodies once instead of at every instant); only robots whose
  // box meets another's that counts are placed instant by instant.
  std::vector<int> order;  // the chunk's robots, by min x
  std::vector<char> live(n, 0);
  std::vector<double> lo, hi;
  const std::size_t last = 2 * to;
  for (std::size_t k0 = 2 * from; k0 <= last; k0 += kChunk) {
    const std::size_t k1 = std::min(last, k0 + kChunk - 1);
    if (poll && poll->expired(work)) {  // the bounds: about one instant's work
      interrupted_ = true;
      return std::nullopt;
    }
    for (int r : active) {
      auto ru = static_cast<std::size_t>(r);
      boxes_[ru] = boundsOverInstants(*models_[ru], *paths[ru], k0, k1, q_[ru], lo, hi);
      live[ru] = 0;
    }
    order = active;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return boxes_[static_cast<std::size_t>(a)].lo.x < boxes_[static_cast<std::size_t>(b)].lo.x;
    });
    overlappingPairs(order, [&](std::size_t ri, std::size_t rj) { live[ri] = live[rj] = 1; });
    order.erase(std::remove_if(order.begin(), order.end(), [&](int r) { return !live[static_cast<std::size_t>(r)]; }),
                order.end());
    std::size_t live_work = 0;
    for (int r : order) live_work += q_[static_cast<std::size_t>(r)].size();

    for (std::size_t k = k0; k <= k1 && !order.empty(); ++k) {
      if (poll && poll->expired(live_work)) {
        interrupted_ = true;
        return std::nullopt;
      }
      for (int r : order) {
        auto ru = static_cast<std::size_t>(r);
        stateAtInstant(*models_[ru], *paths[ru], k, q_[ru].data());
        models_[ru]->bodies(q_[ru].data(), bodies_);
        geo::Aabb box;
        for (const auto& b : bodies_) box.expand(geo::bounds(b));
        boxes_[ru] = box;
      }
      // Insertion sort by min x.
      for (std::size_t i = 1; i < order.size(); ++i) {
        int r = order[i];
        std::size_t j = i;
        while (j > 0 && boxes_[static_cast<std::size_t>(order[j - 1])].lo.x > boxes_[static_cast<std::size_t>(r)].lo.x) {
          order[j] = order[j - 1];
          --j;
        }
        order[j] = r;
      }
      std::optional<Conflict> best;
      overlappingPairs(order, [&](std::size_t ri, std::size_t rj) {
        ++exact_tests_;
        if (!robotsTouch(*models_[ri], q_[ri].data(), *models_[rj], q_[rj].data())) return;
        Conflict c;
        c.a = static_cast<int>(std::min(ri, rj));
        c.b = static_cast<int>(std::max(ri, rj));
        c.t = static_cast<double>(k) / 2.0;
        geo::Vec2 ca = models_[ri]->boundingCenter(q_[ri].data());
        geo::Vec2 cb = models_[rj]->boundingCenter(q_[rj].data());
        c.place = (ca + cb) * 0.5;
        // Deterministic choice among simultaneous conflicts: lowest pair.
        if (!best || std::pair(c.a, c.b) < std::pair(best->a, best->b)) best = c;
      });
      if (best) return best;
    }
  }
  return std::nullopt;
}

}  // namespace earc
