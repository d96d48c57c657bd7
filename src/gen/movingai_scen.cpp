#include "earc/gen/movingai_scen.hpp"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>

#include "earc/gen/embedded_maps.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/format.hpp"

namespace earc::gen {

namespace {

constexpr int kMaxScenRobots = 1024;
// As the map reader's: the largest benchmark maps are about 1500 wide.
constexpr int kMaxScenSide = 8192;

std::string lineText(int line) { return "line " + std::to_string(line); }

std::string cellText(int col, int row) {
  return "(column " + std::to_string(col) + ", row " + std::to_string(row) + ")";
}

std::vector<std::string> splitTabs(const std::string& line) {
  std::vector<std::string> out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t tab = line.find('\t', from);
    out.push_back(line.substr(from, tab == std::string::npos ? std::string::npos : tab - from));
    if (tab == std::string::npos) return out;
    from = tab + 1;
  }
}

// A whole number of the text alone, from lo to hi; else why not.
bool wholeNumber(const std::string& text, long long lo, long long hi, long long& v) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return !text.empty() && ec == std::errc() && end == text.data() + text.size() && v >= lo && v <= hi;
}

// The nine fields of an agent line, named as the README names them.
constexpr const char* kFieldNames[] = {"bucket",      "map",          "width",     "height",        "start column",
                                       "start row",   "goal column",  "goal row",  "optimal length"};

}  // namespace

MovingAiScen parseMovingAiScen(const std::string& text, const std::string& file) {
  MovingAiScen scen;
  scen.file = file;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  int blank_from = 0;  // the first of the blank lines seen since the last agent
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_no == 1) {
      if (line != "version 1")
        throw InputError(file, lineText(1), "expected the header 'version 1', got '" + printableText(line, 80) +
                                                "' (is this a MovingAI .scen file?)");
      continue;
    }
    if (line.empty()) {
      if (!blank_from) blank_from = line_no;
      continue;
    }
    // Blank lines may end the file, not split it.
    if (blank_from) throw InputError(file, lineText(blank_from), "a blank line between agents");
    const std::vector<std::string> f = splitTabs(line);
    if (f.size() != 9)
      throw InputError(file, lineText(line_no),
                       "expected 9 tab-separated fields (bucket, map, width, height, start column, start row, goal "
                       "column, goal row, optimal length), got " + std::to_string(f.size()));
    long long v[9] = {};
    for (int i : {0, 2, 3, 4, 5, 6, 7}) {
      const long long lo = i == 2 || i == 3 ? 1 : 0;
      const long long hi = i == 0 ? (1LL << 40) : kMaxScenSide;
      if (!wholeNumber(f[static_cast<std::size_t>(i)], lo, hi, v[i]))
        throw InputError(file, lineText(line_no),
                         std::string(kFieldNames[i]) + ": expected a whole number from " + std::to_string(lo) +
                             " to " + std::to_string(hi) + ", got '" + printableText(f[static_cast<std::size_t>(i)], 40) +
                             "'");
    }
    {
      std::istringstream len(f[8]);
      double d = 0;
      std::string rest;
      if (f[8].empty() || !(len >> d) || (len >> rest) || !std::isfinite(d) || d < 0)
        throw InputError(file, lineText(line_no),
                         "optimal length: expected a number of 0 or more, got '" + printableText(f[8], 40) + "'");
    }
    if (f[1].empty()) throw InputError(file, lineText(line_no), "map: an empty map name");
    const int w = static_cast<int>(v[2]), h = static_cast<int>(v[3]);
    if (scen.agents.empty()) {
      scen.map_file = f[1];
      scen.width = w;
      scen.height = h;
    } else if (f[1] != scen.map_file || w != scen.width || h != scen.height) {
      throw InputError(file, lineText(line_no),
                       "map " + printableText(f[1], 80) + " of " + std::to_string(w) + " x " + std::to_string(h) +
                           ", where line 2 says " + printableText(scen.map_file, 80) + " of " +
                           std::to_string(scen.width) + " x " + std::to_string(scen.height));
    }
    for (int i : {4, 6})
      if (v[i] >= w)
        throw InputError(file, lineText(line_no), std::string(kFieldNames[i]) + " " + std::to_string(v[i]) +
                                                      " is outside the map's " + std::to_string(w) + " columns");
    for (int i : {5, 7})
      if (v[i] >= h)
        throw InputError(file, lineText(line_no), std::string(kFieldNames[i]) + " " + std::to_string(v[i]) +
                                                      " is outside the map's " + std::to_string(h) + " rows");
    scen.agents.push_back({static_cast<int>(v[4]), static_cast<int>(v[5]), static_cast<int>(v[6]),
                           static_cast<int>(v[7]), line_no});
  }
  if (line_no == 0) throw InputError(file, lineText(1), "the file is empty: expected the header 'version 1'");
  return scen;
}

