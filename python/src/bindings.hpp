// The Python module's parts, bound by module.cpp.
#pragma once

#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace earc::python {

namespace py = pybind11;

// A JSON value as the Python value json.loads gives for its text.
py::object toPython(const nlohmann::json& value);
// A Python value (dict, list, str, numbers, bool, None) as JSON; throws
// py::type_error for anything json.dumps refuses.
nlohmann::json fromPython(const py::handle& value);

// Scenarios, plan(), results and validate().
void bindPlanning(py::module_& m);
// Experience stores: open, build, inspect, export, import.
void bindStore(py::module_& m);

}  // namespace earc::python
