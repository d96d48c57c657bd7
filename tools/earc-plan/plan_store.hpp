// Opening the experience store for `earc-plan plan` (E-ARC only).
#pragma once

#include <memory>
#include <string>

#include "earc/planning/planner.hpp"

namespace earc {

// An InputError naming --db when method is earc and db is empty: a check of
// the options alone, which touches no file (openStoreForPlanning makes it
// too).
void requireDatabaseFor(Method method, const std::string& db);

// The store for method earc (an InputError when --db is missing or the file
// is refused); nullptr for every other method. Without learn it is opened
// read-only: the file stays as it was, byte for byte (no session count, no
// usage counters), and must exist. Its quick_check runs in the background
// (StoreOptions::check_in_background): call awaitCheck() before using the
// plan. With full_disk, a disk too full for the open's writes (creating
// the file, migrating it, counting the session) is no error: the store is
// the file opened read-only, or, when the file could not be created, an
// empty one in memory, and *full_disk says so in a line naming the file.
std::shared_ptr<exp::ExperienceStore> openStoreForPlanning(Method method, const std::string& db, bool learn,
                                                           std::string* full_disk = nullptr);

}  // namespace earc
