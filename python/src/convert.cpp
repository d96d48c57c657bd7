#include <string>

#include "bindings.hpp"

namespace earc::python {

// Through the text: exact for every double (shortest round trip both
// ways) and no second walk over two type systems to keep in step.
py::object toPython(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

nlohmann::json fromPython(const py::handle& value) {
  const std::string text = py::module_::import("json").attr("dumps")(value).cast<std::string>();
  return nlohmann::json::parse(text);
}

}  // namespace earc::python
