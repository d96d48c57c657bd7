// Opening the experience store for `earc-plan plan` (E-ARC only).
#pragma once

#include <memory>
#include <string>

#include "earc/planning/planner.hpp"

namespace earc {

// The store for method earc (an InputError when --db is missing or the file
// is refused); nullptr for every other method.
std::shared_ptr<exp::ExperienceStore> openStoreForPlanning(Method method, const std::string& db);

}  // namespace earc
