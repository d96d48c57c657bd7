// The picture's key: what each mark means, a scale bar, the plan's facts.
#include "svg_parts.hpp"

namespace earc::render::svg_detail {

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

double scaleBarLength(double world_width) {
  const double most = world_width / 4, power = std::pow(10.0, std::floor(std::log10(most)));
  for (double f : {5.0, 2.0})
    if (f * power <= most * (1 + 1e-9)) return f * power;
  return power;
}

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

}  // namespace earc::render::svg_detail
