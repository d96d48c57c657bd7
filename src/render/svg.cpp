#include "earc/render/svg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <sstream>

#include "earc/scene/robot_model.hpp"
#include "earc/util/format.hpp"

namespace earc::render {

namespace {

constexpr double kPaddingPx = 12.0;
constexpr double kTitlePx = 22.0;   // band above each panel for its title
constexpr double kPanelGapPx = 16.0;
constexpr double kPathStrokePx = 1.5;
constexpr double kOutlinePx = 1.2;
constexpr double kFontPx = 11.0;
constexpr double kFadedOpacity = 0.35;  // the start pose when a later step is drawn

// Pixel coordinates are written with two decimals at most: finer is
// invisible and only makes the file bigger.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  std::string s(buf);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

// Well-separated colours: hues a golden angle apart, as #rrggbb.
std::string robotColour(std::size_t i) {
  const double h = std::fmod(static_cast<double>(i) * 137.50776405, 360.0) / 60.0;
  const double s = 0.7, l = i % 2 == 0 ? 0.42 : 0.55;
  const double c = (1.0 - std::abs(2.0 * l - 1.0)) * s;
  const double x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
  double rgb[3] = {0, 0, 0};
  const int sector = static_cast<int>(h) % 6;
  const int order[6][3] = {{0, 1, 2}, {1, 0, 2}, {2, 0, 1}, {2, 1, 0}, {1, 2, 0}, {0, 2, 1}};
  const double parts[3] = {c, x, 0.0};
  for (int k = 0; k < 3; ++k) rgb[k] = parts[order[sector][k]];
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(std::lround((rgb[0] + l - c / 2) * 255)),
                static_cast<int>(std::lround((rgb[1] + l - c / 2) * 255)),
                static_cast<int>(std::lround((rgb[2] + l - c / 2) * 255)));
  return buf;
}

double segmentDistance(geo::Vec2 p, geo::Vec2 a, geo::Vec2 b) {
  const geo::Vec2 d = b - a;
  const double dd = geo::dot(d, d);
  const double t = dd > 0 ? std::clamp(geo::dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
  return geo::norm(p - (a + d * t));
}

// World to picture coordinates of one panel: scaled, y flipped, offset.
struct View {
  geo::Aabb world;
  double scale = 1.0;
  double left = 0.0;
  double top = 0.0;
  geo::Vec2 operator()(geo::Vec2 p) const {
    return {left + (p.x - world.lo.x) * scale, top + (world.hi.y - p.y) * scale};
  }
  double height() const { return (world.hi.y - world.lo.y) * scale; }
  double width() const { return (world.hi.x - world.lo.x) * scale; }
};

// Streams "x,y" of a picture point.
struct Pt {
  geo::Vec2 p;
};
std::ostream& operator<<(std::ostream& out, Pt q) { return out << num(q.p.x) << ',' << num(q.p.y); }

// How a body is painted: its attributes, written inside the element.
struct Paint {
  std::string attributes;
};
std::ostream& operator<<(std::ostream& out, const Paint& p) {
  return p.attributes.empty() ? out : out << ' ' << p.attributes;
}

// A box's corners in picture coordinates, counterclockwise on the picture.
std::array<geo::Vec2, 4> boxCorners(const View& v, const geo::Body& b) {
  const geo::Vec2 ax = b.axis * b.half.x, ay = geo::perp(b.axis) * b.half.y;
  return {v(b.p0 + ax + ay), v(b.p0 - ax + ay), v(b.p0 - ax - ay), v(b.p0 + ax - ay)};
}

// One body's outline as path data ("M... Z"), counterclockwise on the
// picture whatever the body: outlines drawn in one path then overlap
// filled under the nonzero rule (a turn the other way would cut a hole).
std::string outlinePath(const View& v, const geo::Body& b) {
  const double r = b.radius * v.scale;
  std::ostringstream d;
  // In picture coordinates (y down) sweep flag 0 turns counterclockwise.
  const std::string arc = " A" + num(r) + "," + num(r) + " 0 0 0 ";
  switch (b.kind) {
    case geo::CoreKind::Point: {
      const geo::Vec2 c = v(b.p0), e{r, 0};
      d << 'M' << Pt{c + e} << arc << Pt{c - e} << arc << Pt{c + e} << 'Z';
      break;
    }
    case geo::CoreKind::Segment: {
      const geo::Vec2 a = v(b.p0), e = v(b.p1);
      const double len = geo::norm(e - a);
      if (len < 1e-9) return outlinePath(v, geo::Body::disc(b.p0, b.radius));
      // A capsule: two sides and two half circles.
      const geo::Vec2 n = geo::perp((e - a) * (1.0 / len)) * r;
      d << 'M' << Pt{a + n} << " L" << Pt{e + n} << arc << Pt{e - n} << " L" << Pt{a - n} << arc << Pt{a + n} << 'Z';
      break;
    }
    case geo::CoreKind::Rect: {
      const auto c = boxCorners(v, b);
      d << 'M' << Pt{c[0]} << " L" << Pt{c[1]} << " L" << Pt{c[2]} << " L" << Pt{c[3]} << 'Z';
      break;
    }
  }
  return d.str();
}

// One body as an SVG element.
void writeBody(std::ostream& out, const View& v, const geo::Body& b, const Paint& paint) {
  switch (b.kind) {
    case geo::CoreKind::Point: {
      const geo::Vec2 c = v(b.p0);
      out << "<circle cx=\"" << num(c.x) << "\" cy=\"" << num(c.y) << "\" r=\"" << num(b.radius * v.scale) << '"'
          << paint << "/>";
      return;
    }
    case geo::CoreKind::Segment:
      out << "<path d=\"" << outlinePath(v, b) << '"' << paint << "/>";
      return;
    case geo::CoreKind::Rect: {
      const auto c = boxCorners(v, b);
      out << "<polygon points=\"" << Pt{c[0]} << ' ' << Pt{c[1]} << ' ' << Pt{c[2]} << ' ' << Pt{c[3]} << '"' << paint
          << "/>";
      return;
    }
  }
}

std::string opacityAttribute(double opacity) {
  return opacity < 1.0 ? " opacity=\"" + num(opacity) + "\"" : std::string();
}

// A robot at q: its bodies filled (with a thin dark edge) or outlined
// (dashed), plus its heading (mobile) or its joints (arm).
void writePose(std::ostream& out, const View& v, const RobotModel& m, const double* q, bool filled,
               double opacity) {
  std::vector<geo::Body> bodies;
  m.bodies(q, bodies);
  const std::string fade = opacityAttribute(opacity);
  const Paint paint{(filled ? "stroke=\"#222\" stroke-width=\"" + num(0.6 * kOutlinePx) + "\""
                            : "fill=\"none\" stroke-width=\"" + num(kOutlinePx) + "\" stroke-dasharray=\"3,2\"") +
                    fade};
  for (const auto& b : bodies) writeBody(out, v, b, paint);
  if (m.isMobile()) {
    const RobotSpec& s = m.spec();
    const double reach = s.shape == MobileShape::Disc ? s.radius : 0.5 * s.box_size.x;
    const geo::Vec2 a = v({q[0], q[1]}), b = v({q[0] + reach * std::cos(q[2]), q[1] + reach * std::sin(q[2])});
    out << "<line x1=\"" << num(a.x) << "\" y1=\"" << num(a.y) << "\" x2=\"" << num(b.x) << "\" y2=\"" << num(b.y)
        << "\" stroke=\"#222\" stroke-width=\"" << num(kOutlinePx) << '"' << fade << "/>";
    return;
  }
  std::vector<geo::Vec2> joints;
  armJointPositions(m.spec(), q, joints);
  const double r = std::max(1.0, 0.5 * m.spec().link_radius * v.scale);
  for (std::size_t k = 0; k + 1 < joints.size(); ++k) {  // the base larger; the tip has no joint
    const geo::Vec2 c = v(joints[k]);
    out << "<circle cx=\"" << num(c.x) << "\" cy=\"" << num(c.y) << "\" r=\"" << num(k == 0 ? 2.0 * r : r)
        << "\" fill=\"#222\"" << fade << "/>";
  }
}

// The point a robot's path follows: the reference point or the arm's tip.
geo::Vec2 tracePoint(const RobotModel& m, const double* q, std::vector<geo::Vec2>& scratch) {
  if (m.isMobile()) return {q[0], q[1]};
  armJointPositions(m.spec(), q, scratch);
  return scratch.back();
}

// The path of each scenario robot, found by name (nullptr: none drawn).
std::vector<const Path*> pathsByRobot(const Scenario& sc, const Solution& sol) {
  std::vector<const Path*> out(sc.robots.size(), nullptr);
  for (std::size_t k = 0; k < sol.paths.size(); ++k) {
    std::size_t i = k;
    if (!sol.robot_names.empty()) {
      i = 0;
      while (i < sc.robots.size() && sc.robots[i].name != sol.robot_names[k]) ++i;
    }
    if (i < sc.robots.size() && !sol.paths[k].empty() && sol.paths[k].dim() == sc.robots[i].dim())
      out[i] = &sol.paths[k];
  }
  return out;
}

// A path as a polyline in picture coordinates ("x,y x,y ...").
std::string polyline(const RobotModel& m, const Path& path, const View& v, double tolerance) {
  std::vector<geo::Vec2> pts, scratch;
  pts.reserve(path.size());
  for (std::size_t t = 0; t < path.size(); ++t) pts.push_back(v(tracePoint(m, path.at(t), scratch)));
  std::ostringstream line;
  for (const auto& p : decimatePolyline(pts, tolerance)) line << (line.tellp() > 0 ? " " : "") << Pt{p};
  return line.str();
}

// One robot's group in one panel: its path, goal (outlined), start (solid,
// faded when a step is drawn), its pose at *step if given, and its name.
void writeRobot(std::ostream& out, const View& v, const RobotModel& m, std::size_t index, const std::string& polyline,
                const Path* path, const std::size_t* step, bool labels) {
  const RobotSpec& r = m.spec();
  const std::string colour = robotColour(index);
  out << "<g class=\"robot\" data-robot=\"" << xmlText(r.name) << "\" fill=\"" << colour << "\" stroke=\"" << colour
      << "\">\n";
  if (!polyline.empty())
    out << "<polyline class=\"path\" fill=\"none\" stroke-width=\"" << num(kPathStrokePx)
        << "\" stroke-linejoin=\"round\" points=\"" << polyline << "\"/>\n";
  writePose(out, v, m, r.goal.data(), false, 1.0);
  writePose(out, v, m, r.start.data(), true, step ? kFadedOpacity : 1.0);
  const double* now = r.start.data();  // where the name goes
  if (step) {
    if (path) now = path->at(*step);
    writePose(out, v, m, now, true, 1.0);
  }
  if (labels) {
    const geo::Vec2 c = v(m.boundingCenter(now));
    out << "<text x=\"" << num(c.x) << "\" y=\"" << num(c.y - 4.0) << "\" stroke=\"none\" fill=\"#000\">"
        << xmlText(r.name) << "</text>";
  }
  out << "\n</g>\n";
}

std::string render(const Scenario& sc, const Solution* sol, const SvgOptions& o) {
  const auto models = makeRobotModels(sc);
  std::vector<std::size_t> steps = sol ? o.steps : std::vector<std::size_t>{};
  const bool timed = !steps.empty();
  if (!timed) steps.push_back(0);

  View v;
  v.world = sc.workspace;
  v.scale = (o.panel_width_px - 2.0 * kPaddingPx) / (sc.workspace.hi.x - sc.workspace.lo.x);
  v.left = kPaddingPx;  // in panel coordinates: each panel is translated into place
  v.top = kTitlePx + kPaddingPx;
  const double panel_h = v.top + v.height() + kPaddingPx;
  const double total_w = static_cast<double>(steps.size()) * (o.panel_width_px + kPanelGapPx) - kPanelGapPx;
  const std::vector<const Path*> paths = sol ? pathsByRobot(sc, *sol) : std::vector<const Path*>(sc.robots.size());
  std::vector<std::string> polylines(sc.robots.size());  // the same in every panel
  for (std::size_t i = 0; i < sc.robots.size(); ++i)
    if (paths[i]) polylines[i] = polyline(*models[i], *paths[i], v, o.tolerance_px);

  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(total_w) << "\" height=\"" << num(panel_h)
      << "\" viewBox=\"0 0 " << num(total_w) << ' ' << num(panel_h) << "\" font-family=\"sans-serif\" font-size=\""
      << num(kFontPx) << "\">\n<title>" << xmlText(sc.name) << "</title>\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  for (std::size_t k = 0; k < steps.size(); ++k) {
    out << "<g class=\"panel\" transform=\"translate(" << num(static_cast<double>(k) * (o.panel_width_px + kPanelGapPx))
        << ",0)\">\n<text x=\"" << num(v.left) << "\" y=\"" << num(kTitlePx - 6.0) << "\" font-size=\""
        << num(kFontPx + 3) << "\">" << xmlText(sc.name);
    if (timed) out << "  t = " << steps[k];
    out << "</text>\n<rect class=\"workspace\" x=\"" << num(v.left) << "\" y=\"" << num(v.top) << "\" width=\""
        << num(v.width()) << "\" height=\"" << num(v.height()) << "\" fill=\"#fafafa\" stroke=\"#000\" stroke-width=\""
        << num(kOutlinePx) << "\"/>\n";
    // All obstacles are one path, filled as their union: filled one by
    // one, adjacent boxes (merged map cells) each anti-alias their shared
    // edge and leave a light hairline seam along it, stroke or not. The
    // thin stroke of the fill keeps obstacles thinner than a pixel seen.
    if (!sc.obstacles.empty()) {
      out << "<path class=\"obstacles\" fill=\"#666\" stroke=\"#666\" stroke-width=\"0.6\" d=\"";
      for (std::size_t i = 0; i < sc.obstacles.size(); ++i) out << (i ? "\n" : "") << outlinePath(v, sc.obstacles[i].body());
      out << "\"/>\n";
    }
    for (std::size_t i = 0; i < sc.robots.size(); ++i)
      writeRobot(out, v, *models[i], i, polylines[i], paths[i], timed ? &steps[k] : nullptr, o.labels);
    out << "</g>\n";
  }
  out << "</svg>\n";
  return out.str();
}

}  // namespace

std::vector<geo::Vec2> decimatePolyline(const std::vector<geo::Vec2>& pts, double tolerance) {
  if (pts.size() <= 2) return pts;
  std::vector<char> keep(pts.size(), 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> todo{{0, pts.size() - 1}};
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    double worst = -1.0;
    std::size_t at = a;
    for (std::size_t k = a + 1; k < b; ++k) {
      const double d = segmentDistance(pts[k], pts[a], pts[b]);
      if (d > worst) worst = d, at = k;
    }
    if (worst > tolerance) {
      keep[at] = 1;
      todo.push_back({a, at});
      todo.push_back({at, b});
    }
  }
  std::vector<geo::Vec2> out;
  for (std::size_t k = 0; k < pts.size(); ++k)
    if (keep[k]) out.push_back(pts[k]);
  return out;
}

std::string scenarioSvg(const Scenario& scenario, const SvgOptions& options) {
  return render(scenario, nullptr, options);
}

std::string solutionSvg(const Scenario& scenario, const Solution& solution, const SvgOptions& options) {
  return render(scenario, &solution, options);
}

}  // namespace earc::render
