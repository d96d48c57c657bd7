// The persistent experience store: an SQLite file of solved subproblems
// (schema/schema.sql) with an in-memory k-d tree per class for k-closest
// retrieval. Several processes may share one file: each keeps its own
// index and brings it up to date with rows the others inserted (refresh);
// writes are short IMMEDIATE transactions retried on SQLITE_BUSY, so no
// insert is lost and none blocks planning for long.
//
// The planner's calls, in order (see also retrieval.hpp, which adds the
// canonical transform around them):
//   ExperienceStore store(path);                 // opens, migrates, indexes
//   store.nearest(cls, key, k)                   // candidates, nearest first
//   store.recordUse(id, resolved_the_conflict)   // buffered counters
//   store.insert(experience, eps)                // learn a new solution
//   store.flush() / destructor                   // write the counters
//
// All public methods are thread-safe (one internal mutex). Never keep a
// store open across fork().
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "earc/experience/experience.hpp"
#include "earc/experience/history.hpp"
#include "earc/experience/key_index.hpp"
#include "earc/experience/row_cache.hpp"
#include "earc/experience/sqlite.hpp"

namespace earc::exp {

class PgConnection;
struct StoreCore;
class StoreBackend;

// How often a PostgreSQL store asks the server for rows other planners
// committed (the highest id seen, polled) before a retrieval; inserts
// always ask, inside their transaction.
inline constexpr std::chrono::milliseconds kPgPollInterval{50};

// The default bound of a store's cache of retrieved rows (RowCache).
inline constexpr std::size_t kDefaultRowCacheBytes = std::size_t{64} << 20;

struct StoreOptions {
  // No migration and no writes (inspect, verify, export). Older schema
  // versions are readable; newer ones are refused.
  bool read_only = false;
  // Count this open as a planning session (store_meta 'sessions'); rows
  // inserted remember it, and curate --older-than-sessions reads it.
  bool new_session = true;
  // Report rows left out of the index on stderr (once per row and file).
  // Whole-file commands turn it off: they read every row and report a bad
  // one in their own single line, or list them (verify), or count them.
  bool warn_skipped = true;
  // SQLite: quick_check in a background thread, not before the constructor
  // returns (a current file of ours only). Writes wait for its verdict and
  // throw its error; awaitCheck() asks for it.
  bool check_in_background = false;
  // With check_in_background: on a machine with no spare core the check
  // runs in the open instead. Off: always in the background.
  bool check_in_open_when_busy = true;
  // SQLite: integrity_check at open instead of quick_check (index contents
  // too), for the offline commands that write; ignores check_in_background.
  bool full_check = false;
  // An empty database in memory instead of the file, which is not touched
  // (the path only names it in messages). Nothing it learns is kept.
  bool in_memory = false;
  // Rows nearest() read are kept decoded, up to this many bytes (RowCache),
  // and served from memory when retrieved again; 0 turns the cache off.
  std::size_t row_cache_bytes = kDefaultRowCacheBytes;
  // PostgreSQL: a store too large to be read whole at open is read in the
  // background and kept packed if it fits row_cache_bytes (a bound of its
  // own, estimated first); retrievals decode the rows they lack from it.
  bool warm_rows = true;
  ConnectionSettings connection;
};

// For whole-file commands (inspect, export, copy, curate): not a planning
// session, and no warning line before their own report or error.
inline StoreOptions wholeFileStoreOptions(bool read_only) {
  StoreOptions o;
  o.read_only = read_only;
  o.new_session = false;
  o.warn_skipped = false;
  o.warm_rows = false;
  return o;
}

// One retrieved experience and its distance to the query key.
struct Match {
  Experience experience;
  double distance = 0.0;
};

// Usage counters are written in one transaction once this many distinct
// rows have pending updates (and on flush() and close()).
inline constexpr std::size_t kMaxPendingUses = 256;
// A passive WAL checkpoint runs after this many write transactions or this
// much time, whichever comes first.
inline constexpr int kCheckpointEveryWrites = 100;
inline constexpr std::chrono::seconds kCheckpointInterval{30};

// The experience store: an SQLite file, or a PostgreSQL database given as a
// libpq URI (isPostgresLocation), with the same methods and promises.
// Thread-safe (one internal mutex).
class ExperienceStore {
 public:
  // Opens (creating when missing, unless read_only), migrates, loads the index.
  // Throws ForeignDatabaseError, SchemaVersionError, StoreError (unreachable
  // server), InputError (read_only and no database); a failed open leaves no file.
  explicit ExperienceStore(const std::string& path, const StoreOptions& options = {});
  // Flushes pending counters; errors are reported on stderr, not thrown.
  ~ExperienceStore();
  ExperienceStore(const ExperienceStore&) = delete;
  ExperienceStore& operator=(const ExperienceStore&) = delete;

