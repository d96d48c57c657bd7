#include "earc/render/svg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <ostream>
#include <sstream>
#include <string_view>
#include <utility>

#include "earc/scene/robot_model.hpp"
#include "earc/util/format.hpp"

namespace earc::render {

namespace {

constexpr double kPaddingPx = 12.0;
constexpr double kPanelGapPx = 16.0;
constexpr double kFadedOpacity = 0.35;  // the start pose when a later step is drawn
constexpr double kAheadOpacity = 0.5;   // a path's part still to go at a step

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

// The sizes of text, marks and lines, in pixels: an 800-pixel panel's,
// scaled with the panel's width so that a picture reads alike at any
// --width (fixed sizes made the text of a 4000-pixel picture a speck seen
// whole, and crowded a 400-pixel one). The scale stays within 0.85 and 5,
// and no text is smaller than 8 pixels, about the least that reads on a
// screen.
struct Style {
  explicit Style(double panel_width_px) : u(std::clamp(panel_width_px / 800.0, 0.85, 5.0)) {}
  double u;  // the scale
  double px(double at_800) const { return at_800 * u; }
  double text(double at_800) const { return std::max(8.0, at_800 * u); }

  double font() const { return text(11.0); }      // names and the key
  double goalFont() const { return text(8.5); }   // a goal's name
  double titleFont() const { return text(14.0); }  // a panel's title
  double factsFont() const { return text(12.0); }  // the plan's facts under the titles
  double titleBand() const { return titleFont() + px(8.0); }  // above each panel, for its title
  double factsLine() const { return factsFont() + px(3.0); }
  double keyRow() const { return font() + px(5.0); }
  double keyGlyph() const { return font() * 14.0 / 11.0; }  // a key mark's width
  double keyGap() const { return keyGlyph(); }              // between key entries
  double pathStroke() const { return px(1.5); }
  double outline() const { return px(1.2); }
  double halo() const { return 2.5 * font() / 11.0; }  // the white edge around a label
  std::string dashes() const { return num(px(3)) + "," + num(px(2)); }
  std::string aheadDashes() const { return num(px(5)) + "," + num(px(3.5)); }  // a path's part to go
  // The least a robot is drawn, in whole pixels, so that robots do not
  // vanish on a large map (on den520d at 800 pixels a 0.6 x 0.4 box is
  // 2 pixels long): a mobile robot this wide across its bounding circle,
  // an arm's links this thick. Larger ones are drawn true to scale.
  double minRobotAcross() const { return std::round(px(9.0)); }
  double minLinkWidth() const { return std::max(1.0, std::round(px(2.0))); }
};

// Roughly how wide a line of text is drawn: a sans-serif glyph averages
// about 0.6 of the font size (a code point, not a byte, is a glyph).
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

// How many times its true size a mobile robot is drawn: 1, or more for
// one smaller than st.minRobotAcross().
double mobileGrowth(const RobotModel& m, const View& v, const Style& st) {
  const double across = 2.0 * m.boundingRadius() * v.scale;
  return m.isMobile() && across < st.minRobotAcross() ? st.minRobotAcross() / across : 1.0;
}

// The radius an arm's links are drawn with: their own, or more for links
// thinner than st.minLinkWidth().
double drawnLinkRadius(const RobotModel& m, const View& v, const Style& st) {
  return std::max(m.spec().link_radius, 0.5 * st.minLinkWidth() / v.scale);
}

// Whether a robot is drawn larger than it is (see Style::minRobotAcross).
bool drawnEnlarged(const RobotModel& m, const View& v, const Style& st) {
  return m.isMobile() ? mobileGrowth(m, v, st) > 1.0 : drawnLinkRadius(m, v, st) > m.spec().link_radius;
}

// A robot at q: its bodies filled (with a thin dark edge) or outlined
// (dashed), plus its heading (mobile) or its joints (arm); no smaller
// than the style's least sizes.
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

// The point a path follows at each step, in picture coordinates.
std::vector<geo::Vec2> tracePoints(const RobotModel& m, const Path& path, const View& v) {
  std::vector<geo::Vec2> pts, scratch;
  pts.reserve(path.size());
  for (std::size_t t = 0; t < path.size(); ++t) pts.push_back(v(tracePoint(m, path.at(t), scratch)));
  return pts;
}

// Steps [from, to] of a path as a polyline (`cls` "path" or, dashed and
// faded, "path-ahead"), points within `tolerance` of the line dropped.
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

// `text` centred on `at` (its baseline), on a white halo, moved as little
// as needed to lie inside the panel's padding.
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

// Where a robot is drawn at *step: on its path, or at its start when no
// step is drawn or it has no path.
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

// The centre of a box w by h pixels that lies `gap` pixels beyond `from`
// in the direction `dir` (a unit vector on the picture).
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

// Items of the given widths laid out in rows no wider than `width`, `gap`
// apart: each row's item indices. An item wider than the width has a row
// of its own.
std::vector<std::vector<std::size_t>> flowRows(const std::vector<double>& widths, double gap, double width) {
  std::vector<std::vector<std::size_t>> rows;
  double used = 0.0;
  for (std::size_t i = 0; i < widths.size(); ++i) {
    if (rows.empty() || used + gap + widths[i] > width) {
      rows.emplace_back();
      used = -gap;
    }
    rows.back().push_back(i);
    used += gap + widths[i];
  }
  return rows;
}

const char* const kFactGap = " \u00b7 ";  // between the facts of a line: spaces alone collapse to one

// What the solution file says, one fact each: method, solved or why not,
// makespan, sum of costs, planning time. A fact marked true is a failure.
std::vector<std::pair<std::string, bool>> solutionFacts(const Solution& sol) {
  std::vector<std::pair<std::string, bool>> facts;
  if (!sol.method.empty()) facts.emplace_back("method " + sol.method, false);
  if (sol.solved) {
    facts.emplace_back("solved", false);
  } else {
    const std::string why = failureReasons(sol.stats);
    facts.emplace_back("not solved" + (why.empty() ? std::string() : ": " + why), true);
  }
  if (sol.hasPaths()) {
    facts.emplace_back("makespan " + std::to_string(sol.makespan()) + " steps", false);
    facts.emplace_back("sum of costs " + std::to_string(sol.sumOfCosts()), false);
  } else {
    facts.emplace_back("no paths: robots at their starts", true);
  }
  if (sol.stats.is_object() && sol.stats.contains("planning_time_s") && sol.stats["planning_time_s"].is_number())
    facts.emplace_back("planned in " + formatNumber("%.3g", sol.stats["planning_time_s"].get<double>()) + " s", false);
  // earc-plan plan --compact: what the plan was before it, or why the
  // compacted plan was not kept.
  const nlohmann::json* compact = sol.stats.is_object() && sol.stats.contains("compact") ? &sol.stats["compact"] : nullptr;
  if (compact && compact->is_object()) {
    if (compact->contains("rejected")) {
      const nlohmann::json& why = (*compact)["rejected"];  // a file's, whatever it holds
      facts.emplace_back("compaction undone: " + (why.is_string() ? why.get<std::string>() : why.dump()), false);
    } else if (compact->value("makespan_before", nlohmann::json()).is_number_integer() &&
             compact->value("sum_of_costs_before", nlohmann::json()).is_number_integer())
      facts.emplace_back("before --compact: makespan " + std::to_string((*compact)["makespan_before"].get<long long>()) +
                             ", sum of costs " + std::to_string((*compact)["sum_of_costs_before"].get<long long>()),
                         false);
  }
  return facts;
}

// The key's entries: what each mark of the picture means.
enum class KeyMark { Start, Now, FadedStart, Goal, Path, PathAhead, Heading, Joint, LeastRobot, LeastLink, Scale };

struct KeyEntry {
  KeyMark mark;
  std::string text;
  double glyph_px = 0.0;  // the mark's width; 0: st.keyGlyph()
};

// The scale bar's length: the longest 1, 2 or 5 times a power of ten that
// is at most a quarter of the workspace's width.
double scaleBarLength(double world_width) {
  const double most = world_width / 4, power = std::pow(10.0, std::floor(std::log10(most)));
  for (double f : {5.0, 2.0})
    if (f * power <= most * (1 + 1e-9)) return f * power;
  return power;
}

// What each mark of the picture means, and last a scale bar. `enlarged`:
// whether some robots are drawn larger than true, mobile robots and arms.
std::vector<KeyEntry> keyEntries(const Scenario& sc, const View& v, bool paths, bool timed, const Style& st,
                                 std::pair<bool, bool> enlarged) {
  std::vector<KeyEntry> keys;
  const double bar = scaleBarLength(v.world.hi.x - v.world.lo.x);
  const KeyEntry scale{KeyMark::Scale, formatNumber("%g", bar) + (bar == 1.0 ? " unit" : " units"), bar * v.scale};
  if (sc.robots.empty()) return {scale};
  auto isMobile = [](const RobotSpec& r) { return r.kind == RobotKind::Mobile; };
  const bool mobile = std::any_of(sc.robots.begin(), sc.robots.end(), isMobile);
  const bool arms = !std::all_of(sc.robots.begin(), sc.robots.end(), isMobile);
  if (timed) {
    keys.push_back({KeyMark::Now, "robot at t"});
    keys.push_back({KeyMark::FadedStart, "start"});
  } else {
    keys.push_back({KeyMark::Start, "start"});
  }
  keys.push_back({KeyMark::Goal, "goal"});
  if (paths && !timed) keys.push_back({KeyMark::Path, !arms ? "path" : mobile ? "path (arm: its tip)" : "path of the tip"});
  if (paths && timed) {
    keys.push_back({KeyMark::Path, !arms     ? "path travelled"
                                   : mobile ? "path travelled (arm: its tip)"
                                            : "tip's path travelled"});
    keys.push_back({KeyMark::PathAhead, arms && !mobile ? "tip's path to go" : "path to go"});
  }
  if (mobile) keys.push_back({KeyMark::Heading, "heading"});
  if (arms) keys.push_back({KeyMark::Joint, "base and joints"});
  if (enlarged.first)
    keys.push_back({KeyMark::LeastRobot,
                    "robots under " + num(st.minRobotAcross()) + " px drawn " + num(st.minRobotAcross()) + " px across"});
  if (enlarged.second)
    keys.push_back({KeyMark::LeastLink,
                    "links under " + num(st.minLinkWidth()) + " px drawn " + num(st.minLinkWidth()) + " px wide"});
  keys.push_back(scale);
  return keys;
}

// One key mark, `w` wide, its middle at (x, y).
void writeKeyMark(std::ostream& out, const Style& st, KeyMark mark, double x, double y, double w) {
  const double h = st.font() * 9.0 / 11.0, top = y - h / 2;
  const std::string box = "<rect x=\"" + num(x) + "\" y=\"" + num(top) + "\" width=\"" + num(w) + "\" height=\"" +
                          num(h) + "\" ";
  const std::string solid = "fill=\"#999\" stroke=\"#222\" stroke-width=\"" + num(0.6 * st.outline()) + "\"";
  switch (mark) {
    case KeyMark::Start:
    case KeyMark::Now:
      out << box << solid << "/>";
      break;
    case KeyMark::FadedStart:
      out << box << solid << opacityAttribute(kFadedOpacity) << "/>";
      break;
    case KeyMark::Goal:
      out << box << "fill=\"none\" stroke=\"#555\" stroke-width=\"" << num(st.outline()) << "\" stroke-dasharray=\""
          << st.dashes() << "\"/>";
      break;
    case KeyMark::Path:
    case KeyMark::PathAhead:
      out << "<line x1=\"" << num(x) << "\" y1=\"" << num(y) << "\" x2=\"" << num(x + w) << "\" y2=\"" << num(y)
          << "\" stroke=\"#555\" stroke-width=\"" << num(st.pathStroke()) << '"';
      if (mark == KeyMark::PathAhead) out << " stroke-dasharray=\"" << st.aheadDashes() << '"' << opacityAttribute(kAheadOpacity);
      out << "/>";
      break;
    case KeyMark::Heading:
      out << box << solid << "/><path d=\"M" << arrowhead({x + w / 2, y}, {1, 0}, w / 2)
          << "Z\" fill=\"#222\" stroke=\"none\"/>";
      break;
    case KeyMark::Joint:
      out << "<circle cx=\"" << num(x + w * 4 / 14) << "\" cy=\"" << num(y) << "\" r=\"" << num(w * 3 / 14)
          << "\" fill=\"#222\"/><circle cx=\"" << num(x + w * 11 / 14) << "\" cy=\"" << num(y) << "\" r=\""
          << num(w * 1.5 / 14) << "\" fill=\"#222\"/>";
      break;
    case KeyMark::LeastRobot:  // a disc that size
      out << "<circle cx=\"" << num(x + w / 2) << "\" cy=\"" << num(y) << "\" r=\"" << num(st.minRobotAcross() / 2)
          << "\" " << solid << "/>";
      break;
    case KeyMark::LeastLink:  // a link that thick
      out << "<line x1=\"" << num(x) << "\" y1=\"" << num(y) << "\" x2=\"" << num(x + w) << "\" y2=\"" << num(y)
          << "\" stroke=\"#999\" stroke-width=\"" << num(st.minLinkWidth()) << "\" stroke-linecap=\"round\"/>";
      break;
    case KeyMark::Scale:  // a bar with ends
      out << "<path class=\"scale-bar\" d=\"M" << Pt{{x, top}} << " V" << num(top + h) << " M" << Pt{{x, y}} << " H"
          << num(x + w) << " M" << Pt{{x + w, top}} << " V" << num(top + h) << "\" fill=\"none\" stroke=\"#222\" stroke-width=\""
          << num(st.outline()) << "\"/>";
      break;
  }
}

std::string render(const Scenario& sc, const Solution* sol, const SvgOptions& o) {
  const auto models = makeRobotModels(sc);
  const Style st(o.panel_width_px);
  std::vector<std::size_t> steps = sol ? o.steps : std::vector<std::size_t>{};
  const bool timed = !steps.empty();
  if (!timed) steps.push_back(0);
  const double total_w = pictureWidthPx(steps.size(), o.panel_width_px);
  const double text_w = total_w - 2.0 * kPaddingPx;

  // A plan's facts under the panel titles, as many lines as they need.
  const auto facts = sol ? solutionFacts(*sol) : std::vector<std::pair<std::string, bool>>{};
  std::vector<double> fact_w;
  for (const auto& f : facts) fact_w.push_back(textWidth(f.first, st.factsFont()));
  const auto fact_rows = flowRows(fact_w, textWidth(kFactGap, st.factsFont()), text_w);

  View v;
  v.world = sc.workspace;
  v.scale = (o.panel_width_px - 2.0 * kPaddingPx) / (sc.workspace.hi.x - sc.workspace.lo.x);
  v.left = kPaddingPx;  // in panel coordinates: each panel is translated into place
  v.top = st.titleBand() + static_cast<double>(fact_rows.size()) * st.factsLine() + kPaddingPx;
  const std::vector<const Path*> paths = sol ? pathsByRobot(sc, *sol) : std::vector<const Path*>(sc.robots.size());
  std::vector<std::vector<geo::Vec2>> traces(sc.robots.size());
  for (std::size_t i = 0; i < sc.robots.size(); ++i)
    if (paths[i]) traces[i] = tracePoints(*models[i], *paths[i], v);

  // The key below the drawing, never over it.
  std::pair<bool, bool> enlarged{false, false};
  for (const auto& m : models) (m->isMobile() ? enlarged.first : enlarged.second) |= drawnEnlarged(*m, v, st);
  auto keys = keyEntries(sc, v, std::any_of(paths.begin(), paths.end(), [](const Path* p) { return p; }), timed, st,
                         enlarged);
  std::vector<double> key_w;
  for (auto& k : keys) {
    if (k.glyph_px == 0.0) k.glyph_px = st.keyGlyph();
    key_w.push_back(k.glyph_px + st.px(4.0) + textWidth(k.text, st.font()));
  }
  const auto key_rows = flowRows(key_w, st.keyGap(), text_w);
  const double key_top = v.top + v.height() + st.px(8.0);
  const double panel_h = key_top + static_cast<double>(key_rows.size()) * st.keyRow() + kPaddingPx - st.px(8.0);

  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(total_w) << "\" height=\"" << num(panel_h)
      << "\" viewBox=\"0 0 " << num(total_w) << ' ' << num(panel_h) << "\" font-family=\"sans-serif\" font-size=\""
      << num(st.font()) << "\">\n<title>" << xmlText(sc.name) << "</title>\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  for (std::size_t r = 0; r < fact_rows.size(); ++r) {
    out << "<text class=\"facts\" x=\"" << num(kPaddingPx) << "\" y=\""
        << num(st.titleBand() - st.px(6.0) + st.factsLine() * (r + 1.0)) << "\" font-size=\"" << num(st.factsFont())
        << "\" fill=\"#444\">";
    for (std::size_t k = 0; k < fact_rows[r].size(); ++k) {
      const auto& [text, failure] = facts[fact_rows[r][k]];
      if (k) out << kFactGap;
      if (failure)
        out << "<tspan font-weight=\"bold\" fill=\"#c00\">" << xmlText(text) << "</tspan>";
      else
        out << xmlText(text);
    }
    out << "</text>\n";
  }
  for (std::size_t k = 0; k < steps.size(); ++k) {
    out << "<g class=\"panel\" transform=\"translate(" << num(static_cast<double>(k) * (o.panel_width_px + kPanelGapPx))
        << ",0)\">\n<text x=\"" << num(v.left) << "\" y=\"" << num(st.titleBand() - st.px(6.0)) << "\" font-size=\""
        << num(st.titleFont()) << "\">" << xmlText(sc.name);
    if (timed) out << kFactGap << "t = " << steps[k] << " of " << sol->makespan();
    out << "</text>\n<rect class=\"workspace\" x=\"" << num(v.left) << "\" y=\"" << num(v.top) << "\" width=\""
        << num(v.width()) << "\" height=\"" << num(v.height()) << "\" fill=\"#fafafa\" stroke=\"#000\" stroke-width=\""
        << num(st.outline()) << "\"/>\n";
    // All obstacles are one path, filled as their union: filled one by
    // one, adjacent boxes (merged map cells) each anti-alias their shared
    // edge and leave a light hairline seam along it, stroke or not. The
    // thin stroke of the fill keeps obstacles thinner than a pixel seen.
    if (!sc.obstacles.empty()) {
      out << "<path class=\"obstacles\" fill=\"#666\" stroke=\"#666\" stroke-width=\"0.6\" d=\"";
      for (std::size_t i = 0; i < sc.obstacles.size(); ++i) out << (i ? "\n" : "") << outlinePath(v, sc.obstacles[i].body());
      out << "\"/>\n";
    }
    const std::size_t* step = timed ? &steps[k] : nullptr;
    for (std::size_t i = 0; i < sc.robots.size(); ++i)
      writeRobot(out, v, st, *models[i], i, traces[i], paths[i], step, o.tolerance_px);
    // The names over every robot: in each robot's group, a later robot's
    // body covered them.
    if (o.labels && !sc.robots.empty()) {
      out << "<g class=\"labels\">\n";
      for (std::size_t i = 0; i < sc.robots.size(); ++i)
        writeLabels(out, v, st, *models[i], poseAt(sc.robots[i], paths[i], step));
      out << "\n</g>\n";
    }
    out << "</g>\n";
  }
  out << "<g class=\"key\" fill=\"#222\">\n";
  for (std::size_t r = 0; r < key_rows.size(); ++r) {
    const double y = key_top + st.keyRow() * (r + 0.5);
    double x = kPaddingPx;
    for (std::size_t k : key_rows[r]) {
      writeKeyMark(out, st, keys[k].mark, x, y, keys[k].glyph_px);
      out << "<text x=\"" << num(x + keys[k].glyph_px + st.px(4.0)) << "\" y=\"" << num(y + st.font() * 4.0 / 11.0)
          << "\">" << keys[k].text << "</text>\n";
      x += key_w[k] + st.keyGap();
    }
  }
  out << "</g>\n";
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

double pictureWidthPx(std::size_t panels, double panel_width_px) {
  return static_cast<double>(std::max<std::size_t>(panels, 1)) * (panel_width_px + kPanelGapPx) - kPanelGapPx;
}

PictureSize svgSizePx(const std::string& svg) {
  const std::string_view root = std::string_view(svg).substr(0, svg.find('>'));
  auto attribute = [&](std::string_view name) {
    const std::size_t at = root.find(" " + std::string(name) + "=\"");
    return at == std::string_view::npos ? 0.0 : std::strtod(root.data() + at + name.size() + 3, nullptr);
  };
  return {attribute("width"), attribute("height")};
}

std::string scenarioSvg(const Scenario& scenario, const SvgOptions& options) {
  return render(scenario, nullptr, options);
}

std::string solutionSvg(const Scenario& scenario, const Solution& solution, const SvgOptions& options) {
  return render(scenario, &solution, options);
}

}  // namespace earc::render
