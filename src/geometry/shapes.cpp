// Exact planar signed distances between cores (point, segment, rectangle).
//
// Every formula here mirrors shared/tools/check_solution.py operation by
// operation (same products, same order of additions, division rather than
// multiplication by a reciprocal), so that a body pair is judged the same
// way by the planner and by the independent checker, bit for bit when the
// arguments come in the checker's order.
#include "earc/geometry/shapes.hpp"

#include <limits>
#include <utility>

namespace earc::geo {
namespace {

// |sin(angle)| at or below which two segments count as parallel (checker's
// PARALLEL_EPS): the SAT on the two normals is only complete when they are not.
constexpr double kParallelEps = 1e-9;

double distPointSegment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double dd = dot(d, d);
  double t = 0.0;
  if (dd > 0.0) t = std::min(std::max(dot(p - a, d) / dd, 0.0), 1.0);
  return norm(p - (a + d * t));
}

// Signed distance from a local point q to the centred box of half sizes h.
double sdfCentredBox(Vec2 q, Vec2 h) {
  const double lx = std::abs(q.x) - h.x;
  const double ly = std::abs(q.y) - h.y;
  const double outside = norm({std::max(lx, 0.0), std::max(ly, 0.0)});
  const double inside = std::min(std::max(lx, ly), 0.0);
  return outside + inside;
}

// p in the frame of a rectangle centred at c with unit axis u.
Vec2 toLocal(Vec2 p, Vec2 c, Vec2 u) {
  const Vec2 d = p - c;
  return {dot(d, u), cross(u, d)};
}

// Unit vector perpendicular to d (the zero vector when d is).
Vec2 unitNormal(Vec2 d, double len) {
  const double l = len > 0.0 ? len : 1.0;
  const Vec2 n = perp(d);
  return {n.x / l, n.y / l};
}

// Overlap of an interval [min(q0,q1), max(q0,q1)] with the point 0.
double overlapWithZero(double q0, double q1) {
  return std::min(-std::min(q0, q1), std::max(q0, q1));
}

double sdPointRect(Vec2 p, Vec2 c, Vec2 u, Vec2 h) { return sdfCentredBox(toLocal(p, c, u), h); }

double sdSegSeg(Vec2 a1, Vec2 b1, Vec2 a2, Vec2 b2) {
  const double dist = std::min(std::min(distPointSegment(a1, a2, b2), distPointSegment(b1, a2, b2)),
                               std::min(distPointSegment(a2, a1, b1), distPointSegment(b2, a1, b1)));
  const Vec2 d1 = b1 - a1;
  const Vec2 d2 = b2 - a2;
  const double l1 = norm(d1);
  const double l2 = norm(d2);
  const bool proper = std::abs(cross(d1, d2)) > kParallelEps * l1 * l2;
  if (!proper) return dist;
  // SAT on the two segment normals (complete for non-parallel segments).
  const Vec2 n1 = unitNormal(d1, l1);
  const Vec2 n2 = unitNormal(d2, l2);
  const double o1 = overlapWithZero(dot(a2 - a1, n1), dot(b2 - a1, n1));
  const double o2 = overlapWithZero(dot(a1 - a2, n2), dot(b1 - a2, n2));
  if (o1 >= 0.0 && o2 >= 0.0) return -std::min(o1, o2);
  return dist;
}

constexpr std::pair<double, double> kCornerSigns[4] = {{1.0, 1.0}, {1.0, -1.0}, {-1.0, 1.0}, {-1.0, -1.0}};

double sdSegRect(Vec2 a, Vec2 b, Vec2 c, Vec2 u, Vec2 h) {
  const Vec2 la = toLocal(a, c, u);
  const Vec2 lb = toLocal(b, c, u);
  // SAT on the rectangle's axes and the segment's normal: exact penetration.
  const double ox = std::min(std::max(la.x, lb.x) + h.x, h.x - std::min(la.x, lb.x));
  const double oy = std::min(std::max(la.y, lb.y) + h.y, h.y - std::min(la.y, lb.y));
  const Vec2 d = lb - la;
  const double ln = norm(d);
  double on = std::numeric_limits<double>::infinity();
  if (ln > 0.0) {
    const Vec2 n = unitNormal(d, ln);
    const double e = h.x * std::abs(n.x) + h.y * std::abs(n.y);
    on = e - std::abs(dot(la, n));
  }
  const double pen = std::min(std::min(ox, oy), on);
  if (pen >= 0.0) return -pen;
  // Separated: the closest pair involves a vertex of one of the two.
  double dist = std::min(sdfCentredBox(la, h), sdfCentredBox(lb, h));
  for (auto [sx, sy] : kCornerSigns) dist = std::min(dist, distPointSegment({sx * h.x, sy * h.y}, la, lb));
  return dist;
}

// The least overlap of two rectangles' projections on the four edge
// normals (SAT): their penetration depth when >= 0; when < 0, minus a
// lower bound on the gap between them.
double rectRectPenetration(Vec2 c1, Vec2 u1, Vec2 h1, Vec2 c2, Vec2 u2, Vec2 h2) {
  const Vec2 v1 = perp(u1);
  const Vec2 v2 = perp(u2);
  const Vec2 dc = c2 - c1;
  double pen = std::numeric_limits<double>::infinity();
  for (Vec2 n : {u1, v1, u2, v2}) {
    const double e1 = h1.x * std::abs(dot(u1, n)) + h1.y * std::abs(dot(v1, n));
    const double e2 = h2.x * std::abs(dot(u2, n)) + h2.y * std::abs(dot(v2, n));
    pen = std::min(pen, e1 + e2 - std::abs(dot(dc, n)));
  }
  return pen;
}

double sdRectRect(Vec2 c1, Vec2 u1, Vec2 h1, Vec2 c2, Vec2 u2, Vec2 h2) {
  const double pen = rectRectPenetration(c1, u1, h1, c2, u2, h2);
  if (pen >= 0.0) return -pen;
  const Vec2 v1 = perp(u1);
  const Vec2 v2 = perp(u2);
  double dist = std::numeric_limits<double>::infinity();
  for (auto [sx, sy] : kCornerSigns) {
    const Vec2 k1 = c1 + u1 * (sx * h1.x) + v1 * (sy * h1.y);
    const Vec2 k2 = c2 + u2 * (sx * h2.x) + v2 * (sy * h2.y);
    dist = std::min(dist, std::min(sdPointRect(k1, c2, u2, h2), sdPointRect(k2, c1, u1, h1)));
  }
  return dist;
}

// Signed distance between cores with a.kind <= b.kind (point < segment < rect).
double coreDistanceOrdered(const Body& a, const Body& b) {
  switch (a.kind) {
    case CoreKind::Point:
      switch (b.kind) {
        case CoreKind::Point: return norm(a.p0 - b.p0);
        case CoreKind::Segment: return distPointSegment(a.p0, b.p0, b.p1);
        case CoreKind::Rect: return sdPointRect(a.p0, b.p0, b.axis, b.half);
      }
      break;
    case CoreKind::Segment:
      if (b.kind == CoreKind::Segment) return sdSegSeg(a.p0, a.p1, b.p0, b.p1);
      return sdSegRect(a.p0, a.p1, b.p0, b.axis, b.half);
    case CoreKind::Rect:
      return sdRectRect(a.p0, a.axis, a.half, b.p0, b.axis, b.half);
  }
  return std::numeric_limits<double>::quiet_NaN();  // unreachable for valid kinds
}

}  // namespace

