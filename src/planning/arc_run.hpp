// ARC's run over one scenario (runArc): the conflict loop and its state.
// Internal to the planning layer: arc.cpp holds the loop, arc_jam.cpp the
// hand-over of jams to the crowd solver.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "earc/planning/arc.hpp"
#include "earc/planning/crowd.hpp"

namespace earc {

// When ARC hands a jam to the crowd solver, and how big it is (arc_jam.cpp
// says how they are used).
constexpr int kJamLevel = 1;
constexpr double kJamConflictsPerRobot = 3.0;
constexpr int kJamCappedGroups = 8;
constexpr std::size_t kJamMinRecurrences = 4;
constexpr std::size_t kFirstJam = 16;
constexpr std::size_t kJamGrowth = 4;
constexpr double kJamMinBudgetS = 0.25;
// The final compaction pass's share of the plan's time so far, at most.
constexpr double kCompactShare = 0.25;
// The states the shortcuts' timing searches try per route position
// (ArcSettings::compact_shortcut_robots).
constexpr std::size_t kShortcutStates = 3;

// One plan of ARC. Not thread-safe; used once.
class ArcRun {
 public:
  ArcRun(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context,
         std::vector<std::unique_ptr<SubproblemSolver>> hierarchy)
      : scenario_(scenario), settings_(settings), context_(context), hierarchy_(std::move(hierarchy)),
        world_(scenario), owned_models_(makeRobotModels(scenario)),
        deadline_(Deadline(settings.time_limit_s).withWorkBudgets(settings.work_budgets).stoppedBy(context.stop)) {
    for (const auto& m : owned_models_) models_.push_back(m.get());
  }

  PlanResult run();

 private:
  bool resolve(const Conflict& c, std::size_t max_robots);
  std::optional<bool> handOverJam(const Conflict& c, const std::vector<int>& robots);
  std::size_t firstJamSize(std::size_t conflict_robots) const;
  std::optional<int> conflictsWithResolved(const Subproblem& sub, const LocalSolution& local);
  void leaveOutGroupWaits(const Subproblem& sub, const LocalSolution& local);
  void traceEvent(nlohmann::json ev) {
    if (settings_.trace) events_.push_back(std::move(ev));
  }
  // The plan's time so far: work done with --deterministic, else seconds.
  double soFar() const { return deadline_.countsWork() ? workSecondsDone() - plan_work0_ : plan_clock_.seconds(); }
  void report(std::atomic<int> PlanProgress::*field, int value) {
    if (context_.progress) (context_.progress->*field).store(value, std::memory_order_relaxed);
  }

  const Scenario& scenario_;
  const PlannerSettings& settings_;
  const PlanContext& context_;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy_;
  CollisionWorld world_;
  std::vector<std::shared_ptr<const RobotModel>> owned_models_;
  std::vector<const RobotModel*> models_;
  Deadline deadline_;
  bool whole_problem_failed_ = false;
  std::vector<Path> paths_;
  std::vector<ResolvedSpan> spans_;
  std::unique_ptr<RoadmapSet> roadmaps_;
  nlohmann::json events_ = nlohmann::json::array();
  // Statistics.
  int conflicts_ = 0;
  int expansions_ = 0;
  int merged_ = 0;
  int subproblem_id_ = 0;
  std::map<std::string, std::int64_t> by_solver_;
  std::map<std::string, std::int64_t> by_size_;
  std::map<std::string, double> solver_time_;
  std::set<FailureCause> failures_;
  std::size_t last_t_start_ = 0;
  ConflictRecurrence recurrence_;
  int cap_raised_ = 0;
  // Jams handed to the crowd solver (handOverJam).
  bool crowd_ok_ = false;
  std::vector<int> jam_group_;
  std::size_t jam_size_ = 0;
  int conflicts_at_handover_ = 0;
  int capped_since_handover_ = 0;
  std::size_t jam_conflicts_since_handover_ = 0;
  std::vector<CrowdHandover> handovers_;
  double crowd_s_ = 0.0;
  // A jam planned with every robot in it, with --refine: the crowd
  // solver's run, whose lattice refinement is not part of the first plan.
  std::optional<LacamStats> whole_crowd_;
  double lattice_s_ = 0.0;
  Stopwatch plan_clock_;
  const double plan_work0_ = workSecondsDone();
  std::int64_t waits_left_out_ = 0;
  std::int64_t window_retimed_ = 0;
  std::int64_t restamped_ = 0, restamped_around_ = 0, lockstep_ = 0, restamped_steps_ = 0;
};

}  // namespace earc
