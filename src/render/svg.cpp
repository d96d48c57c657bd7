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
#include "svg_parts.hpp"

namespace earc::render {

using namespace svg_detail;

namespace {

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

// Paths as polylines in one colour per robot (mobile robots: the reference
// point; arms: the end of the last link), starts and goals, and the robots
// at options.steps (a robot past its last state stays there), each step's
// panel drawing the part of a path travelled solid and the part to go
// dashed and faded.
std::string solutionSvg(const Scenario& scenario, const Solution& solution, const SvgOptions& options) {
  return render(scenario, &solution, options);
}

}  // namespace earc::render
