// The SVG picture's parts, shared by svg.cpp (the picture), svg_draw.cpp
// (robots, paths and labels) and svg_key.cpp (the key). Internal to src/render.
#pragma once

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

namespace earc::render::svg_detail {

// Pixel coordinates are written with two decimals at most: finer is
// invisible and only makes the file bigger.
std::string num(double v);

inline constexpr double kPaddingPx = 12.0;

inline constexpr double kPanelGapPx = 16.0;

inline constexpr double kFadedOpacity = 0.35;  // the start pose when a later step is drawn

inline constexpr double kAheadOpacity = 0.5;   // a path's part still to go at a step

// The sizes of text, marks and lines, in pixels: an 800-pixel panel's,
// scaled with the panel's width (within 0.85 and 5) so that a picture reads
// alike at any --width; no text is smaller than 8 pixels.
struct Style {
  // Fixed sizes made the text of a 4000-pixel picture a speck seen whole,
  // and crowded a 400-pixel one; 8 pixels is about the least that reads.
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
  // The least a robot is drawn across its bounding circle, and an arm's
  // links thick, in whole pixels, so that robots do not vanish on a large
  // map (a 0.6 x 0.4 box on den520d); larger ones are drawn true to scale.
  double minRobotAcross() const { return std::round(px(9.0)); }
  double minLinkWidth() const { return std::max(1.0, std::round(px(2.0))); }
};

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

// How a body is painted: its attributes, written inside the element.
struct Paint {
  std::string attributes;
};

inline const char* const kFactGap = " \u00b7 ";  // between the facts of a line: spaces alone collapse to one

// The key's entries: what each mark of the picture means.
enum class KeyMark { Start, Now, FadedStart, Goal, Path, PathAhead, Heading, Joint, LeastRobot, LeastLink, Scale };

struct KeyEntry {
  KeyMark mark;
  std::string text;
  double glyph_px = 0.0;  // the mark's width; 0: st.keyGlyph()
};


std::string robotColour(std::size_t i);

// Roughly how wide a line of text is drawn: a sans-serif glyph averages
// about 0.6 of the font size (a code point, not a byte, is a glyph).
double textWidth(std::string_view text, double font_px);

double segmentDistance(geo::Vec2 p, geo::Vec2 a, geo::Vec2 b);

std::ostream& operator<<(std::ostream& out, Pt q);

std::ostream& operator<<(std::ostream& out, const Paint& p);

// A box's corners in picture coordinates, counterclockwise on the picture.
std::array<geo::Vec2, 4> boxCorners(const View& v, const geo::Body& b);

// One body's outline as path data ("M... Z"), counterclockwise on the
// picture whatever the body: outlines drawn in one path then overlap
// filled under the nonzero rule (a turn the other way would cut a hole).
std::string outlinePath(const View& v, const geo::Body& b);

// One body as an SVG element.
void writeBody(std::ostream& out, const View& v, const geo::Body& b, const Paint& paint);

std::string arrowhead(geo::Vec2 centre, geo::Vec2 dir, double reach);

std::string opacityAttribute(double opacity);

// How many times its true size a mobile robot is drawn: 1, or more for
// one smaller than st.minRobotAcross().
double mobileGrowth(const RobotModel& m, const View& v, const Style& st);

// The radius an arm's links are drawn with: their own, or more for links
// thinner than st.minLinkWidth().
double drawnLinkRadius(const RobotModel& m, const View& v, const Style& st);

// Whether a robot is drawn larger than it is (see Style::minRobotAcross).
bool drawnEnlarged(const RobotModel& m, const View& v, const Style& st);

// A robot at q: its bodies filled (with a thin dark edge) or outlined
// (dashed), plus its heading (mobile) or its joints (arm); no smaller
// than the style's least sizes.
void writePose(std::ostream& out, const View& v, const Style& st, const RobotModel& m, const double* q, bool filled,
               double opacity);

// The point a robot's path follows: the reference point or the arm's tip.
geo::Vec2 tracePoint(const RobotModel& m, const double* q, std::vector<geo::Vec2>& scratch);

// The path of each scenario robot, found by name (nullptr: none drawn).
std::vector<const Path*> pathsByRobot(const Scenario& sc, const Solution& sol);

// The point a path follows at each step, in picture coordinates.
std::vector<geo::Vec2> tracePoints(const RobotModel& m, const Path& path, const View& v);

// Steps [from, to] of a path as a polyline (`cls` "path" or, dashed and
// faded, "path-ahead"), points within `tolerance` of the line dropped.
void writePathLine(std::ostream& out, const Style& st, const std::vector<geo::Vec2>& pts, std::size_t from,
                   std::size_t to, const char* cls, double tolerance);

// `text` centred on `at` (its baseline), on a white halo, moved as little
// as needed to lie inside the panel's padding.
void writeLabel(std::ostream& out, const View& v, const Style& st, const std::string& text, geo::Vec2 at,
                double font_px, const char* fill);

// Where a robot is drawn at *step: on its path, or at its start when no
// step is drawn or it has no path.
const double* poseAt(const RobotSpec& r, const Path* path, const std::size_t* step);

void writeRobot(std::ostream& out, const View& v, const Style& st, const RobotModel& m, std::size_t index,
                const std::vector<geo::Vec2>& trace, const Path* path, const std::size_t* step, double tolerance);

// The centre of a box w by h pixels that lies `gap` pixels beyond `from`
// in the direction `dir` (a unit vector on the picture).
geo::Vec2 besideAt(geo::Vec2 from, geo::Vec2 dir, double gap, double w, double h);

void writeLabels(std::ostream& out, const View& v, const Style& st, const RobotModel& m, const double* q);

// Items of the given widths laid out in rows no wider than `width`, `gap`
// apart: each row's item indices. An item wider than the width has a row
// of its own.
std::vector<std::vector<std::size_t>> flowRows(const std::vector<double>& widths, double gap, double width);

// What the solution file says, one fact each: method, solved or why not,
// makespan, sum of costs, planning time. A fact marked true is a failure.
std::vector<std::pair<std::string, bool>> solutionFacts(const Solution& sol);

// The scale bar's length: the longest 1, 2 or 5 times a power of ten that
// is at most a quarter of the workspace's width.
double scaleBarLength(double world_width);

// What each mark of the picture means, and last a scale bar. `enlarged`:
// whether some robots are drawn larger than true, mobile robots and arms.
std::vector<KeyEntry> keyEntries(const Scenario& sc, const View& v, bool paths, bool timed, const Style& st,
                                 std::pair<bool, bool> enlarged);

// One key mark, `w` wide, its middle at (x, y).
void writeKeyMark(std::ostream& out, const Style& st, KeyMark mark, double x, double y, double w);

}  // namespace earc::render::svg_detail
