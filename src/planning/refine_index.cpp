#include "refine_index.hpp"

#include <algorithm>
#include <cmath>

#include "earc/planning/conflict.hpp"

namespace earc::refine {

geo::Aabb boundsOverSteps(const RobotModel& m, const Path& path, std::size_t s0, std::size_t s1) {
  geo::Aabb box;
  s1 = std::min(s1, path.size() - 1);
  s0 = std::min(s0, s1);
  for (std::size_t t = s0; t <= s1; ++t) {
    const geo::Vec2 c = m.boundingCenter(path.at(t));
    box.expand({c, c});
  }
  return box.inflated(m.boundingRadius());
}

template <class Visit>
void Occupancy::forCells(const geo::Aabb& box, Visit&& visit) {
  auto ix = [&](double x) { return std::clamp(static_cast<long>(std::floor((x - area_.lo.x) / cell_)), 0L, nx_ - 1); };
  auto iy = [&](double y) { return std::clamp(static_cast<long>(std::floor((y - area_.lo.y) / cell_)), 0L, ny_ - 1); };
  const long x0 = ix(box.lo.x), x1 = ix(box.hi.x), y0 = iy(box.lo.y), y1 = iy(box.hi.y);
  for (long y = y0; y <= y1; ++y)
    for (long x = x0; x <= x1; ++x) visit(grid_[static_cast<std::size_t>(y * nx_ + x)]);
}

// The index: per chunk of steps, the robots still on their way then with
// the box their bodies stay in; and a grid of the goals where the robots
// that have arrived stand.
Occupancy::Occupancy(const std::vector<const RobotModel*>& models, const std::vector<Path>& paths, const geo::Aabb& workspace)
    : models_(models), paths_(paths), len_(paths.size(), 0), in_(paths.size(), 0), goal_(paths.size()),
      stamp_(paths.size(), 0) {
  double radius = 0.0;
  for (const RobotModel* m : models_) radius = std::max(radius, m->boundingRadius());
  area_ = workspace;
  const double w = area_.hi.x - area_.lo.x, h = area_.hi.y - area_.lo.y;
  cell_ = std::max({2.0 * radius, w / 256.0, h / 256.0, 1e-9});
  nx_ = std::max<long>(1, static_cast<long>(std::ceil(w / cell_)));
  ny_ = std::max<long>(1, static_cast<long>(std::ceil(h / cell_)));
  grid_.resize(static_cast<std::size_t>(nx_ * ny_));
  for (std::size_t r = 0; r < paths_.size(); ++r) insert(r);
}

void Occupancy::insert(std::size_t r) {
  const Path& p = paths_[r];
  if (in_[r] || p.empty()) return;
  in_[r] = 1;
  len_[r] = p.size() - 1;
  const RobotModel& m = *models_[r];
  const std::size_t chunks = len_[r] == 0 ? 0 : (len_[r] - 1) / kChunkSteps + 1;
  if (chunks_.size() < chunks) chunks_.resize(chunks);
  for (std::size_t c = 0; c < chunks; ++c)
    chunks_[c].push_back({static_cast<std::uint32_t>(r), boundsOverSteps(m, p, c * kChunkSteps, (c + 1) * kChunkSteps)});
  goal_[r] = boundsOverSteps(m, p, len_[r], len_[r]);
  forCells(goal_[r], [&](std::vector<std::uint32_t>& cell) { cell.push_back(static_cast<std::uint32_t>(r)); });
}

void Occupancy::remove(std::size_t r) {
  if (!in_[r]) return;
  in_[r] = 0;
  const std::size_t chunks = len_[r] == 0 ? 0 : (len_[r] - 1) / kChunkSteps + 1;
  for (std::size_t c = 0; c < chunks; ++c) {
    auto& list = chunks_[c];
    for (std::size_t i = 0; i < list.size(); ++i)
      if (list[i].robot == r) {
        list[i] = list.back();
        list.pop_back();
        break;
      }
  }
  forCells(goal_[r], [&](std::vector<std::uint32_t>& cell) {
    auto it = std::find(cell.begin(), cell.end(), static_cast<std::uint32_t>(r));
    if (it != cell.end()) {
      *it = cell.back();
      cell.pop_back();
    }
  });
}

std::size_t Occupancy::gatherNear(std::size_t r, std::size_t c, const geo::Aabb& box) {
  near_.clear();
  std::size_t tests = 1;
  if (c < chunks_.size()) {
    tests += chunks_[c].size();
    for (const auto& e : chunks_[c])
      if (e.robot != r && e.box.overlaps(box)) near_.push_back({e.robot, false});
  }
  ++tick_;
  forCells(box, [&](std::vector<std::uint32_t>& cell) {
    for (std::uint32_t o : cell) {
      ++tests;
      if (o == r || stamp_[o] == tick_ || len_[o] > c * kChunkSteps) continue;
      stamp_[o] = tick_;
      if (goal_[o].overlaps(box)) near_.push_back({o, true});
    }
  });
  return tests;
}

Check Occupancy::clear(std::size_t r, const Path& p, std::size_t k0, std::size_t k1, DeadlinePoll& poll) {
  const RobotModel& m = *models_[r];
  q_.resize(static_cast<std::size_t>(m.dim()));
  for (std::size_t c = k0 / kChunkInstants; c <= k1 / kChunkInstants; ++c) {
    const std::size_t ia = std::max(k0, c * kChunkInstants), ib = std::min(k1, c * kChunkInstants + kChunkInstants - 1);
    const geo::Aabb box = boundsOverSteps(m, p, ia / 2, (ib + 1) / 2);
    const std::size_t tests = gatherNear(r, c, box);
    if (poll.expired(tests / 8 + 1)) return Check::OutOfTime;
    if (near_.empty()) continue;
    for (std::size_t k = ia; k <= ib; ++k) {
      stateAtInstant(m, p, k, q_.data());
      if (const Check hit = touchesNear(r, q_.data(), k, poll); hit != Check::Clear) return hit;
    }
  }
  return Check::Clear;
}

Check Occupancy::touchesNear(std::size_t r, const double* q, std::size_t k, DeadlinePoll& poll) {
  const RobotModel& m = *models_[r];
  against_.set(m, q);
  for (const Near& n : near_) {
    const RobotModel& mo = *models_[n.robot];
    const double* qo = paths_[n.robot].back();
    if (!n.parked) {
      qo_.resize(static_cast<std::size_t>(mo.dim()));
      stateAtInstant(mo, paths_[n.robot], k, qo_.data());
      qo = qo_.data();
    }
    const RobotAgainst::Result hit = against_.check(mo, qo);
    if (hit == RobotAgainst::Result::Apart) continue;
    if (hit == RobotAgainst::Result::Touch) return Check::Contact;
    if (poll.expired(static_cast<std::size_t>(m.dim() + mo.dim()))) return Check::OutOfTime;
  }
  return poll.expired(near_.size() / 8 + 1) ? Check::OutOfTime : Check::Clear;
}

Check Occupancy::clearAt(std::size_t r, const double* q, std::size_t k, DeadlinePoll& poll) {
  const RobotModel& m = *models_[r];
  const std::size_t c = k / kChunkInstants;
  const geo::Vec2 centre = m.boundingCenter(q);
  const geo::Aabb box = geo::Aabb{centre, centre}.inflated(m.boundingRadius());
  const std::size_t tests = gatherNear(r, c, box);
  if (poll.expired(tests / 8 + 1)) return Check::OutOfTime;
  return near_.empty() ? Check::Clear : touchesNear(r, q, k, poll);
}

void Occupancy::robotsNear(std::size_t r, std::size_t c, const geo::Aabb& box, std::vector<std::size_t>& out) {
  if (c < chunks_.size())
    for (const auto& e : chunks_[c])
      if (e.robot != r && e.box.overlaps(box)) out.push_back(e.robot);
  forCells(box, [&](std::vector<std::uint32_t>& cell) {
    for (std::uint32_t o : cell)
      if (o != r && len_[o] <= c * kChunkSteps && goal_[o].overlaps(box)) out.push_back(o);
  });
}

}  // namespace earc::refine