MovingAiScen readMovingAiScen(const std::string& path) { return parseMovingAiScen(readTextFile(path), path); }

const EmbeddedMap* findEmbeddedMovingAiScen(std::string_view name) {
  for (const EmbeddedMap& m : embeddedMovingAiScens())
    if (m.name == name) return &m;
  return nullptr;
}

std::optional<MovingAiScen> embeddedMovingAiScen(std::string_view name) {
  const EmbeddedMap* m = findEmbeddedMovingAiScen(name);
  if (!m) return std::nullopt;
  return parseMovingAiScen(std::string(m->text), "datasets/movingai/" + std::string(name) + ".scen");
}

MobileFootprint defaultScenFootprint() {
  MobileFootprint f;
  f.shape = MobileShape::Disc;
  f.radius = 0.3;
  return f;
}

namespace {

// The file's map must be this one: its name (without directory and
// extension) and size.
void requireScenMap(const GridMap& map, const MovingAiScen& scen) {
  if (scen.agents.empty()) return;
  const std::string name = std::filesystem::path(scen.map_file).stem().string();
  if (name != map.name || scen.width != map.width || scen.height != map.height)
    throw InputError(scen.file, lineText(scen.agents.front().line),
                     "its agents are on map " + printableText(scen.map_file, 80) + " of " + std::to_string(scen.width) +
                         " x " + std::to_string(scen.height) + " cells, not on " + map.name + " of " +
                         std::to_string(map.width) + " x " + std::to_string(map.height));
}

// Every agent's cells free (the file's agents must all fit the map).
void requireFreeCells(const GridMap& map, const MovingAiScen& scen) {
  for (const ScenAgent& a : scen.agents)
    for (const auto& [what, col, row] : {std::tuple{"start", a.start_col, a.start_row}, std::tuple{"goal", a.goal_col, a.goal_row}})
      if (map.isBlocked(col, row))
        throw InputError(scen.file, lineText(a.line),
                         std::string(what) + " cell " + cellText(col, row) + " is blocked on map " + map.name);
}

// Breadth-first search on the free cells, reusing its buffers.
class GridBfs {
 public:
  explicit GridBfs(const GridMap& map) : map_(map), dist_(map.blocked.size(), -1) {}
  // Moves from (c0, r0) to (c1, r1), or -1.
  int distance(int c0, int r0, int c1, int r1) {
    for (std::size_t i : touched_) dist_[i] = -1;
    touched_.clear();
    const std::size_t w = static_cast<std::size_t>(map_.width);
    const std::size_t from = static_cast<std::size_t>(r0) * w + static_cast<std::size_t>(c0);
    const std::size_t to = static_cast<std::size_t>(r1) * w + static_cast<std::size_t>(c1);
    if (map_.blocked[from] || map_.blocked[to]) return -1;
    dist_[from] = 0;
    touched_.push_back(from);
    for (std::size_t head = 0; head < touched_.size(); ++head) {
      const std::size_t cell = touched_[head];
      if (cell == to) return dist_[cell];
      const int col = static_cast<int>(cell % w), row = static_cast<int>(cell / w);
      const int next[4][2] = {{col + 1, row}, {col - 1, row}, {col, row + 1}, {col, row - 1}};
      for (const auto& n : next) {
        if (n[0] < 0 || n[1] < 0 || n[0] >= map_.width || n[1] >= map_.height) continue;
        const std::size_t j = static_cast<std::size_t>(n[1]) * w + static_cast<std::size_t>(n[0]);
        if (map_.blocked[j] || dist_[j] >= 0) continue;
        dist_[j] = dist_[cell] + 1;
        touched_.push_back(j);
      }
    }
    return -1;
  }

 private:
  const GridMap& map_;
  std::vector<int> dist_;
  std::vector<std::size_t> touched_;
};

void requireRobots(const MovingAiScen& scen, int robots) {
  if (robots < 1 || robots > kMaxScenRobots)
    throw SettingError("robots", "must be in [1, " + std::to_string(kMaxScenRobots) + "], got " + std::to_string(robots));
  if (static_cast<std::size_t>(robots) > scen.agents.size())
    throw InputError(scen.file, "",
                     "the file has " + std::to_string(scen.agents.size()) + " agents, fewer than the " +
                         std::to_string(robots) + " robots asked for");
}

}  // namespace

