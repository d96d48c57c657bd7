#include "refine_retime.hpp"

#include <algorithm>
#include <vector>

namespace earc::refine {

namespace {

// The last instant at which robot r standing at q meets someone, searched
// back from instant k1 to k0; -1 for none, -2 when the poll ran out.
long long lastContactAt(Occupancy& occ, const RobotModel& m, std::size_t r, const double* q, std::size_t k0,
                        std::size_t k1, DeadlinePoll& poll) {
  Path stay(m.dim());
  stay.push(q);
  // A chunk at a time (one box each), then instant by instant in the
  // latest chunk that is not clear.
  for (std::size_t c = k1 / kChunkInstants + 1; c-- > k0 / kChunkInstants;) {
    const std::size_t a = std::max(k0, c * kChunkInstants), b = std::min(k1, c * kChunkInstants + kChunkInstants - 1);
    const Check whole = occ.clear(r, stay, a, b, poll);
    if (whole == Check::OutOfTime) return -2;
    if (whole == Check::Clear) continue;
    for (std::size_t k = b + 1; k-- > a;) {
      const Check at = occ.clearAt(r, q, k, poll);
      if (at == Check::OutOfTime) return -2;
      if (at == Check::Contact) return static_cast<long long>(k);
    }
  }
  return -1;
}

}  // namespace

// Searches (route position, step) pairs; the poll's time also ends it.
std::optional<Path> retimeAlong(Occupancy& occ, const RobotModel& m, std::size_t r, const Path& path, std::size_t t0,
                                const Path& route, std::size_t before, std::size_t horizon, DeadlinePoll& poll,
                                std::size_t max_states) {
  if (route.empty() || t0 + route.size() - 1 >= before) return std::nullopt;
  const std::size_t last = route.size() - 1;
  // Arriving at step T counts only when standing at the end from 2T on
  // meets no one.
  const long long blocked = lastContactAt(occ, m, r, route.back(), 2 * (t0 + last), 2 * std::max(horizon, before), poll);
  if (blocked == -2) return std::nullopt;
  const std::size_t earliest = blocked < 0 ? 0 : static_cast<std::size_t>(blocked) / 2 + 1;
  if (earliest >= before) return std::nullopt;
  // Best first over (route position i, waits so far w), the robot at
  // step t0 + i + w: fewest waits first, and among equally many the
  // furthest on, so that a way with no waits runs straight to the end
  // and a blocked one first tries waiting where it was blocked.
  const std::size_t slack = before - t0 - last;  // waits that still arrive before `before`
  if (static_cast<double>(last + 1) * static_cast<double>(slack) > 4e6) return std::nullopt;
  std::vector<unsigned char> how((last + 1) * slack, 0);  // 1 moved there, 2 waited there
  struct Entry {
    std::size_t i, w;
    unsigned char by;
  };
  std::vector<std::vector<Entry>> open(slack);
  open[0].push_back({0, 0, 1});
  std::vector<double> mid(static_cast<std::size_t>(m.dim()));
  std::size_t states = 0;
  std::size_t at_i = 0, at_w = 0;
  bool arrived = false;
  for (std::size_t w = 0; w < slack && !arrived; ++w) {
    while (!open[w].empty() && !arrived) {
      const Entry e = open[w].back();
      open[w].pop_back();
      unsigned char& seen = how[e.i * slack + e.w];
      if (seen) continue;
      if (++states > max_states || poll.seenExpired()) return std::nullopt;
      const std::size_t t = t0 + e.i + e.w;
      if (t > t0) {
        // The step into (i, w) from step t - 1: its midpoint, then its end.
        const double* from = e.by == 1 ? route.at(e.i - 1) : route.at(e.i);
        m.interpolate(from, route.at(e.i), 0.5, mid.data());
        if (occ.clearAt(r, mid.data(), 2 * t - 1, poll) != Check::Clear) continue;
        if (occ.clearAt(r, route.at(e.i), 2 * t, poll) != Check::Clear) continue;
      }
      seen = e.by;
      if (e.i == last && t >= earliest) {
        at_i = e.i;
        at_w = e.w;
        arrived = true;
        break;
      }
      if (e.w + 1 < slack) open[e.w + 1].push_back({e.i, e.w + 1, 2});
      if (e.i < last) open[e.w].push_back({e.i + 1, e.w, 1});
    }
  }
  if (!arrived) return std::nullopt;
  // Back from the arrival to t0, then forward.
  std::vector<std::size_t> at;
  for (std::size_t i = at_i, w = at_w;;) {
    at.push_back(i);
    if (i == 0 && w == 0) break;
    if (how[i * slack + w] == 1) {
      --i;
    } else {
      --w;
    }
  }
  std::reverse(at.begin(), at.end());
  Path out(m.dim());
  out.reserve(t0 + at.size());
  for (std::size_t t = 0; t < t0; ++t) out.push(path.at(t));
  for (std::size_t s : at) out.push(route.at(s));
  out.dropTrailingWaits();
  return out;
}

}  // namespace earc::refine
