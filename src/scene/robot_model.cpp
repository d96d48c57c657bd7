// The two robot kinds of the contract: SE(2) mobile robots (disc or box
// footprint) and fixed-base planar serial arms (a capsule per link).
// Kinematics follow shared/tools/check_solution.py operation by operation.
#include "earc/scene/robot_model.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cstdio>
#include <stdexcept>

#include "earc/scene/robot_signature.hpp"

namespace earc {
namespace {

// Slack under which a fractional step count still rounds down: a motion of
// 3 + 1e-12 steps (rounding noise of a planner's own interpolation) takes 3.
constexpr double kStepSlack = 1e-9;

std::string fmt6(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The fixed parts of geometry signatures, for the writers below and the
// reader (robotFromSignature).
constexpr std::string_view kDiscPrefix = "mobile:disc:r=";
constexpr std::string_view kBoxPrefix = "mobile:box:";
constexpr std::string_view kArmPrefix = "arm:links=";
constexpr std::string_view kArmRadius = ":r=";
constexpr std::string_view kArmLimits = ":limits=";

void requireNonNegative(double v, const char* what, const RobotSpec& spec) {
  if (!(v >= 0.0) || !std::isfinite(v))
    throw std::invalid_argument("robot '" + spec.name + "': " + what + " must be a finite number >= 0");
}

void requirePositive(double v, const char* what) {
  if (!(v > 0.0) || !std::isfinite(v))
    throw std::invalid_argument(std::string("resolution.") + what + " must be a finite number > 0");
}

// Calls visit(i, joint_i, joint_i+1) for each link i of an arm. Mirrors the
// checker: link angles are base_angle + cumulative sum of q, and joint i is
// base + (cumulative sum of the link vectors), not joint i-1 + link i.
template <class Visit>
void walkArm(const RobotSpec& arm, const double* q, Visit&& visit) {
  double qsum = 0.0;
  geo::Vec2 reach;
  geo::Vec2 prev = arm.base_position;
  for (std::size_t i = 0; i < arm.links.size(); ++i) {
    qsum = i == 0 ? q[0] : qsum + q[i];
    const double phi = arm.base_angle + qsum;
    const geo::Vec2 step{arm.links[i] * std::cos(phi), arm.links[i] * std::sin(phi)};
    reach = i == 0 ? step : reach + step;
    const geo::Vec2 next = arm.base_position + reach;
    visit(i, prev, next);
    prev = next;
  }
}

// (1 - s) a + s b: exactly a at s = 0, exactly b at s = 1, and at s = 1/2
// the same rounding as the checker's midpoint 0.5 (a + b).
double lerp(double a, double b, double s) { return (1.0 - s) * a + s * b; }

class MobileRobot final : public RobotModel {
 public:
  MobileRobot(RobotSpec spec, Resolution res) : RobotModel(std::move(spec), res) {
    center_is_position_ = true;
    if (spec_.shape == MobileShape::Disc) {
      requireNonNegative(spec_.radius, "disc radius", spec_);
      bounding_radius_ = spec_.radius;
    } else {
      requireNonNegative(spec_.box_size.x, "box length", spec_);
      requireNonNegative(spec_.box_size.y, "box width", spec_);
      bounding_radius_ = std::hypot(0.5 * spec_.box_size.x, 0.5 * spec_.box_size.y);
    }
  }

  int dim() const override { return 3; }

  double distance(const double* a, const double* b) const override {
    const double translation = geo::norm({b[0] - a[0], b[1] - a[1]});
    const double rotation = std::abs(geo::angleDiff(a[2], b[2]));
    return std::max(translation / resolution_.translation, rotation / resolution_.rotation);
  }

  void interpolate(const double* a, const double* b, double s, double* out) const override {
    out[0] = lerp(a[0], b[0], s);
    out[1] = lerp(a[1], b[1], s);
    // At s = 1 the target heading itself, not a + (its 2 pi-equivalent).
    out[2] = s >= 1.0 ? b[2] : a[2] + s * geo::angleDiff(a[2], b[2]);
  }

  void bodies(const double* q, std::vector<geo::Body>& out) const override {
    out.clear();
    const geo::Vec2 c{q[0], q[1]};
    if (spec_.shape == MobileShape::Disc)
      out.push_back(geo::Body::disc(c, spec_.radius));
    else
      out.push_back(geo::Body::box(c, spec_.box_size * 0.5, q[2]));
  }

  bool selfCollides(const double*) const override { return false; }
  bool selfCollides(const std::vector<geo::Body>&, const std::vector<geo::Aabb>&) const override { return false; }
  bool withinLimits(const double*) const override { return true; }

  std::string geometrySignature() const override {
    std::string s;
    if (spec_.shape == MobileShape::Disc) {
      s += kDiscPrefix;
      s += fmt6(spec_.radius);
    } else {
      s += kBoxPrefix;
      s += fmt6(spec_.box_size.x);
      s += 'x';
      s += fmt6(spec_.box_size.y);
    }
    return s;
  }

  // x and y: the workspace inset by the footprint's inner radius (the least
  // distance from the centre to the footprint's edge at any heading), so no
  // position where the robot fits is left out; the centre line where even
  // that does not fit.
  void samplingBounds(const geo::Aabb& ws, std::vector<double>& lo, std::vector<double>& hi) const override {
    const double inner = spec_.shape == MobileShape::Disc
                             ? spec_.radius
                             : 0.5 * std::min(spec_.box_size.x, spec_.box_size.y);
    auto axis = [inner](double wlo, double whi, double& l, double& h) {
      l = wlo + inner;
      h = whi - inner;
      if (l > h) l = h = 0.5 * (wlo + whi);
    };
    lo.assign(3, 0.0);
    hi.assign(3, 0.0);
    axis(ws.lo.x, ws.hi.x, lo[0], hi[0]);
    axis(ws.lo.y, ws.hi.y, lo[1], hi[1]);
    lo[2] = -std::numbers::pi;
    hi[2] = std::numbers::pi;
  }

  bool isMobile() const override { return true; }
};

class ArmRobot final : public RobotModel {
 public:
  ArmRobot(RobotSpec spec, Resolution res) : RobotModel(std::move(spec), res) {
    if (spec_.links.empty()) throw std::invalid_argument("robot '" + spec_.name + "': an arm needs at least one link");
    for (double l : spec_.links) requireNonNegative(l, "link length", spec_);
    requireNonNegative(spec_.link_radius, "link radius", spec_);
    if (spec_.joint_limits.empty())
      spec_.joint_limits.assign(spec_.links.size(), {-std::numbers::pi, std::numbers::pi});
    if (spec_.joint_limits.size() != spec_.links.size())
      throw std::invalid_argument("robot '" + spec_.name + "': one joint limit pair per link expected");
    for (auto [l, h] : spec_.joint_limits)
      if (!(l <= h)) throw std::invalid_argument("robot '" + spec_.name + "': joint limit lo > hi");
    // The base, and the sum of the link lengths plus the link radius.
    fixed_center_ = spec_.base_position;
    bounding_radius_ = spec_.link_radius;
    for (double l : spec_.links) bounding_radius_ += l;
  }

  int dim() const override { return static_cast<int>(spec_.links.size()); }

  double distance(const double* a, const double* b) const override {
    double worst = 0.0;
    for (int i = 0; i < dim(); ++i) worst = std::max(worst, std::abs(b[i] - a[i]));
    return worst / resolution_.joint;
  }

  void interpolate(const double* a, const double* b, double s, double* out) const override {
    for (int i = 0; i < dim(); ++i) out[i] = lerp(a[i], b[i], s);
  }

  void bodies(const double* q, std::vector<geo::Body>& out) const override {
    out.resize(spec_.links.size());
    walkArm(spec_, q, [&](std::size_t i, geo::Vec2 from, geo::Vec2 to) {
      out[i] = geo::Body::capsule(from, to, spec_.link_radius);
    });
  }

  // The bodies at the box's middle, widened by how far any point can move
  // from there: turning joint i by d moves every point beyond it by at
  // most |d| times its distance from the joint, which is at most the
  // links from i on plus the link radius (the links beyond turn with it,
  // rigidly). Summed over the joints, with a hair of slack for rounding.
  geo::Aabb boundsWithin(const double* lo, const double* hi) const override {
    const std::size_t n = spec_.links.size();
    thread_local std::vector<double> mid;
    mid.resize(n);
    double widen = 0.0;
    double reach = spec_.link_radius;
    for (std::size_t i = n; i-- > 0;) {
      mid[i] = 0.5 * (lo[i] + hi[i]);
      reach += spec_.links[i];
      widen += 0.5 * (hi[i] - lo[i]) * reach;
    }
    thread_local std::vector<geo::Body> links;
    bodies(mid.data(), links);
    geo::Aabb box;
    for (const auto& link : links) box.expand(geo::bounds(link));
    return box.inflated(widen * (1.0 + 1e-9) + 1e-9);
  }

  bool selfCollides(const double* q) const override {
    if (spec_.links.size() < 3) return false;
    thread_local std::vector<geo::Body> links;  // per-thread scratch: no allocation per call
    thread_local std::vector<geo::Aabb> boxes;
    bodies(q, links);
    boxes.resize(links.size());
    for (std::size_t i = 0; i < links.size(); ++i) boxes[i] = geo::bounds(links[i]);
    return selfCollides(links, boxes);
  }

  bool selfCollides(const std::vector<geo::Body>& links, const std::vector<geo::Aabb>& boxes) const override {
    // Links that share a joint never count (contract); all others must not touch.
    for (std::size_t i = 0; i + 2 < links.size(); ++i)
      for (std::size_t j = i + 2; j < links.size(); ++j)
        if (boxes[i].overlaps(boxes[j]) && geo::touches(links[i], links[j])) return true;
    return false;
  }

  // The checker's joint-limit test allows the contract's 1e-6 slack.
  bool withinLimits(const double* q) const override {
    for (int i = 0; i < dim(); ++i) {
      const auto [l, h] = spec_.joint_limits[static_cast<std::size_t>(i)];
      if (!(q[i] >= l - geo::kContactTolerance && q[i] <= h + geo::kContactTolerance)) return false;
    }
    return true;
  }

  std::string geometrySignature() const override {
    // Appended piece by piece: "lit" + std::string&& trips GCC 12's -Wrestrict.
    std::string s(kArmPrefix);
    for (std::size_t i = 0; i < spec_.links.size(); ++i) {
      if (i) s += ',';
      s += fmt6(spec_.links[i]);
    }
    s += kArmRadius;
    s += fmt6(spec_.link_radius);
    s += kArmLimits;
    for (std::size_t i = 0; i < spec_.joint_limits.size(); ++i) {
      if (i) s += ',';
      s += fmt6(spec_.joint_limits[i].first);
      s += '/';
      s += fmt6(spec_.joint_limits[i].second);
    }
    return s;
  }

  void samplingBounds(const geo::Aabb&, std::vector<double>& lo, std::vector<double>& hi) const override {
    lo.clear();
    hi.clear();
    for (auto [l, h] : spec_.joint_limits) {
      lo.push_back(l);
      hi.push_back(h);
    }
  }

  bool isMobile() const override { return false; }
};

// Reads the pieces geometrySignature writes, front to back; any mismatch
// makes it fail for good.
class SignatureReader {
 public:
  explicit SignatureReader(std::string_view text) : rest_(text) {}
  bool skip(std::string_view piece) {
    if (!ok_ || !rest_.starts_with(piece)) return false;
    rest_.remove_prefix(piece.size());
    return true;
  }
  void expect(std::string_view piece) { ok_ = skip(piece); }
  // from_chars, not strtod: "0x0.4" (a box of length 0) is not hexadecimal.
  double number() {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(rest_.data(), rest_.data() + rest_.size(), v);
    if (!ok_ || ec != std::errc() || !std::isfinite(v)) {
      ok_ = false;
      return 0.0;
    }
    rest_.remove_prefix(static_cast<std::size_t>(end - rest_.data()));
    return v;
  }
  bool done() const { return ok_ && rest_.empty(); }

 private:
  std::string_view rest_;
  bool ok_ = true;
};

}  // namespace

// The writer stays the one description of the format: what is read is
// written again and must come out the same.
std::optional<RobotSpec> robotFromSignature(std::string_view signature) {
  SignatureReader in(signature);
  RobotSpec spec;
  if (in.skip(kDiscPrefix)) {
    spec.shape = MobileShape::Disc;
    spec.radius = in.number();
  } else if (in.skip(kBoxPrefix)) {
    spec.shape = MobileShape::Box;
    spec.box_size.x = in.number();
    in.expect("x");
    spec.box_size.y = in.number();
  } else if (in.skip(kArmPrefix)) {
    spec.kind = RobotKind::Manipulator;
    do {
      spec.links.push_back(in.number());
    } while (in.skip(","));
    in.expect(kArmRadius);
    spec.link_radius = in.number();
    in.expect(kArmLimits);
    do {
      const double lo = in.number();
      in.expect("/");
      spec.joint_limits.emplace_back(lo, in.number());
    } while (in.skip(","));
  }
  if (!in.done()) return std::nullopt;
  try {
    if (makeRobotModel(spec, Resolution{})->geometrySignature() != signature) return std::nullopt;
  } catch (const std::invalid_argument&) {
    return std::nullopt;  // a negative radius, limits lo > hi, ...
  }
  return spec;
}

// A box holding the robot's bodies at every configuration q with lo[i]
// <= q[i] <= hi[i] for each coordinate, for broad phases over many
// instants at once; it may be larger than the tightest such box. By
// default the bounding disc around every centre in the box (for a
// mobile robot its positions, whatever the heading).
geo::Aabb RobotModel::boundsWithin(const double* lo, const double* hi) const {
  const double r = boundingRadius() * (1.0 + 1e-9) + 1e-9;
  if (!center_is_position_) return geo::Aabb{fixed_center_, fixed_center_}.inflated(r);
  return geo::Aabb{{lo[0], lo[1]}, {hi[0], hi[1]}}.inflated(r);
}

int RobotModel::stepsBetween(const double* a, const double* b) const {
  const double d = distance(a, b);
  if (!(d >= 0.0) || d > static_cast<double>(INT_MAX))
    throw NoStepCountError("robot '" + spec_.name + "': no finite step count between these configurations");
  if (d == 0.0) return 0;
  return std::max(1, static_cast<int>(std::ceil(d - kStepSlack)));
}

std::unique_ptr<RobotModel> makeRobotModel(const RobotSpec& spec, const Resolution& res) {
  requirePositive(res.translation, "translation");
  requirePositive(res.rotation, "rotation");
  requirePositive(res.joint, "joint");
  if (spec.kind == RobotKind::Mobile) return std::make_unique<MobileRobot>(spec, res);
  return std::make_unique<ArmRobot>(spec, res);
}

std::vector<std::shared_ptr<const RobotModel>> makeRobotModels(const Scenario& scenario) {
  std::vector<std::shared_ptr<const RobotModel>> models;
  models.reserve(scenario.robots.size());
  for (const auto& spec : scenario.robots) models.push_back(makeRobotModel(spec, scenario.resolution));
  return models;
}

RobotModels::RobotModels(const Scenario& scenario) : owned(makeRobotModels(scenario)) {
  raw.reserve(owned.size());
  for (const auto& m : owned) raw.push_back(m.get());
}

void armJointPositions(const RobotSpec& arm, const double* q, std::vector<geo::Vec2>& out) {
  out.clear();
  out.push_back(arm.base_position);
  walkArm(arm, q, [&](std::size_t, geo::Vec2, geo::Vec2 to) { out.push_back(to); });
}

// A solver's interpolation or OMPL's wrapped headings leave a robot waiting
// at its goal on a state that differs from the exact goal by rounding or by
// 2 pi, and the exact goal only at the very end: without this its cost ran
// to the makespan.
void settleAtGoal(const RobotModel& model, Path& path) {
  constexpr double kSame = 1e-6;  // in steps of the robot's resolution
  if (path.size() < 2) return;
  const std::size_t last = path.size() - 1;
  std::size_t k = last;
  while (k > 0 && model.distance(path.at(k - 1), path.at(last)) < kSame) --k;
  for (std::size_t t = k; t < last; ++t) std::copy_n(path.at(last), path.dim(), path.mutableAt(t));
}

}  // namespace earc
