// The experiment suites of the E-ARC paper ("Experiments"): mobile robots
// and facing pairs of 5-DOF arms, each without and with random obstacles
// that move from trial to trial, at growing robot counts; and, beside
// them, mobile robots on MovingAI benchmark maps (fixed obstacles, random
// starts and goals per trial), and the crowd suites: the first N agents
// of a MovingAI scenario file, N growing to hundreds. A trial's
// scenario is a pure function of (suite, robots, trial, run seed): every
// method sees the same scenarios, so results are paired by seed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "earc/scene/scenario.hpp"

namespace earc::bench {

struct Suite {
  std::string name;         // "mobile", "mobile-obst", "arms", "arms-obst", "movingai-..."
  std::string family;       // "mobile" or "arms"
  bool obstacles = false;
  std::vector<int> robots;  // the robot counts run by default
  std::string map;          // MovingAI suites: the embedded map's name
  std::string scen;         // crowd suites: the embedded scenario file's name
  int most_robots = 0;      // crowd suites: the file's agents

  // One of the paper's suites (earc-bench run --full): the generated ones.
  bool paper() const { return map.empty(); }
  // Robots from a scenario file, any count from 2 to most_robots.
  bool crowd() const { return !scen.empty(); }
};

// The paper's suites first, then the MovingAI ones, then the crowd ones.
const std::vector<Suite>& allSuites();
// Throws InputError naming `option` (the one the name came from) and the
// suites for an unknown name.
const Suite& suiteByName(const std::string& name, const std::string& option = "--suites");

// Whether a run may plan this many robots of the suite: one of its
// counts, or for a crowd suite any from 2 to its file's agents.
bool suiteTakes(const Suite& suite, int robots);
// The counts a run plans, ascending: the suite's, or of `asked` (when not
// empty) those it takes.
std::vector<int> suiteCounts(const Suite& suite, const std::vector<int>& asked);
// "mobile: 2, 4, 8, 16, 32", "crowd-empty-16-16: 2 to 128", for messages.
std::string suiteCountsText(const Suite& suite);

// The methods of the comparison, in the order tables list them.
const std::vector<std::string>& allMethods();
// "earc, arc, ...", for messages.
std::string allMethodsText();

// Seeds of one trial: the scenario's, and the planner's (one for every
// method, so that a method's randomness is paired too).
struct TrialSeeds {
  std::uint64_t scenario = 0;
  std::uint64_t planner = 0;
};
TrialSeeds trialSeeds(const Suite& suite, int robots, int trial, std::uint64_t run_seed);

// The scenario of a trial, "<suite>-<robots>-t<trial>": a function of the
// arguments (a crowded draw is retried with derived seeds).
Scenario trialScenario(const Suite& suite, int robots, int trial, std::uint64_t run_seed);

// The scenario of problem `index` for growing a database of this suite's
// kind: drawn from a stream of `seed` disjoint from trialSeeds(), so that a
// database built with the benchmark's seed never holds its test problems.
Scenario databaseProblem(const Suite& suite, int robots, int index, std::uint64_t seed);

// A crowd suite's lower bound on the sum of costs of `robots` robots
// (bench/crowds.hpp); nothing for other suites.
std::optional<std::int64_t> suiteLowerBound(const Suite& suite, int robots);

// Trials that come from scenario files (earc-bench run FILE...) are of
// this suite: one trial per file and method, with the file's robots.
inline constexpr const char* kFilesSuite = "files";

// What a results file's suite column may hold: every suite's name and
// kFilesSuite.
std::vector<std::string> resultSuiteNames();

// A scenario file given to earc-bench run.
struct ScenarioFile {
  std::string path;        // as given
  Scenario scenario;
  std::string family;      // "mobile" or "arms": which E-ARC database it takes
  int trial = 0;           // among the files of its robot count, in the order given
  std::uint64_t hash = 0;  // of its content as read: a resumed run checks it
  // Of what its problems share with others of their kind (workspace,
  // obstacles, robots without starts and goals, resolution): files with
  // the same world share a Lightning database.
  std::uint64_t world = 0;
  int robots() const { return static_cast<int>(scenario.robots.size()); }
};

// A scenario's JSON without its name and its robots' starts and goals: what
// its problems share with others of their kind (ScenarioFile::world hashes it).
nlohmann::json scenarioWorldJson(const Scenario& scenario);

// Reads the scenario files, numbered per robot count in the order given.
// Throws InputError naming a file that is invalid, has fewer than 2 or more
// than kMaxResultsRobots robots, or mixes mobile robots and arms.
std::vector<ScenarioFile> loadScenarioFiles(const std::vector<std::string>& paths);

// Seeds of a file's trial: the scenario's is the file's hash (recorded, so
// that a resumed run can tell that the file changed), the planner's
// derives from it and the run seed.
TrialSeeds fileTrialSeeds(const ScenarioFile& file, std::uint64_t run_seed);

// Problem `index` for growing a Lightning database of a file's world: its
// robots at random starts and goals, from a stream of `seed` that trials
// never use.
Scenario fileDatabaseProblem(const ScenarioFile& file, int index, std::uint64_t seed);

// Splits "a,b,c" (empty items dropped).
std::vector<std::string> splitList(const std::string& list);

}  // namespace earc::bench
