// Scenarios, plan() and validate() for Python. plan() takes the options of
// `earc-plan plan` by their Python names and applies the same checks.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/methods/options.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/planner.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/validate/validator.hpp"

namespace earc::python {

namespace {

// A plan's outcome as Python sees it.
struct PyPlan {
  PlanResult result;
};

// Warnings about an input read all the same, as Python warnings.
void warnAll(const InputWarnings& warnings) {
  for (const InputWarning& w : warnings)
    PyErr_WarnEx(PyExc_UserWarning, inputWarningLine(w, "earc").c_str(), 1);
}

// A str or os.PathLike as a file name.
std::string fsPath(const py::object& p) { return py::str(py::module_::import("os").attr("fspath")(p)); }

// load_scenario(path or dict): read, then checked as the programs check it.
Scenario loadAny(const py::object& source) {
  InputWarnings warnings;
  Scenario s;
  if (py::isinstance<py::dict>(source)) {
    s = scenarioFromJson(fromPython(source), "scenario", &warnings);
    checkScenarioGeometry(s, "scenario");
  } else {
    s = loadScenario(fsPath(source), &warnings);
  }
  warnAll(warnings);
  return s;
}

// Each robot's path: (times, configurations), steps 0..n-1 and an n x dim
// array of its configurations.
py::list pathArrays(const Solution& sol) {
  py::list out;
  for (const Path& p : sol.paths) {
    const auto n = static_cast<py::ssize_t>(p.size()), dim = static_cast<py::ssize_t>(p.dim());
    py::array_t<long long> times(n);
    auto t = times.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) t(i) = i;
    py::array_t<double> q({n, dim});
    std::copy(p.raw().begin(), p.raw().end(), q.mutable_data());
    out.append(py::make_tuple(times, q));
  }
  return out;
}

// MethodOptions with the checks the command line leaves to CLI11, then
// the checks every front end shares; errors name the Python argument.
PlannerSettings settingsFor(const MethodOptions& o) {
  if (!(o.time_limit > 0)) throw InputError("", "time_limit", "must be a positive number of seconds");
  if (!(o.refine >= 0)) throw InputError("", "refine", "must be 0 or more seconds");
  if (o.window && (*o.window < 1 || *o.window > 1000000)) throw InputError("", "window", "must be in 1..1000000");
  if (o.db_k && (*o.db_k < 1 || *o.db_k > 1000)) throw InputError("", "db_k", "must be in 1..1000");
  if (o.db_repair_max && (*o.db_repair_max < 0 || *o.db_repair_max > 1000))
    throw InputError("", "db_repair_max", "must be in 0..1000");
  if (o.db_max_stretch && !(*o.db_max_stretch >= 0)) throw InputError("", "db_max_stretch", "must be 0 or more");
  const PlannerSettings s = plannerSettingsFor(o, OptionStyle::Python);
  if (s.method == Method::Earc && o.db.empty())
    throw InputError("", "db", "method earc needs an experience database file (earc.build_store makes one; a new file name starts empty)");
  if (s.method == Method::Lightning && !o.db.empty() && !o.learn && !std::filesystem::exists(o.db))
    throw InputError(o.db, "db", "no such Lightning database (build one with earc-bench lightning-db)");
  return s;
}

// The plan of `checked`, on this thread (the GIL released by the caller).
PlanResult planUnlocked(const Scenario& checked, const PlannerSettings& s, const MethodOptions& o,
                        const PlanContext& context) {
  if (s.method != Method::Earc) return plan(checked, s, nullptr, context);
  exp::StoreOptions options;
  if (!o.learn) {
    options.read_only = true;
    options.new_session = false;
  }
  auto store = exp::withInputErrors(o.db, [&] { return std::make_unique<exp::ExperienceStore>(o.db, options); });
  PlanResult r = exp::withInputErrors(o.db, [&] { return plan(checked, s, store.get(), context); });
  exp::withInputErrors(o.db, [&] { store->close(); });
  return r;
}

// How often a plan's caller looks for a signal (Ctrl-C) while it waits.
constexpr auto kSignalPoll = std::chrono::milliseconds(50);

// Plans on a worker thread while this one, without the GIL, checks for
// signals: a KeyboardInterrupt (or a handler's exception) stops the plan
// and is raised once the worker has returned.
PyPlan planPy(const Scenario& scenario, const MethodOptions& o) {
  const PlannerSettings s = settingsFor(o);
  const Scenario checked = requireRobots(scenario, "scenario");
  StopFlag stop{false};
  PlanContext context;
  context.stop = &stop;
  PyPlan out;
  bool interrupted = false;
  {
    py::gil_scoped_release unlocked;
    std::future<PlanResult> planned =
        std::async(std::launch::async, [&] { return planUnlocked(checked, s, o, context); });
    while (planned.wait_for(kSignalPoll) != std::future_status::ready) {
      py::gil_scoped_acquire locked;
      if (PyErr_CheckSignals() != 0) {
        interrupted = true;
        break;
      }
    }
    if (interrupted) {
      stop.store(true);
      planned.wait();  // its outcome, error or not, gives way to the signal's
    } else {
      out.result = planned.get();
    }
  }
  if (interrupted) throw py::error_already_set();
  return out;
}

py::object reportToPython(const ValidationReport& r) {
  py::list violations;
  for (const Violation& v : r.violations) {
    py::dict d;
    d["type"] = violationTypeName(v.type);
    d["t"] = v.t;
    d["robots"] = v.robots;
    d["detail"] = v.detail;
    violations.append(d);
  }
  py::dict d;
  d["valid"] = r.valid;
  d["violation_count"] = r.violation_count;
  d["violations"] = violations;
  d["makespan"] = r.makespan;
  d["sum_of_costs"] = r.sum_of_costs;
  d["total_distance"] = r.total_distance;
  return py::module_::import("types").attr("SimpleNamespace")(**d);
}

// validate(scenario, plan result, solution dict or solution file).
py::object validatePy(const Scenario& scenario, const py::object& what) {
  Solution sol;
  if (py::isinstance<PyPlan>(what)) {
    sol = what.cast<const PyPlan&>().result.solution;
  } else if (py::isinstance<py::dict>(what)) {
    InputWarnings warnings;
    sol = solutionFromJson(fromPython(what), &scenario, "solution", &warnings);
    warnAll(warnings);
  } else {
    InputWarnings warnings;
    sol = loadSolution(fsPath(what), &scenario, &warnings);
    warnAll(warnings);
  }
  ValidationReport report;
  {
    py::gil_scoped_release unlocked;
    report = validateSolution(scenario, sol);
  }
  return reportToPython(report);
}

}  // namespace

