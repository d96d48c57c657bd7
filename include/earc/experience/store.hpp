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
  // Run PRAGMA quick_check on a second connection in a background thread
  // instead of before the constructor returns (planner opens). It reads the
  // whole file: about 0.2 s at 100,000 mobile entries (190 MB), more than
  // the plan it would hold up. Only a file that is already ours, in WAL
  // mode and at the current schema version is opened this way (nothing to
  // migrate or switch). Every write (insert, counter flush) and the
  // session count wait for the check first and throw its error, so a
  // damaged file is still never written to. awaitCheck() asks for the
  // verdict (and counts the session).
  bool check_in_background = false;
  // ... except on a machine with no spare core (runnable threads at least
  // the cores this process may use): there an idle-class thread gets no
  // time, and the check runs in the open instead (src/experience/sqlite_backend.cpp). Off:
  // always in the background (tests of the background path).
  bool check_in_open_when_busy = true;
  // Run PRAGMA integrity_check at open instead of quick_check: index
  // contents too (Connection::requireIntegrityCheck). For the offline
  // commands that write into an existing file (earc-db build, import,
  // curate), which must not add to a damaged one; ignores
  // check_in_background.
  bool full_check = false;
  // A new, empty database in memory instead of the file, which is not
  // touched (the path only names it in messages): for a plan whose
  // database cannot be created (a full disk), which then plans as E-ARC
  // with no experience. Nothing it learns is kept.
  bool in_memory = false;
  // Rows nearest() read are kept decoded, up to this many bytes (RowCache),
  // and served from memory when retrieved again; 0 turns the cache off.
  std::size_t row_cache_bytes = kDefaultRowCacheBytes;
  ConnectionSettings connection;
};

// For whole-file commands (inspect, export, copy, curate): not a planning
// session, and no warning line before their own report or error.
inline StoreOptions wholeFileStoreOptions(bool read_only) {
  StoreOptions o;
  o.read_only = read_only;
  o.new_session = false;
  o.warn_skipped = false;
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

// One store, two engines: `path` is an SQLite file, or a PostgreSQL
// database given as a libpq URI (postgresql://USER@HOST:PORT/DBNAME;
// isPostgresLocation), which the same methods read and write with the same
// promises (docs/experience-postgresql.md). The k-d trees, the row cache
// and the duplicate check are shared (StoreCore); each engine is a
// StoreBackend (src/experience/store_backend.hpp).
class ExperienceStore {
 public:
  // Opens (creating when missing, unless read_only) and loads the index.
  // A PostgreSQL location: connects (a one-line StoreError naming it when
  // the server cannot be reached), checks identity, migrates, loads.
  // Throws ForeignDatabaseError, SchemaVersionError, StoreError; read_only,
  // InputError for a file that is missing or no database yet
  // (requireDatabaseFile). A file this open created is removed again when
  // the open fails before anything was committed to it (a full disk): a
  // new database appears whole or not at all, never as an empty file.
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

  // Up to k experiences of the class, nearest key first (Euclidean), decoded
  // and checked. Rows that fail decoding are skipped and reported once on
  // stderr (earc-db verify names them all). The first `skip` of the k
  // nearest are left out, unread: a caller that wants more after trying
  // the k nearest asks for the next ones without reading those again. Rows
  // read before come from the row cache, usage counters as they were then.
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
  };
  RetrievalStats retrievalStats() const;
  // The row cache's size now: rows and their bytes. Thread-safe.
  std::pair<std::size_t, std::size_t> rowCacheSize() const;

  // Stores e unless an entry of its class lies within near_duplicate_eps in
  // key space (distance <= eps; eps < 0 disables the check), checked inside
  // the write transaction after loading every committed row. Sets id,
  // created_session and (when 0) created_at. Returns the new id, or nothing
  // for a near duplicate. Throws std::invalid_argument when findProblem(e).
  std::optional<std::int64_t> insert(const Experience& e, double near_duplicate_eps);
  // Several experiences in ONE transaction, each checked against the store
  // and the batch's earlier entries: all are stored (or skipped as
  // duplicates) or, on error, none. SessionStamp::AsGiven keeps each row's
  // created_session (an import restoring exported rows) instead of this
  // session's.
  enum class SessionStamp { ThisSession, AsGiven };
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

  // This open's line in the file's history (history.hpp): "learn" in the
  // planning session unless a command describes itself (build, import,
  // curate). insert() and insertAll() count their rows on it in their own
  // transaction; a maintenance command that changes rows through
  // connection() records them itself, inside its transaction.
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

// A database that holds experiences, none of them for these robots'
// geometry, answers nothing: E-ARC then plans as ARC does (and learns).
// The one line that says so, naming `db`, or "" when a class fits or the
// store is empty (a new file is expected to start so).
std::string noClassFitsWarning(const ExperienceStore& store, const Scenario& scenario, const std::string& db);

}  // namespace earc::exp
