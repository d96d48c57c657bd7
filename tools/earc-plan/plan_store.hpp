// Opening the experience store for `earc-plan plan` (E-ARC only).
#pragma once

#include <memory>
#include <string>

#include "earc/planning/planner.hpp"

namespace earc {

// The store for method earc (an InputError when --db is missing or the file
// is refused); nullptr for every other method. Without learn it is opened
// read-only: the file stays as it was, byte for byte (no session count, no
// usage counters), and must exist. Its quick_check runs in the background
// (StoreOptions::check_in_background): call awaitCheck() before using the
// plan.
std::shared_ptr<exp::ExperienceStore> openStoreForPlanning(Method method, const std::string& db, bool learn);

}  // namespace earc
