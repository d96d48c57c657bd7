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

// The store for method earc (InputError when --db is missing or the file is
// refused), else nullptr; read-only without learn; row_cache_bytes bounds its
// row cache (0: off). Call awaitCheck() before using the plan. full_disk: .cpp.
std::shared_ptr<exp::ExperienceStore> openStoreForPlanning(Method method, const std::string& db, bool learn,
                                                           std::size_t row_cache_bytes,
                                                           std::string* full_disk = nullptr);

// The option --db-row-cache-mb N of plan and serve, into `mib`: the bound
// of the store's row cache in MiB (0: off). rowCacheBytes: the bound in
// bytes, StoreOptions' default when the option was not given.
void addRowCacheOption(CLI::App& cmd, std::optional<std::size_t>& mib);
std::size_t rowCacheBytes(const std::optional<std::size_t>& mib);

}  // namespace earc
