#include "earc/planning/path_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>

#include "earc/geometry/shapes.hpp"

namespace earc {

namespace {

using geo::Vec2;

double crossOf(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
Vec2 minus(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }

// A convex polygon, counter-clockwise, inside an obstacle grown by a
// disc's radius: a disc centre that stays out of the grown obstacle stays
// out of it, so ways around these polygons are no longer than the disc's.
using Polygon = std::vector<Vec2>;

Polygon grownInside(const Obstacle& o, double rho) {
  Polygon out;
  auto add = [&](Vec2 p) {
    if (out.empty() || std::hypot(p.x - out.back().x, p.y - out.back().y) > 1e-9) out.push_back(p);
  };
  if (o.type == Obstacle::Type::Circle) {
    constexpr int kSides = 16;
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * M_PI * k / kSides;
      add({o.center.x + (o.radius + rho) * std::cos(a), o.center.y + (o.radius + rho) * std::sin(a)});
    }
  } else {
    // Each corner pushed out along its two sides' normals (points on the
    // grown box's rounded boundary).
    const double c = std::cos(o.angle), s = std::sin(o.angle);
    const Vec2 ax{c, s}, ay{-s, c};
    const double hx = 0.5 * o.size.x, hy = 0.5 * o.size.y;
    const Vec2 corner[4] = {{hx, -hy}, {hx, hy}, {-hx, hy}, {-hx, -hy}};
    const Vec2 before[4] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};  // normal of the side ending at the corner
    for (int k = 0; k < 4; ++k) {
      const Vec2 after = before[(k + 1) % 4];
      for (Vec2 n : {before[k], after}) {
        const Vec2 local{corner[k].x + rho * n.x, corner[k].y + rho * n.y};
        add({o.center.x + local.x * ax.x + local.y * ay.x, o.center.y + local.x * ax.y + local.y * ay.y});
      }
    }
  }
  if (out.size() > 1 && std::hypot(out.front().x - out.back().x, out.front().y - out.back().y) <= 1e-9) out.pop_back();
  return out;
}

// Whether the open segment ab passes through the polygon's interior (a
// segment along its boundary does not).
bool crosses(const Polygon& poly, Vec2 a, Vec2 b) {
  if (poly.size() < 3) return false;
  const Vec2 d = minus(b, a);
  double lo = 0.0, hi = 1.0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2 v = poly[k], e = minus(poly[(k + 1) % poly.size()], v);
    const double len = std::hypot(e.x, e.y);
    // Inside: cross(e, x - v) > 0, by more than a rounding margin.
    const double f0 = crossOf(e, minus(a, v)) - 1e-9 * len, slope = crossOf(e, d);
    if (slope == 0.0) {
      if (f0 <= 0.0) return false;
    } else if (slope > 0.0) {
      lo = std::max(lo, -f0 / slope);
    } else {
      hi = std::min(hi, -f0 / slope);
    }
    if (hi - lo <= 1e-12) return false;
  }
  return true;
}

bool insideAny(const std::vector<Polygon>& polys, Vec2 p) {
  for (const Polygon& poly : polys) {
    if (poly.size() < 3) continue;
    bool in = true;
    for (std::size_t k = 0; k < poly.size() && in; ++k) {
      const Vec2 e = minus(poly[(k + 1) % poly.size()], poly[k]);
      in = crossOf(e, minus(p, poly[k])) > 1e-9 * std::hypot(e.x, e.y);
    }
    if (in) return true;
  }
  return false;
}

// The visibility graph of the polygons' corners for one disc radius: the
// corners that are free and, per pair, their distance when one sees the other.
struct Corners {
  std::vector<Polygon> polys;
  std::vector<Vec2> at;
  std::vector<std::vector<std::pair<std::size_t, double>>> sees;

  bool visible(Vec2 a, Vec2 b) const {
    for (const Polygon& poly : polys)
      if (crosses(poly, a, b)) return false;
    return true;
  }