std::vector<int> scenGridDistances(const GridMap& map, const MovingAiScen& scen, int robots) {
  requireScenMap(map, scen);
  requireRobots(scen, robots);
  GridBfs bfs(map);
  std::vector<int> out;
  for (int i = 0; i < robots; ++i) {
    const ScenAgent& a = scen.agents[static_cast<std::size_t>(i)];
    out.push_back(bfs.distance(a.start_col, a.start_row, a.goal_col, a.goal_row));
  }
  return out;
}

int stepsPerCell(double translation) {
  // A hair under a whole number of steps is that number (1 / 0.05 is
  // 20.000000000000004 in doubles).
  return static_cast<int>(std::ceil(1.0 / translation - 1e-9));
}

std::int64_t scenLowerBound(const GridMap& map, const MovingAiScen& scen, int robots, double translation) {
  const std::vector<int> d = scenGridDistances(map, scen, robots);
  std::int64_t moves = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (d[i] < 0)
      throw InputError(scen.file, lineText(scen.agents[i].line), "the goal cannot be reached from the start on map " + map.name);
    moves += d[i];
  }
  return moves * stepsPerCell(translation);
}

// Refused: another map name or size; any agent's cell blocked (the whole
// file must fit the map); among the first `robots`, two agents on one
// start or one goal cell, or a goal out of reach; fewer agents than asked.
Scenario scenarioFromScen(const GridMap& map, const MovingAiScen& scen, const ScenSettings& settings) {
  const int n = settings.robots;
  const MobileFootprint& f = settings.footprint;
  requireFootprint(f, std::min(map.width, map.height),
                   "the " + std::to_string(map.width) + " x " + std::to_string(map.height) + " map");
  // Within its cell a robot touches neither the blocked cells nor the
  // robots of other cells, so every instance is valid.
  if (f.shape == MobileShape::Disc && f.radius > 0.5)
    throw SettingError("radius", "must be at most 0.5 for a robot at a cell centre to fit its cell, got " +
                                     formatNumber(f.radius));
  if (f.shape == MobileShape::Box && (f.box_size.x > 1.0 || f.box_size.y > 1.0))
    throw SettingError("shape", "the box footprint must fit in a cell");
  requireScenMap(map, scen);
  requireFreeCells(map, scen);
  requireRobots(scen, n);
  std::map<std::pair<int, int>, int> starts, goals;  // cell -> line
  GridBfs bfs(map);
  for (int i = 0; i < n; ++i) {
    const ScenAgent& a = scen.agents[static_cast<std::size_t>(i)];
    const auto s = starts.emplace(std::pair{a.start_col, a.start_row}, a.line);
    if (!s.second)
      throw InputError(scen.file, lineText(a.line), "start cell " + cellText(a.start_col, a.start_row) +
                                                        " is also the start of line " + std::to_string(s.first->second));
    const auto g = goals.emplace(std::pair{a.goal_col, a.goal_row}, a.line);
    if (!g.second)
      throw InputError(scen.file, lineText(a.line), "goal cell " + cellText(a.goal_col, a.goal_row) +
                                                        " is also the goal of line " + std::to_string(g.first->second));
    if (bfs.distance(a.start_col, a.start_row, a.goal_col, a.goal_row) < 0)
      throw InputError(scen.file, lineText(a.line), "goal cell " + cellText(a.goal_col, a.goal_row) +
                                                        " cannot be reached from start cell " +
                                                        cellText(a.start_col, a.start_row) + " on map " + map.name);
  }

  Scenario s;
  s.name = "movingai-" + std::filesystem::path(scen.file).stem().string() + footprintTag(f) + "-" + std::to_string(n);
  s.workspace = {{0.0, 0.0}, {static_cast<double>(map.width), static_cast<double>(map.height)}};
  for (const CellRect& r : mergeBlockedCells(map)) s.obstacles.push_back(cellRectObstacle(map, r));
  auto centre = [&map](int col, int row) {
    return std::vector<double>{col + 0.5, map.height - 1 - row + 0.5, 0.0};
  };
  for (int i = 0; i < n; ++i) {
    const ScenAgent& a = scen.agents[static_cast<std::size_t>(i)];
    RobotSpec r = mobileRobot(i, f);
    r.start = centre(a.start_col, a.start_row);
    r.goal = centre(a.goal_col, a.goal_row);
    s.robots.push_back(std::move(r));
  }
  return s;
}

}  // namespace earc::gen
