// Inside ExperienceStore: its engine-independent state and logic
// (StoreCore: the k-d trees, the row cache, the duplicate check, the row
// checks) and the engine it reads and writes through (StoreBackend: an
// SQLite file or a PostgreSQL database). Not a public header.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "earc/experience/store.hpp"

namespace earc::exp {

using StoredIds = std::vector<std::optional<std::int64_t>>;
using SessionStamp = ExperienceStore::SessionStamp;
// Rows read by id, those found only (a deleted or undecodable row is left out).
using SharedRows = std::vector<std::shared_ptr<const Experience>>;

// What a store knows whichever engine holds its rows. Not thread-safe:
// ExperienceStore's mutex guards it.
struct StoreCore {
  StoreCore(std::string location, const StoreOptions& opts);

  std::string path;
  StoreOptions options;
  int version = 0;           // the schema version, set by the backend
  std::int64_t session = 0;  // this open's planning session
  KeyIndex index;
  RowCache row_cache;
  std::int64_t max_loaded = 0;        // the highest id indexed
  std::int64_t loaded_deletions = -1;  // store_meta 'deletions' when loaded
  std::uint64_t retrievals = 0;
  std::uint64_t rows_returned = 0;
  std::uint64_t warm_hits = 0;
  std::map<std::int64_t, std::pair<std::int64_t, std::int64_t>> pending_uses;  // id -> (retrieved, succeeded)
  HistoryWriter history;
  bool history_described = false;  // else "learn", "planning session N"

  // Indexes one row's key, or reports it skipped (warnSkipped) when it
  // does not fit its class.
  void indexKeyRow(std::int64_t id, const std::string& kind, std::int64_t robot_count, std::string signature,
                   std::string base_class, std::span<const unsigned char> key_blob);
  // After a deletion anywhere: the index and the row cache start afresh.
  void forgetRows();
  // Reports a row left out on stderr, once per store and row (warn_skipped).
  void warnSkipped(std::int64_t id, const std::string& why) const;
  // near[skip..] as matches, nearest first: rows from the row cache, the
  // others read by `read` (given their ids) and cached.
  std::vector<Match> matches(const std::vector<Neighbor>& near, std::size_t skip,
                             const std::function<SharedRows(const std::vector<std::int64_t>&)>& read);
  // The batch stamped for storing. Throws std::invalid_argument when findProblem.
  std::vector<Experience> prepareRows(const std::vector<Experience>& batch, SessionStamp stamp) const;
  // Indices of the rows to store: those with no entry of their class within
  // eps, in the index or earlier in the batch. Call with every committed row
  // loaded. Throws std::invalid_argument for a key of the wrong dimension.
  std::vector<std::size_t> novelRows(const std::vector<Experience>& rows, double eps) const;
  // Committed rows enter the index.
  void indexInserted(const std::vector<Experience>& rows, const StoredIds& ids);
  // Names this open's history line "learn" unless a command described it.
  void describeLearning();
};

// One engine's reads and writes for ExperienceStore. Its constructor opens
// the store (identity, migration, session, first load into the core); the
// destructor closes it. Not thread-safe: ExperienceStore's mutex guards it.
class StoreBackend {
 public:
  explicit StoreBackend(StoreCore& core) : core_(core) {}
  virtual ~StoreBackend() = default;
  StoreBackend(const StoreBackend&) = delete;
  StoreBackend& operator=(const StoreBackend&) = delete;

  // Loads rows committed elsewhere into the core's index. `force`: now,
  // even where the engine polls at intervals.
  virtual void refresh(bool force) = 0;
  // Runs `search` (a refresh and a lookup) as one read; the engine's
  // answer to a store that fails meanwhile.
  virtual std::vector<Match> retrieve(const std::function<std::vector<Match>()>& search) = 0;
  // The rows with these ids as stored now; one that fails decoding is
  // reported (warnSkipped) and left out.
  virtual SharedRows readRows(const std::vector<std::int64_t>& ids) = 0;
  virtual std::optional<Experience> fetch(std::int64_t id) = 0;
  // Before any write: waits for a background check, throwing its error.
  virtual void awaitCheck() {}
  virtual ExperienceStore::CheckRun checkRun() const { return ExperienceStore::CheckRun::InOpen; }
  // Whether a background check is still running (a write would wait for it).
  virtual bool checkRunning() const { return false; }
  // Stores the prepared rows that are no near duplicates in one
  // transaction (refreshing inside it), with the history line's count;
  // their ids, nothing for a duplicate.
  virtual StoredIds insert(const std::vector<Experience>& rows, double eps, SessionStamp stamp) = 0;
  // Adds the pending usage counters in one transaction.
  virtual void writeUses(const std::map<std::int64_t, std::pair<std::int64_t, std::int64_t>>& uses) = 0;
  // After each write transaction (insert, counters).
  virtual void afterWrite() {}
  // Before close flushes: false when nothing may be written (a damaged
  // file whose error was thrown before); may throw that error.
  virtual bool readyToClose() { return true; }
  // After close flushed (a writable store).
  virtual void closeWritable() {}
  virtual HistoryTail readHistory(int limit) = 0;
  // Waits for a background read of the rows; the rows it holds (0: none).
  virtual std::size_t awaitWarmRows() { return 0; }
  // The engine's connection, or null for the other engine.
  virtual Connection* sqliteConnection() { return nullptr; }
  virtual PgConnection* pgConnection() { return nullptr; }

 protected:
  StoreCore& core_;
};

// Open the store core.path (ExperienceStore's constructor has the contract).
std::unique_ptr<StoreBackend> openSqliteBackend(StoreCore& core);
std::unique_ptr<StoreBackend> openPgBackend(StoreCore& core);

}  // namespace earc::exp