  const std::string& path() const;
  int schemaVersion() const;
  // This open's planning session (store_meta 'sessions' after counting it).
  // Waits for a background check, which comes before counting it.
  std::int64_t session();
  bool readOnly() const;

  // Waits for the background quick_check (StoreOptions::check_in_background)
  // and throws DamagedDatabaseError when it failed; returns at once when
  // the check ran at open or has been awaited.
  void awaitCheck();

  // Where this open's structural check ran: in the constructor, or in the
  // background thread, or (a background check starved of CPU) on the
  // thread that awaited it. InOpen for PostgreSQL and once closed.
  enum class CheckRun { InOpen, Background, TakenOver };
  CheckRun checkRun() const;

  // Loads rows other connections committed since the last refresh (all rows
  // again after a deletion anywhere). Cheap when nothing changed: one
  // PRAGMA data_version. nearest() and insert() call it themselves.
  void refresh();

  // Up to k experiences of the class, nearest key first, decoded and checked,
  // the first `skip` of them left out unread; damaged rows are skipped (said
  // once on stderr). Cached rows keep the usage counters they were read with.
  std::vector<Match> nearest(const ExperienceClass& cls, std::span<const double> key, std::size_t k,
                             std::size_t skip = 0);
  // The same search without reading rows: ids and distances only.
  std::vector<Neighbor> nearestIds(const ExperienceClass& cls, std::span<const double> key, std::size_t k);
  // The row as stored now (never from the row cache), or nothing.
  std::optional<Experience> get(std::int64_t id);

  // What nearest() did since the open: calls, rows it returned, and rows it
  // found in the row cache or had to read. Thread-safe.
  struct RetrievalStats {
    std::uint64_t retrievals = 0;
    std::uint64_t rows = 0;
    std::uint64_t cache_hits = 0;
    std::uint64_t cache_misses = 0;
    std::uint64_t warm_hits = 0;  // misses decoded from the background copy (warm_rows)
  };
  RetrievalStats retrievalStats() const;
  // The row cache's size now: rows and their bytes. Thread-safe.
  std::pair<std::size_t, std::size_t> rowCacheSize() const;
  // Waits until the background read of StoreOptions::warm_rows has ended
  // (other calls wait meanwhile); the rows it holds then (0 without one).
  std::size_t awaitWarmRows();

  // Stores e unless its class holds a key within near_duplicate_eps (< 0: no
  // check), checked in the write transaction. Returns the new id, or nothing
  // for a near duplicate; throws std::invalid_argument when findProblem(e).
  std::optional<std::int64_t> insert(const Experience& e, double near_duplicate_eps);
  // insertAll's session for its rows: this session's, or each row's own
  // created_session (an import restoring exported rows).
  enum class SessionStamp { ThisSession, AsGiven };
  // Several experiences in one transaction, each checked against the store
  // and the batch's earlier ones: all stored (or skipped as near duplicates)
  // or, on error, none. Returns insert()'s answer per entry.
  std::vector<std::optional<std::int64_t>> insertAll(const std::vector<Experience>& batch, double near_duplicate_eps,
                                                     SessionStamp stamp = SessionStamp::ThisSession);

  // Counts one retrieval of row id, and one success when it resolved the
  // subproblem. Buffered; written by flush().
  void recordUse(std::int64_t id, bool success);
  void flush();
  // Flush, checkpoint, close. Further calls throw std::logic_error.
  void close();

  std::size_t size() const;
  // Loaded classes with their entry counts and key dimensions.
  struct ClassInfo {
    ExperienceClass cls;
    std::size_t entries = 0;
    std::size_t key_dim = 0;
  };
  std::vector<ClassInfo> classes() const;
  const ClassIndex* classIndex(const ExperienceClass& cls) const;

  // The underlying connection, for maintenance commands (earc-db). Not for
  // the planner: bypasses the index and the mutex. SQLite only
  // (std::logic_error for a PostgreSQL store); pgConnection() the other.
  Connection& connection();
  bool isPostgres() const;
  PgConnection& pgConnection();
  // The last `limit` lines of the store's history, either engine.
  HistoryTail readHistoryLines(int limit);

  // Names this open's line in the store's history (history.hpp; "learn"
  // unless a command describes itself); insert() and insertAll() count
  // their rows on it.
  void describeHistory(std::string operation, std::string detail);
  const HistoryWriter& history() const;

 private:
  void flushLocked();
  void requireOpen() const;
  void requireWritable() const;

  mutable std::mutex mutex_;
  // The engine-independent state and the engine (src/experience/store_backend.hpp);
  // backend_ is null once closed.
  std::unique_ptr<StoreCore> core_;
  std::unique_ptr<StoreBackend> backend_;
};

// The one line, naming `db`, saying that a store with experiences holds
// none for these robots' geometry (E-ARC then plans as ARC); "" when a
// class fits or the store is empty.
std::string noClassFitsWarning(const ExperienceStore& store, const Scenario& scenario, const std::string& db);

}  // namespace earc::exp
