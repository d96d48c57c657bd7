// Experience stores for Python: open one (for plan(db=...) or to look
// inside), build one, inspect, verify, export and import. Store errors
// become earc.InputError naming the file, as the programs say them.
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/store.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/io/input_error.hpp"
#include "earc/methods/builder.hpp"

namespace earc::python {

namespace {

std::string pathOf(const py::object& p) { return py::str(py::module_::import("os").attr("fspath")(p)); }

// An open store; closed by close(), by `with`, or when collected.
class PyStore {
 public:
  PyStore(const std::string& path, bool read_only) {
    exp::StoreOptions options;
    options.read_only = read_only;
    options.new_session = false;
    store_ = exp::withInputErrors(path, [&] { return std::make_unique<exp::ExperienceStore>(path, options); });
  }
  exp::ExperienceStore& get() {
    if (!store_) throw std::runtime_error("the experience store is closed");
    return *store_;
  }
  void close() {
    if (!store_) return;
    const std::string path = store_->path();
    exp::withInputErrors(path, [&] { store_->close(); });
    store_.reset();
  }

 private:
  std::unique_ptr<exp::ExperienceStore> store_;
};

py::list classesOf(exp::ExperienceStore& store) {
  py::list out;
  for (const auto& c : store.classes()) {
    py::dict d;
    d["label"] = c.cls.label();
    d["entries"] = c.entries;
    d["key_dim"] = c.key_dim;
    out.append(d);
  }
  return out;
}

// build_store's settings from a scenario, as `earc-db build --scenario` takes them.
exp::BuildSettings settingsFromScenario(const Scenario& s, const std::optional<std::string>& kind) {
  exp::BuildSettings b;
  b.resolution = s.resolution;
  const auto arms = std::count_if(s.robots.begin(), s.robots.end(),
                                  [](const RobotSpec& r) { return r.kind == RobotKind::Manipulator; });
  if (kind) {
    if (*kind != "mobile" && *kind != "arms") throw InputError("", "kind", "expected mobile or arms");
    b.kind = *kind == "arms" ? RobotKind::Manipulator : RobotKind::Mobile;
  } else {
    if (arms > 0 && arms < static_cast<std::ptrdiff_t>(s.robots.size()))
      throw InputError("scenario", "$.robots", "holds mobile robots and arms: say which with kind");
    b.kind = arms > 0 ? RobotKind::Manipulator : RobotKind::Mobile;
  }
  if (b.kind == RobotKind::Mobile) {
    const exp::Footprints fleet = exp::scenarioFootprints(s);
    if (fleet.robots.empty()) throw InputError("scenario", "$.robots", "no mobile robot to build for");
    b.mobile_robots = fleet.robots;
    b.mobile_shares = fleet.counts;
  } else {
    for (const auto& r : s.robots)
      if (r.kind == RobotKind::Manipulator) b.arms.push_back(r);
    if (b.arms.size() < 2) throw InputError("scenario", "$.robots", "fewer than two arms to build for");
    if (exp::armPairClasses(b.arms, b.resolution).empty())
      throw InputError("scenario", "$.robots", exp::noArmPairClassReason(b.arms));
  }
  return b;
}

py::dict buildStore(const py::object& path_obj, const Scenario* scenario, std::optional<std::string> kind, int count,
                    std::uint64_t seed, int threads, double time_per_problem, bool deterministic, double dedupe) {
  const std::string path = pathOf(path_obj);
  exp::BuildSettings s;
  if (scenario) {
    s = settingsFromScenario(*scenario, kind);
  } else if (kind) {
    if (*kind != "mobile" && *kind != "arms") throw InputError("", "kind", "expected mobile or arms");
    s.kind = *kind == "arms" ? RobotKind::Manipulator : RobotKind::Mobile;
  }
  if (count < 0) throw InputError("", "count", "must be 0 (the default count) or more");
  if (threads < 1 || threads > 256) throw InputError("", "threads", "must be in 1..256");
  if (!(time_per_problem > 0)) throw InputError("", "time_per_problem", "must be a positive number of seconds");
  s.count = count;
  s.seed = seed;
  s.threads = threads;
  s.time_per_problem_s = time_per_problem;
  s.work_budgets = deterministic;
  s.near_duplicate_eps = dedupe;
  exp::BuildReport r;
  {
    py::gil_scoped_release unlocked;
    r = exp::withInputErrors(path, [&] {
      exp::StoreOptions options;
      options.new_session = false;
      options.full_check = true;
      exp::ExperienceStore store(path, options);
      exp::BuildReport report = exp::buildDatabase(store, s);
      store.close();
      return report;
    });
  }
  py::dict d;
  d["problems"] = r.problems;
  d["solved"] = r.solved;
  d["inserted"] = r.inserted;
  d["duplicates"] = r.duplicates;
  d["unsolved"] = r.unsolved;
  d["no_query"] = r.no_query;
  d["seconds"] = r.seconds;
  d["inserted_per_class"] = r.inserted_per_class;
  return d;
}

}  // namespace

void bindStore(py::module_& m) {
  py::class_<PyStore>(m, "ExperienceStore", "An open experience database (SQLite)")
      .def_property_readonly("path", [](PyStore& s) { return s.get().path(); })
      .def_property_readonly("schema_version", [](PyStore& s) { return s.get().schemaVersion(); })
      .def_property_readonly("read_only", [](PyStore& s) { return s.get().readOnly(); })
      .def("__len__", [](PyStore& s) { return s.get().size(); })
      .def("classes", [](PyStore& s) { return classesOf(s.get()); },
           "Each class held: label, entries, key_dim")
      .def("close", &PyStore::close)
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](PyStore& s, py::args) { s.close(); });

  m.def(
      "open_store", [](const py::object& path, bool read_only) { return std::make_unique<PyStore>(pathOf(path), read_only); },
      py::arg("path"), py::arg("read_only") = false,
      "Opens (creating unless read_only) an experience database; earc.InputError for a file that is not one");

  m.def("build_store", &buildStore, py::arg("path"), py::arg("scenario") = nullptr, py::kw_only(),
        py::arg("kind") = py::none(), py::arg("count") = 0, py::arg("seed") = 1, py::arg("threads") = 2,
        py::arg("time_per_problem") = 0.5, py::arg("deterministic") = false, py::arg("dedupe") = 1e-3,
        "Fills the database at path with solved random subproblems, as `earc-db build` does (for the "
        "scenario's robots when given); returns the build's counts. The GIL is released while building.");

  m.def(
      "inspect_store",
      [](const py::object& path, int samples) {
        const std::string p = pathOf(path);
        return toPython(exp::inspectJson(exp::withInputErrors(p, [&] { return exp::inspectDatabase(p, samples); })));
      },
      py::arg("path"), py::arg("samples") = 0,
      "What `earc-db inspect --json` reports (earc.inspect.v1), read without writing");

  m.def(
      "verify_store",
      [](const py::object& path) {
        const exp::VerifyReport r = exp::verifyDatabase(pathOf(path));
        py::dict d;
        d["ok"] = r.ok();
        d["schema_version"] = r.schema_version;
        d["rows"] = r.rows;
        d["problems"] = r.problems;
        d["notes"] = r.notes;
        return d;
      },
      py::arg("path"), "Checks every row of the database, as `earc-db verify` does");

  m.def(
      "export_store",
      [](const py::object& path, const py::object& out) {
        const std::string p = pathOf(path), o = pathOf(out);
        py::gil_scoped_release unlocked;
        return exp::withInputErrors(p, [&] { return exp::exportJsonl(p, o); });
      },
      py::arg("path"), py::arg("out"), "Writes every row as JSON lines (earc.experiences.v1); returns the row count");

  m.def(
      "import_store",
      [](PyStore& store, const std::vector<std::string>& inputs) {
        exp::ImportReport r;
        {
          py::gil_scoped_release unlocked;
          r = exp::importInto(store.get(), inputs);
        }
        py::dict d;
        d["read"] = r.read;
        d["inserted"] = r.inserted;
        d["already_stored"] = r.already_stored;
        return d;
      },
      py::arg("store"), py::arg("inputs"), "Adds every row of exports or databases, all or none");
}

}  // namespace earc::python
