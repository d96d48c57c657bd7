#include "earc/experience/keys.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "earc/util/version.hpp"

namespace earc::exp {

namespace {

std::string joinSignatures(std::span<const RobotTraits> robots, const std::vector<int>& order) {
  std::string s;
  for (std::size_t c = 0; c < order.size(); ++c) {
    if (c) s += '|';
    s += robots[static_cast<std::size_t>(order[c])].signature;
  }
  return s;
}

// kArmKeyJoints: with all of an arm's joints the k-d tree visits nearly
// every leaf and loses to a linear scan. The joints near the base decide
// where the arm is, so the first three keep most of what "close" means
// while the tree is 3x faster than a scan (docs/performance-log.md); the
// planner validates (and repairs) every candidate anyway.
int armKeyJoints(int dim) { return std::min(dim, kArmKeyJoints); }

std::vector<double> armKey(const std::vector<int>& order, const std::vector<std::vector<double>>& starts,
                           const std::vector<std::vector<double>>& goals) {
  std::vector<double> key;
  for (int i : order) {
    const auto& s = starts[static_cast<std::size_t>(i)];
    const auto& g = goals[static_cast<std::size_t>(i)];
    const int m = armKeyJoints(static_cast<int>(s.size()));
    key.insert(key.end(), s.begin(), s.begin() + m);
    key.insert(key.end(), g.begin(), g.begin() + m);
  }
  return key;
}

void checkShape(std::span<const RobotTraits> robots, const std::vector<std::vector<double>>& starts,
                const std::vector<std::vector<double>>& goals) {
  if (!hasExperienceClass(robots))
    throw std::invalid_argument("canonicalize: robots form no experience class (mobile robots, or two equal-dimension arms)");
  if (starts.size() != robots.size() || goals.size() != robots.size())
    throw std::invalid_argument("canonicalize: one start and one goal per robot expected");
  for (std::size_t i = 0; i < robots.size(); ++i)
    if (starts[i].size() != static_cast<std::size_t>(robots[i].dim) ||
        goals[i].size() != static_cast<std::size_t>(robots[i].dim))
      throw std::invalid_argument("canonicalize: start or goal dimension differs from the robot's");
}

Canonical canonicalMobile(std::span<const RobotTraits> robots, const std::vector<std::vector<double>>& starts,
                          const std::vector<std::vector<double>>& goals) {
  const std::size_t n = robots.size();
  Canonical c;
  double sx = 0, sy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sx += starts[i][0] + goals[i][0];
    sy += starts[i][1] + goals[i][1];
  }
  c.offset = {sx / static_cast<double>(2 * n), sy / static_cast<double>(2 * n)};
  auto quant = [](double v) { return std::llround(v / kOrderQuantum); };
  c.order.resize(n);
  std::iota(c.order.begin(), c.order.end(), 0);
  auto rank = [&](int i) {
    const auto& s = starts[static_cast<std::size_t>(i)];
    const auto& g = goals[static_cast<std::size_t>(i)];
    return std::array<long long, 4>{quant(s[0] - c.offset.x), quant(s[1] - c.offset.y), quant(g[0] - c.offset.x),
                                    quant(g[1] - c.offset.y)};
  };
  std::stable_sort(c.order.begin(), c.order.end(), [&](int a, int b) { return rank(a) < rank(b); });
  for (int i : c.order) {
    const auto& s = starts[static_cast<std::size_t>(i)];
    const auto& g = goals[static_cast<std::size_t>(i)];
    c.key.insert(c.key.end(), {s[0] - c.offset.x, s[1] - c.offset.y, g[0] - c.offset.x, g[1] - c.offset.y});
  }
  c.cls = {RobotKind::Mobile, static_cast<int>(n), joinSignatures(robots, c.order), ""};
  return c;
}

Canonical canonicalArms(std::span<const RobotTraits> robots, const std::vector<std::vector<double>>& starts,
                        const std::vector<std::vector<double>>& goals) {
  RelativeTransform ab = relativeBaseTransform(robots[0], robots[1]);
  RelativeTransform ba = relativeBaseTransform(robots[1], robots[0]);
  std::string sab = baseClassString(ab.dx, ab.dy, ab.dtheta);
  std::string sba = baseClassString(ba.dx, ba.dy, ba.dtheta);
  Canonical c;
  c.order = {0, 1};
  if (sba < sab) {
    c.order = {1, 0};
  } else if (sba == sab) {
    c.symmetric = true;
    std::vector<int> other{1, 0};
    if (armKey(other, starts, goals) < armKey(c.order, starts, goals)) c.order = other;
  }
  c.sign = c.order[0] == 0 ? 1 : -1;
  c.key = armKey(c.order, starts, goals);
  c.cls = {RobotKind::Manipulator, 2, joinSignatures(robots, c.order), std::min(sab, sba)};
  return c;
}

}  // namespace

RobotTraits traitsOf(const RobotModel& robot) {
  const RobotSpec& spec = robot.spec();
  return {spec.kind, robot.dim(), robot.geometrySignature(), spec.base_position, spec.base_angle};
}

int keyDimension(RobotKind kind, int robot_count, int robot_dim) {
  return kind == RobotKind::Mobile ? 4 * robot_count : 2 * robot_count * armKeyJoints(robot_dim);
}

