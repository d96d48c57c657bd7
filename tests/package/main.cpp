// plan_one SCENARIO [DB]: loads the scenario, plans it with ARC (E-ARC when
// a database is given), validates the plan and prints one line; exit 0 when
// solved and valid, 1 when not, 2 for bad input.
#include <earc/earc.hpp>

#include <iostream>
#include <memory>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: plan_one SCENARIO [DB]\n";
    return 2;
  }
  try {
    const earc::Scenario scenario = earc::loadScenario(argv[1]);
    earc::PlannerSettings settings;
    settings.seed = 7;
    settings.time_limit_s = 60;
    settings.work_budgets = true;
    std::unique_ptr<earc::exp::ExperienceStore> store;
    if (argc > 2) {
      store = std::make_unique<earc::exp::ExperienceStore>(argv[2]);
      settings.method = earc::Method::Earc;
    }
    const earc::PlanResult result = earc::plan(scenario, settings, store.get());
    const earc::ValidationReport report = earc::validateSolution(scenario, result.solution);
    std::cout << "plan_one " << earc::version() << ": " << (result.solution.solved ? "solved" : "not solved")
              << ", valid " << (report.valid ? "yes" : "no") << ", robots " << result.solution.paths.size()
              << ", makespan " << report.makespan << ", sum of costs " << report.sum_of_costs
              << ", method " << result.stats.method.value_or("") << "\n";
    return result.solution.solved && report.valid ? 0 : 1;
  } catch (const earc::InputError& e) {
    std::cerr << "plan_one: " << e.what() << "\n";
    return 2;
  }
}
