#include "plan_store.hpp"

#include <filesystem>

#include "earc/cli/subcommands.hpp"
#include "earc/experience/pg_connection.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"

namespace earc {

namespace {

// The store; with full_disk, a disk too full for the open's writes falls
// back as said above openStoreForPlanning.
std::shared_ptr<exp::ExperienceStore> openStore(const std::string& db, const exp::StoreOptions& options,
                                                std::string* full_disk) {
  try {
    return std::make_shared<exp::ExperienceStore>(db, options);
  } catch (const InputError&) {
    throw;
  } catch (const exp::NoSpaceError& e) {
    if (!full_disk) throw InputError(db, "database", exp::withoutFile(e.what(), db));
    // The open had to write (create the file, switch it to WAL, migrate
    // it, count the session) and the disk had no room: the plan is made
    // all the same, without learning. A file that holds a database is
    // read as it is; one that could not be created (the store removed
    // what it made) is an empty database in memory: E-ARC then plans as
    // ARC does.
    std::error_code ec;
    const bool there = std::filesystem::file_size(db, ec) > 0 && !ec;
    exp::StoreOptions fallback;
    fallback.row_cache_bytes = options.row_cache_bytes;
    fallback.new_session = false;
    fallback.check_in_background = there;
    fallback.read_only = there;
    fallback.in_memory = !there;
    *full_disk = db + ": " + exp::kDiskFull +
                 (there ? "; E-ARC planned with what the database holds and learned nothing"
                        : ", so the database could not be created; E-ARC planned as ARC does, with no experience, "
                          "and learned nothing");
    return openStore(db, fallback, nullptr);
  } catch (const std::exception& e) {
    // Foreign, newer or damaged files: one line naming the file, nothing written.
    const std::string named = exp::isPostgresLocation(db) ? exp::maskedLocation(db) : db;
    throw InputError(named, "database", exp::withoutFile(e.what(), named));
  }
}

}  // namespace

void requireDatabaseFor(Method method, const std::string& db) {
  if (method == Method::Earc && db.empty())
    throw InputError("", "--db", "method earc needs an experience database file (earc-db build makes one; a new file name starts empty)");
}

// Without learn the file stays as it was, byte for byte (no session count,
// no usage counters), and must exist. Its quick_check runs in the
// background (StoreOptions::check_in_background). With full_disk, a disk
// too full for the open's writes (creating the file, migrating it,
// counting the session) is no error: the store is the file opened
// read-only, or, when the file could not be created, an empty one in
// memory, and *full_disk says so in a line naming the file.
std::shared_ptr<exp::ExperienceStore> openStoreForPlanning(Method method, const std::string& db, bool learn,
                                                           std::size_t row_cache_bytes, std::string* full_disk) {
  if (method != Method::Earc) return nullptr;
  requireDatabaseFor(method, db);
  exp::StoreOptions options;
  options.row_cache_bytes = row_cache_bytes;
  options.check_in_background = true;
  if (!learn) {
    options.read_only = true;
    options.new_session = false;
  }
  return openStore(db, options, full_disk);
}

void addRowCacheOption(CLI::App& cmd, std::optional<std::size_t>& mib) {
  cmd.add_option("--db-row-cache-mb", mib,
                 "E-ARC: keep up to this many MiB of retrieved experiences decoded in memory, and a PostgreSQL "
                 "store that fits in half of it whole from the open, a larger one packed in the background when "
                 "it fits (0: off; default " +
                     std::to_string(exp::kDefaultRowCacheBytes >> 20) + ")")
      ->check(cli::wholeNumberIn(0, 65536));
}

std::size_t rowCacheBytes(const std::optional<std::size_t>& mib) {
  return mib ? *mib << 20 : exp::kDefaultRowCacheBytes;
}

}  // namespace earc