std::vector<double> keyOfCanonicalPaths(RobotKind kind, const std::vector<Path>& paths) {
  std::vector<double> key;
  for (const Path& p : paths) {
    if (p.empty()) throw std::invalid_argument("keyOfCanonicalPaths: empty path");
    const double* s = p.at(0);
    const double* g = p.back();
    const int m = kind == RobotKind::Mobile ? 2 : armKeyJoints(p.dim());
    if (kind == RobotKind::Mobile) {
      key.insert(key.end(), {s[0], s[1], g[0], g[1]});
    } else {
      key.insert(key.end(), s, s + m);
      key.insert(key.end(), g, g + m);
    }
  }
  return key;
}

std::string baseClassString(double dx, double dy, double dtheta) {
  auto q = [](double v) { return std::llround(v / kBaseClassQuantum); };
  long long qx = q(dx), qy = q(dy), qt = q(geo::wrapAngle(dtheta));
  // wrapAngle answers [-pi, pi); -pi and pi are one angle: keep +pi.
  const long long qpi = q(std::numbers::pi);
  if (qt == -qpi) qt = qpi;
  char buf[96];
  std::snprintf(buf, sizeof buf, "dx=%.3f,dy=%.3f,dth=%.3f", static_cast<double>(qx) * kBaseClassQuantum,
                static_cast<double>(qy) * kBaseClassQuantum, static_cast<double>(qt) * kBaseClassQuantum);
  return buf;
}

RelativeTransform relativeBaseTransform(const RobotTraits& a, const RobotTraits& b) {
  const geo::Vec2 d = b.base - a.base;
  const double c = std::cos(a.base_angle), s = std::sin(a.base_angle);
  return {c * d.x + s * d.y, -s * d.x + c * d.y, geo::wrapAngle(b.base_angle - a.base_angle)};
}

bool hasExperienceClass(std::span<const RobotTraits> robots) {
  if (robots.empty()) return false;
  if (std::all_of(robots.begin(), robots.end(), [](const RobotTraits& r) { return r.kind == RobotKind::Mobile; }))
    return std::all_of(robots.begin(), robots.end(), [](const RobotTraits& r) { return r.dim == 3; });
  return robots.size() == 2 && robots[0].kind == RobotKind::Manipulator &&
         robots[1].kind == RobotKind::Manipulator && robots[0].dim == robots[1].dim && robots[0].dim > 0;
}

Canonical canonicalize(std::span<const RobotTraits> robots, const std::vector<std::vector<double>>& starts,
                       const std::vector<std::vector<double>>& goals) {
  checkShape(robots, starts, goals);
  return robots.front().kind == RobotKind::Mobile ? canonicalMobile(robots, starts, goals)
                                                  : canonicalArms(robots, starts, goals);
}

Canonical canonicalize(const std::vector<const RobotModel*>& robots, const std::vector<std::vector<double>>& starts,
                       const std::vector<std::vector<double>>& goals) {
  std::vector<RobotTraits> traits;
  traits.reserve(robots.size());
  for (const RobotModel* r : robots) traits.push_back(traitsOf(*r));
  return canonicalize(traits, starts, goals);
}

Canonical swappedRoles(const Canonical& c, const std::vector<std::vector<double>>& starts,
                       const std::vector<std::vector<double>>& goals) {
  if (!c.symmetric) throw std::invalid_argument("swappedRoles: only symmetric arm pairs have two canonical forms");
  Canonical s = c;
  s.order = {c.order[1], c.order[0]};
  s.sign = -c.sign;
  s.key = armKey(s.order, starts, goals);
  return s;
}

Experience canonicalExperience(const Canonical& form, const std::vector<Path>& subproblem_paths) {
  Experience e;
  e.cls = form.cls;
  e.paths = form.toCanonical(subproblem_paths);
  e.key = keyOfCanonicalPaths(e.cls.kind, e.paths);
  e.cost = pathCost(e.paths);
  e.made_by = version();
  return e;
}

std::vector<Path> Canonical::toCanonical(const std::vector<Path>& paths) const {
  if (paths.size() != order.size()) throw std::invalid_argument("toCanonical: one path per robot expected");
  std::vector<Path> out;
  out.reserve(order.size());
  for (int i : order) {
    Path p = paths[static_cast<std::size_t>(i)];
    if (cls.kind == RobotKind::Mobile)
      for (std::size_t t = 0; t < p.size(); ++t) {
        p.mutableAt(t)[0] -= offset.x;
        p.mutableAt(t)[1] -= offset.y;
      }
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<Path> Canonical::fromCanonical(const std::vector<Path>& paths) const {
  if (paths.size() != order.size()) throw std::invalid_argument("fromCanonical: one path per robot expected");
  std::vector<Path> out(order.size());
  for (std::size_t c = 0; c < order.size(); ++c) {
    Path p = paths[c];
    if (cls.kind == RobotKind::Mobile)
      for (std::size_t t = 0; t < p.size(); ++t) {
        p.mutableAt(t)[0] += offset.x;
        p.mutableAt(t)[1] += offset.y;
      }
    out[static_cast<std::size_t>(order[c])] = std::move(p);
  }
  return out;
}

}  // namespace earc::exp
