// `import earc`: load a scenario, plan it, validate the plan, use an
// experience store. Errors are Python exceptions carrying the programs'
// one-line messages: earc.InputError (a ValueError) for bad input.
#include <string>

#include "bindings.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/version.hpp"

PYBIND11_MODULE(earc, m) {
  namespace py = pybind11;
  m.doc() = "E-ARC multi-robot motion planning: scenarios, plans, validation, experience stores";
  m.attr("__version__") = earc::version();
  static py::exception<earc::InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const earc::InputError& e) {
      input_error(e.what());
    }
  });
  earc::python::bindPlanning(m);
  earc::python::bindStore(m);
}