  Corners(const std::vector<Obstacle>& obstacles, double rho) {
    for (const Obstacle& o : obstacles) polys.push_back(grownInside(o, rho));
    for (const Polygon& poly : polys)
      for (Vec2 p : poly)
        if (!insideAny(polys, p)) at.push_back(p);
    sees.resize(at.size());
    for (std::size_t i = 0; i < at.size(); ++i)
      for (std::size_t j = i + 1; j < at.size(); ++j)
        if (visible(at[i], at[j])) {
          const double d = std::hypot(at[i].x - at[j].x, at[i].y - at[j].y);
          sees[i].push_back({j, d});
          sees[j].push_back({i, d});
        }
  }

  // Shortest way from a to b around the polygons (Dijkstra; the corners
  // that a and b see joined on the fly).
  double shortest(Vec2 a, Vec2 b) const {
    if (visible(a, b)) return std::hypot(b.x - a.x, b.y - a.y);
    const std::size_t n = at.size();
    std::vector<double> to_b(n, -1.0), dist(n, std::numeric_limits<double>::infinity());
    using Item = std::pair<double, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    for (std::size_t i = 0; i < n; ++i) {
      if (visible(at[i], b)) to_b[i] = std::hypot(b.x - at[i].x, b.y - at[i].y);
      if (visible(a, at[i])) {
        dist[i] = std::hypot(at[i].x - a.x, at[i].y - a.y);
        open.push({dist[i], i});
      }
    }
    double best = std::numeric_limits<double>::infinity();
    while (!open.empty()) {
      const auto [d, i] = open.top();
      open.pop();
      if (d > dist[i] || d >= best) continue;
      if (to_b[i] >= 0.0) best = std::min(best, d + to_b[i]);
      for (const auto& [j, w] : sees[i])
        if (d + w < dist[j]) {
          dist[j] = d + w;
          open.push({dist[j], j});
        }
    }
    return best;
  }
};

std::size_t stepsFor(double amount, double resolution) {
  return amount <= 0.0 ? 0 : static_cast<std::size_t>(std::ceil(amount / resolution - 1e-9));
}

}  // namespace

std::vector<std::size_t> straightLineBounds(const Scenario& scenario, const std::vector<const RobotModel*>& models) {
  std::vector<std::size_t> out;
  for (std::size_t r = 0; r < scenario.robots.size(); ++r) {
    const RobotSpec& spec = scenario.robots[r];
    out.push_back(static_cast<std::size_t>(models[r]->stepsBetween(spec.start.data(), spec.goal.data())));
  }
  return out;
}

// A mobile robot's way is its inscribed disc's: any path of the body
// carries that disc, so the disc's shortest way bounds the body's.
std::vector<std::size_t> ownPathLowerBounds(const Scenario& scenario, const std::vector<const RobotModel*>& models,
                                            std::size_t max_obstacles) {
  std::vector<std::size_t> out = straightLineBounds(scenario, models);
  if (scenario.obstacles.empty() || scenario.obstacles.size() > max_obstacles) return out;
  const Resolution& res = scenario.resolution;
  // One graph per inscribed radius; less a step's length, so that a
  // motion checked at its steps and midpoints cannot cut a corner closer.
  std::map<double, Corners> graphs;
  for (std::size_t r = 0; r < scenario.robots.size(); ++r) {
    const RobotSpec& spec = scenario.robots[r];
    if (spec.kind != RobotKind::Mobile) continue;
    const double inscribed = spec.shape == MobileShape::Disc ? spec.radius : 0.5 * std::min(spec.box_size.x, spec.box_size.y);
    const double rho = std::max(0.0, inscribed - res.translation);
    auto it = graphs.find(rho);
    if (it == graphs.end()) it = graphs.emplace(rho, Corners(scenario.obstacles, rho)).first;
    const double way = it->second.shortest({spec.start[0], spec.start[1]}, {spec.goal[0], spec.goal[1]});
    if (!std::isfinite(way)) continue;  // enclosed: the straight line stands
    out[r] = std::max(out[r], stepsFor(way, res.translation));
  }
  return out;
}

}  // namespace earc
