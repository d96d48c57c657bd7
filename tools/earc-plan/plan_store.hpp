// Opening the experience store for `earc-plan plan` and `serve` (E-ARC only),
// and their option --db-row-cache-mb.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "earc/experience/store.hpp"
#include "earc/planning/planner.hpp"

namespace CLI {
class App;
}

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
// row_cache_bytes bounds the store's cache of retrieved rows (0: off).
std::shared_ptr<exp::ExperienceStore> openStoreForPlanning(Method method, const std::string& db, bool learn,
                                                           std::size_t row_cache_bytes,
                                                           std::string* full_disk = nullptr);

// The option --db-row-cache-mb N of plan and serve, into `mib`: the bound
// of the store's row cache in MiB (0: off). rowCacheBytes: the bound in
// bytes, StoreOptions' default when the option was not given.
void addRowCacheOption(CLI::App& cmd, std::optional<std::size_t>& mib);
std::size_t rowCacheBytes(const std::optional<std::size_t>& mib);

}  // namespace earc