double signedDistance(const Body& a, const Body& b) {
  // The checker orders the cores by kind but subtracts the radii in the
  // caller's order; so do we.
  const double core = a.kind <= b.kind ? coreDistanceOrdered(a, b) : coreDistanceOrdered(b, a);
  return core - a.radius - b.radius;
}

bool touches(const Body& a, const Body& b) {
  // Two rectangles (boxes, box obstacles) that a separating axis keeps
  // further apart than their radii cannot touch: the exact distance, eight
  // corner distances with a square root each, is only worked out when
  // they are closer than that. Otherwise this is signedDistance's own
  // arithmetic, in the same order, so the answer is the same.
  if (a.kind == CoreKind::Rect && b.kind == CoreKind::Rect) {
    const double pen = rectRectPenetration(a.p0, a.axis, a.half, b.p0, b.axis, b.half);
    if (pen >= 0.0) return -pen - a.radius - b.radius < -kContactTolerance;
    if (-pen > a.radius + b.radius) return false;
  }
  return signedDistance(a, b) < -kContactTolerance;
}

Aabb bounds(const Body& b) {
  Vec2 lo;
  Vec2 hi;
  switch (b.kind) {
    case CoreKind::Point:
      lo = b.p0;
      hi = b.p0;
      break;
    case CoreKind::Segment:
      lo = {std::min(b.p0.x, b.p1.x), std::min(b.p0.y, b.p1.y)};
      hi = {std::max(b.p0.x, b.p1.x), std::max(b.p0.y, b.p1.y)};
      break;
    case CoreKind::Rect: {
      const Vec2 ext{b.half.x * std::abs(b.axis.x) + b.half.y * std::abs(b.axis.y),
                     b.half.x * std::abs(b.axis.y) + b.half.y * std::abs(b.axis.x)};
      lo = b.p0 - ext;
      hi = b.p0 + ext;
      break;
    }
  }
  return {{lo.x - b.radius, lo.y - b.radius}, {hi.x + b.radius, hi.y + b.radius}};
}

double excessOutside(const Body& b, const Aabb& box) { return excessOutside(bounds(b), box); }

double excessOutside(const Aabb& bb, const Aabb& box) {
  return std::max(std::max(box.lo.x - bb.lo.x, box.lo.y - bb.lo.y),
                  std::max(bb.hi.x - box.hi.x, bb.hi.y - box.hi.y));
}

}  // namespace earc::geo
