// The picture's robots, paths and labels.
#include "svg_parts.hpp"

namespace earc::render::svg_detail {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  std::string s(buf);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

// One colour per robot: 20 colours chosen greedily, each as far as it can
// be (CIELAB) from those before it, from obstacle grey and from white:
// any two of them differ by a CIELAB distance of 33 or more, and two in a
// row by 43 or more, so a 21st robot repeats the first colour but next
// to neighbours of other colours. (Hues a golden angle apart made robots
// 6 and 14 both green, 7 apart.) tools/viewer/viewer.js has the same list.
std::string robotColour(std::size_t i) {
  static const char* const kPalette[] = {"#d62728", "#0000ff", "#00b400", "#ff00c3", "#0069e1", "#c39600", "#0fb487",
                                         "#961e5a", "#3c5a00", "#00a5e1", "#7800b4", "#783c0f", "#d287e1", "#f08787",
                                         "#ff0078", "#ff7800", "#5a4b87", "#e100ff", "#87a500", "#b4965a"};
  return kPalette[i % std::size(kPalette)];
}

double textWidth(std::string_view text, double font_px) {
  const auto glyphs = std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; });
  return static_cast<double>(glyphs) * 0.6 * font_px;
}

double segmentDistance(geo::Vec2 p, geo::Vec2 a, geo::Vec2 b) {
  const geo::Vec2 d = b - a;
  const double dd = geo::dot(d, d);
  const double t = dd > 0 ? std::clamp(geo::dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
  return geo::norm(p - (a + d * t));
}

std::ostream& operator<<(std::ostream& out, Pt q) { return out << num(q.p.x) << ',' << num(q.p.y); }

std::ostream& operator<<(std::ostream& out, const Paint& p) {
  return p.attributes.empty() ? out : out << ' ' << p.attributes;
}

std::array<geo::Vec2, 4> boxCorners(const View& v, const geo::Body& b) {
  const geo::Vec2 ax = b.axis * b.half.x, ay = geo::perp(b.axis) * b.half.y;
  return {v(b.p0 + ax + ay), v(b.p0 - ax + ay), v(b.p0 - ax - ay), v(b.p0 + ax - ay)};
}

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

// A heading mark: an arrowhead inside the body's front, pointing along
// `dir` (a unit vector on the picture), its tip `reach` pixels from the
// centre and its base 0.45 of that: it stays clear of the centre, where
// the path ends, so that it does not read as the path's last bend (a
// line from the centre did).
std::string arrowhead(geo::Vec2 centre, geo::Vec2 dir, double reach) {
  const geo::Vec2 tip = centre + dir * reach, base = centre + dir * (0.45 * reach), side = geo::perp(dir) * (0.3 * reach);
  std::ostringstream points;
  points << Pt{tip} << ' ' << Pt{base + side} << ' ' << Pt{base - side};
  return points.str();
}

std::string opacityAttribute(double opacity) {
  return opacity < 1.0 ? " opacity=\"" + num(opacity) + "\"" : std::string();
}

double mobileGrowth(const RobotModel& m, const View& v, const Style& st) {
  const double across = 2.0 * m.boundingRadius() * v.scale;
  return m.isMobile() && across < st.minRobotAcross() ? st.minRobotAcross() / across : 1.0;
}

double drawnLinkRadius(const RobotModel& m, const View& v, const Style& st) {
  return std::max(m.spec().link_radius, 0.5 * st.minLinkWidth() / v.scale);
}

bool drawnEnlarged(const RobotModel& m, const View& v, const Style& st) {
  return m.isMobile() ? mobileGrowth(m, v, st) > 1.0 : drawnLinkRadius(m, v, st) > m.spec().link_radius;
}

void writePose(std::ostream& out, const View& v, const Style& st, const RobotModel& m, const double* q, bool filled,
               double opacity) {
  std::vector<geo::Body> bodies;
  m.bodies(q, bodies);
  const double growth = mobileGrowth(m, v, st), link_radius = m.isMobile() ? 0.0 : drawnLinkRadius(m, v, st);
  for (auto& b : bodies) {
    if (growth > 1.0) {  // about the robot's centre
      const geo::Vec2 c = m.boundingCenter(q);
      b.p0 = c + (b.p0 - c) * growth;
      b.p1 = c + (b.p1 - c) * growth;
      b.half = b.half * growth;
      b.radius *= growth;
    }
    if (!m.isMobile()) b.radius = link_radius;
  }
  const std::string fade = opacityAttribute(opacity);
  const Paint paint{(filled ? "stroke=\"#222\" stroke-width=\"" + num(0.6 * st.outline()) + "\""
                            : "fill=\"none\" stroke-width=\"" + num(st.outline()) + "\" stroke-dasharray=\"" +
                                  st.dashes() + "\"") +
                    fade};
  for (const auto& b : bodies) writeBody(out, v, b, paint);
  if (m.isMobile()) {
    const RobotSpec& s = m.spec();
    const double reach = growth * (s.shape == MobileShape::Disc ? s.radius : 0.5 * s.box_size.x);
    out << "<polygon class=\"heading\" points=\""
        << arrowhead(v({q[0], q[1]}), {std::cos(q[2]), -std::sin(q[2])}, reach * v.scale)
        << "\" fill=\"#222\" stroke=\"none\"" << fade << "/>";
    return;
  }
  std::vector<geo::Vec2> joints;
  armJointPositions(m.spec(), q, joints);
  const double r = std::max(st.px(1.0), 0.5 * link_radius * v.scale);
  for (std::size_t k = 0; k + 1 < joints.size(); ++k) {  // the base larger; the tip has no joint
    const geo::Vec2 c = v(joints[k]);
    out << "<circle cx=\"" << num(c.x) << "\" cy=\"" << num(c.y) << "\" r=\"" << num(k == 0 ? 2.0 * r : r)
        << "\" fill=\"#222\"" << fade << "/>";
  }
}

geo::Vec2 tracePoint(const RobotModel& m, const double* q, std::vector<geo::Vec2>& scratch) {
  if (m.isMobile()) return {q[0], q[1]};
  armJointPositions(m.spec(), q, scratch);
  return scratch.back();
}

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

std::vector<geo::Vec2> tracePoints(const RobotModel& m, const Path& path, const View& v) {
  std::vector<geo::Vec2> pts, scratch;
  pts.reserve(path.size());
  for (std::size_t t = 0; t < path.size(); ++t) pts.push_back(v(tracePoint(m, path.at(t), scratch)));
  return pts;
}

void writePathLine(std::ostream& out, const Style& st, const std::vector<geo::Vec2>& pts, std::size_t from,
                   std::size_t to, const char* cls, double tolerance) {
  const bool ahead = std::string_view(cls) == "path-ahead";
  out << "<polyline class=\"" << cls << "\" fill=\"none\" stroke-width=\"" << num(st.pathStroke()) << '"';
  if (ahead) out << " stroke-dasharray=\"" << st.aheadDashes() << '"' << opacityAttribute(kAheadOpacity);
  out << " stroke-linejoin=\"round\" points=\"";
  const std::vector<geo::Vec2> part(pts.begin() + static_cast<std::ptrdiff_t>(from),
                                    pts.begin() + static_cast<std::ptrdiff_t>(to) + 1);
  const char* gap = "";
  for (const auto& p : decimatePolyline(part, tolerance)) out << std::exchange(gap, " ") << Pt{p};
  out << "\"/>\n";
}

void writeLabel(std::ostream& out, const View& v, const Style& st, const std::string& text, geo::Vec2 at,
                double font_px, const char* fill) {
  const double w = textWidth(text, font_px), right = 2.0 * v.left + v.width();
  const double x = std::max(2.0, std::min(at.x - w / 2, right - 2.0 - w));
  const double y = std::clamp(at.y, v.top + font_px, v.top + v.height() - 2.0);
  out << "<text class=\"label\" x=\"" << num(x) << "\" y=\"" << num(y) << "\"";
  if (font_px != st.font()) out << " font-size=\"" << num(font_px) << '"';
  out << " fill=\"" << fill << "\" stroke=\"#fff\" stroke-width=\"" << num(st.halo()) << "\" stroke-linejoin=\"round\" "
      << "paint-order=\"stroke\">" << xmlText(text) << "</text>";
}

const double* poseAt(const RobotSpec& r, const Path* path, const std::size_t* step) {
  return step && path ? path->at(*step) : r.start.data();
}

// One robot's group in one panel: its path (at a step: the part travelled
// solid, the part to go dashed and faded), goal (outlined), start (solid,
// faded when a step is drawn) and its pose at *step if given.
// `trace`: tracePoints of its path, empty when it has none.
void writeRobot(std::ostream& out, const View& v, const Style& st, const RobotModel& m, std::size_t index,
                const std::vector<geo::Vec2>& trace, const Path* path, const std::size_t* step, double tolerance) {
  const RobotSpec& r = m.spec();
  const std::string colour = robotColour(index);
  out << "<g class=\"robot\" data-robot=\"" << xmlText(r.name) << "\" fill=\"" << colour << "\" stroke=\"" << colour
      << "\">\n";
  if (!trace.empty()) {
    const std::size_t last = trace.size() - 1, t = step ? std::min(*step, last) : last;
    if (t > 0 || !step) writePathLine(out, st, trace, 0, t, "path", tolerance);
    if (t < last) writePathLine(out, st, trace, t, last, "path-ahead", tolerance);
  }
  writePose(out, v, st, m, r.goal.data(), false, 1.0);
  writePose(out, v, st, m, r.start.data(), true, step ? kFadedOpacity : 1.0);
  if (step) writePose(out, v, st, m, poseAt(r, path, step), true, 1.0);
  out << "\n</g>\n";
}

geo::Vec2 besideAt(geo::Vec2 from, geo::Vec2 dir, double gap, double w, double h) {
  return from + dir * (gap + std::abs(dir.x) * w / 2 + std::abs(dir.y) * h / 2);
}

// A robot's names in one panel, each on a white halo so that it reads
// over paint, moved inside the panel near its edges. A mobile robot's
// name is above it (at q) and, small, below its goal. An arm's name is
// beside its base on the side away from its links at its start, goal and
// q (above the base, the links ran through it), and its goal's name
// past the goal pose's tip, along the last link.
void writeLabels(std::ostream& out, const View& v, const Style& st, const RobotModel& m, const double* q) {
  const RobotSpec& r = m.spec();
  if (m.isMobile()) {
    const double body = mobileGrowth(m, v, st) * m.boundingRadius() * v.scale;
    writeLabel(out, v, st, r.name, v(m.boundingCenter(q)) - geo::Vec2{0, body + st.px(3.0)}, st.font(), "#000");
    writeLabel(out, v, st, r.name, v(m.boundingCenter(r.goal.data())) + geo::Vec2{0, body + st.goalFont() + st.px(1.0)},
               st.goalFont(), "#333");
    return;
  }
  std::vector<geo::Vec2> joints;
  geo::Vec2 links{0, 0};  // the sum of the joints' offsets from the base, on the picture
  for (const double* pose : {r.start.data(), r.goal.data(), q}) {
    armJointPositions(r, pose, joints);
    for (std::size_t k = 1; k < joints.size(); ++k) links = links + (v(joints[k]) - v(joints[0]));
  }
  const double far = geo::norm(links), thick = drawnLinkRadius(m, v, st) * v.scale;
  const geo::Vec2 away = far > 1e-9 ? links * (-1.0 / far) : geo::Vec2{0, 1};
  // A label's box: its width, and its height from the baseline up (names
  // mostly lack descenders); `at` below is the baseline's middle.
  auto placed = [&](const std::string& text, double font, geo::Vec2 from, geo::Vec2 dir, double gap) {
    const double h = 0.75 * font;
    return besideAt(from, dir, gap, textWidth(text, font), h) + geo::Vec2{0, h / 2};
  };
  // The base's disc is twice a joint's (writePose).
  const double base_r = 2.0 * std::max(st.px(1.0), 0.5 * thick);
  writeLabel(out, v, st, r.name, placed(r.name, st.font(), v(r.base_position), away, base_r + st.px(3.0)), st.font(),
             "#000");
  armJointPositions(r, r.goal.data(), joints);
  const geo::Vec2 tip = v(joints.back()), last = tip - v(joints[joints.size() - 2]);
  const double len = geo::norm(last);
  const geo::Vec2 along = len > 1e-9 ? last * (1.0 / len) : away;
  writeLabel(out, v, st, r.name, placed(r.name, st.goalFont(), tip, along, thick + st.px(2.0)), st.goalFont(), "#333");
}

}  // namespace earc::render::svg_detail
