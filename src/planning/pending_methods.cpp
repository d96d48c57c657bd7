// Lightning is being built (benchmark issue); until then asking for it is a
// clear error, never a fake result.
#include <stdexcept>

#include "earc/planning/methods.hpp"

namespace earc {

PlanResult planLightning(const Scenario&, const PlannerSettings&) {
  throw std::runtime_error("method 'lightning' is not available in this build yet");
}

}  // namespace earc
