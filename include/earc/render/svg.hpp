// Pictures of scenarios and solutions as SVG: the workspace, the obstacles,
// every robot's start (solid) and goal (outlined), and for a solution each
// robot's path and the robots at chosen time steps, with the robots' names
// and a key that ends with a scale bar. Robots too small to see are drawn
// at a least size, which the key then states. The world's y axis points
// up; the picture's points down, so y is flipped.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "earc/geometry/shapes.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/scene/solution.hpp"

namespace earc::render {

struct SvgOptions {
  // Time steps at which every robot is drawn, one panel per step side by
  // side, left to right in this order (earc-plan render refuses steps that
  // do not increase). Empty: one panel without a time step.
  std::vector<std::size_t> steps;
  // Text, marks and lines are those of an 800-pixel panel scaled with the
  // width (0.85 to 5 times, no text under 8 pixels).
  double panel_width_px = 800.0;
  // Path polylines drop points that lie within this distance of the
  // simplified line: a 5000-step path becomes a few dozen points.
  double tolerance_px = 0.5;
  bool labels = true;  // robot names
};

// Scenario only: options.steps are ignored (there are no paths).
std::string scenarioSvg(const Scenario& scenario, const SvgOptions& options = {});

// Paths as polylines in one colour per robot, starts and goals, and the
// robots at options.steps, a panel each: the part of a path travelled solid,
// the part to go dashed and faded.
std::string solutionSvg(const Scenario& scenario, const Solution& solution, const SvgOptions& options = {});

// The width in pixels of a picture of `panels` panels (1 without steps)
// side by side, known before anything is drawn.
double pictureWidthPx(std::size_t panels, double panel_width_px);

// rsvg-convert (librsvg) makes no PNG wider or taller than this: beyond
// it, it fails with three lines of its own.
inline constexpr double kMaxPngSidePx = 32767;

// The width and height in pixels that an SVG made here declares on its
// root element (0 for one it does not declare).
struct PictureSize {
  double width = 0;
  double height = 0;
};
PictureSize svgSizePx(const std::string& svg);

// Douglas-Peucker simplification: keeps the first and last point and every
// point needed so that no dropped point lies farther than tolerance from the
// kept polyline.
std::vector<geo::Vec2> decimatePolyline(const std::vector<geo::Vec2>& points, double tolerance);

// writeImage's checks, for a command to make before its work: InputError
// naming `option` for a name ending in neither .svg nor .png, runtime_error
// when a .png needs rsvg-convert and it is missing. True for PNG.
bool requireImageOutput(const std::string& path, const std::string& option);

// Writes the SVG to path, or for a path ending in ".png" converts it with
// rsvg-convert, after requireImageOutput's checks. Throws
// std::runtime_error when rsvg-convert fails.
void writeImage(const std::string& path, const std::string& svg);

}  // namespace earc::render