void bindPlanning(py::module_& m) {
  py::class_<Scenario>(m, "Scenario", "A scenario: workspace, obstacles, robots with start and goal")
      .def_readonly("name", &Scenario::name)
      .def_property_readonly("robots",
                             [](const Scenario& s) {
                               py::list names;
                               for (const RobotSpec& r : s.robots) names.append(r.name);
                               return names;
                             })
      .def("to_dict", [](const Scenario& s) { return toPython(scenarioToJson(s)); },
           "The scenario as its JSON document (earc.scenario.v1)")
      .def("__repr__", [](const Scenario& s) {
        return "<earc.Scenario '" + s.name + "', " + std::to_string(s.robots.size()) + " robots>";
      });

  m.def("load_scenario", &loadAny, py::arg("source"),
        "A scenario from a JSON file (path) or a dict of the same document, checked as earc-plan checks it. "
        "Raises earc.InputError naming the file and field.");

  py::class_<PyPlan>(m, "PlanResult", "What plan() returns")
      .def_property_readonly("success", [](const PyPlan& p) { return p.result.solution.solved; })
      .def_property_readonly("paths", [](const PyPlan& p) { return pathArrays(p.result.solution); },
                             "Per robot, (times, configurations): steps 0..n-1 and an n x dim float array")
      .def_property_readonly("robots", [](const PyPlan& p) { return p.result.solution.robot_names; })
      .def_property_readonly("stats", [](const PyPlan& p) { return toPython(p.result.stats.toJson()); })
      .def_property_readonly("failures",
                             [](const PyPlan& p) {
                               std::vector<std::string> out;
                               for (FailureCause c : p.result.failures) out.push_back(failureCauseName(c));
                               return out;
                             })
      .def_property_readonly("trace", [](const PyPlan& p) { return toPython(p.result.trace); })
      .def("to_dict", [](const PyPlan& p) { return toPython(solutionToJson(p.result.solution)); },
           "The solution as earc-plan writes it (earc.solution.v1)")
      .def("save", [](const PyPlan& p, const py::object& path) { saveSolution(fsPath(path), p.result.solution); },
           py::arg("path"), "Writes the solution file as earc-plan plan -o does")
      .def("__repr__", [](const PyPlan& p) {
        return std::string("<earc.PlanResult ") + (p.result.solution.solved ? "solved" : "not solved") + ", " +
               std::to_string(p.result.solution.paths.size()) + " paths>";
      });

  m.def(
      "plan",
      [](const Scenario& scenario, const std::string& method, std::uint64_t seed, double time_limit, double refine,
         std::optional<py::object> db, bool learn, bool deterministic, std::optional<int> window, bool crowd,
         bool compact, bool trace, bool shadow_decoupled, std::optional<int> db_k, std::optional<int> db_repair_max,
         std::optional<double> db_max_stretch, bool retime_windows) {
        MethodOptions o;
        o.method = method;
        o.seed = seed;
        o.time_limit = time_limit;
        o.refine = refine;
        if (db && !db->is_none()) o.db = fsPath(*db);
        o.learn = learn;
        o.deterministic = deterministic;
        o.window = window;
        o.crowd = crowd;
        o.compact = compact;
        o.retime_windows = retime_windows;
        o.trace = trace;
        o.shadow_decoupled = shadow_decoupled;
        o.db_k = db_k;
        o.db_repair_max = db_repair_max;
        o.db_max_stretch = db_max_stretch;
        return planPy(scenario, o);
      },
      py::arg("scenario"), py::arg("method") = "arc", py::kw_only(), py::arg("seed") = 1,
      py::arg("time_limit") = 60.0, py::arg("refine") = 0.0, py::arg("db") = py::none(), py::arg("learn") = true,
      py::arg("deterministic") = false, py::arg("window") = py::none(), py::arg("crowd") = true,
      py::arg("compact") = false, py::arg("trace") = false, py::arg("shadow_decoupled") = false,
      py::arg("db_k") = py::none(), py::arg("db_repair_max") = py::none(), py::arg("db_max_stretch") = py::none(),
      py::arg("retime_windows") = false,
      "Plans the scenario as `earc-plan plan` does with the same options (--no-learn is learn=False, --no-crowd "
      "crowd=False); the same seed gives the same paths. The GIL is released while planning; Ctrl-C (SIGINT) "
      "stops the plan and raises KeyboardInterrupt.");

  m.def("validate", &validatePy, py::arg("scenario"), py::arg("solution"),
        "Validates a PlanResult, a solution dict or a solution file against the scenario: valid, violations, "
        "makespan, sum_of_costs");
}

}  // namespace earc::python
