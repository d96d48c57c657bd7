// E-ARC and Lightning are being built (experience-store and benchmark
// issues); until then asking for them is a clear error, never a fake result.
#include <stdexcept>

#include "earc/planning/methods.hpp"

namespace earc {

PlanResult planEarc(const Scenario&, const PlannerSettings&, exp::ExperienceStore*) {
  throw std::runtime_error("method 'earc' is not available in this build yet");
}

PlanResult planLightning(const Scenario&, const PlannerSettings&) {
  throw std::runtime_error("method 'lightning' is not available in this build yet");
}

}  // namespace earc
