// ExperienceStore's SQLite engine: one file, shared by the processes of one
// machine. Other connections' rows are found through PRAGMA data_version;
// writes are IMMEDIATE transactions retried on SQLITE_BUSY.
#include "sqlite_backend.hpp"

#include <sched.h>

#include <cstdio>
#include <filesystem>

#include "earc/experience/maintenance.hpp"
#include "earc/experience/rows.hpp"
#include "earc/experience/schema.hpp"

namespace earc::exp {

namespace {

// Whether fewer threads are runnable on the machine (procs_running in
// /proc/stat, this one included) than this process may use cores: a core
// would otherwise idle. True where it cannot be read.
bool spareCore() {
  cpu_set_t cpus;
  if (sched_getaffinity(0, sizeof cpus, &cpus) != 0) return true;
  std::FILE* f = std::fopen("/proc/stat", "r");
  if (!f) return true;
  char line[256];
  long running = -1;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "procs_running %ld", &running) == 1) break;
  std::fclose(f);
  return running < 0 || running < CPU_COUNT(&cpus);
}

// Resets a cached statement however the scope is left.
struct ResetStatementOnExit {
  Statement& s;
  ~ResetStatementOnExit() { s.reset(); }
};

}  // namespace

std::unique_ptr<StoreBackend> openSqliteBackend(StoreCore& core) { return std::make_unique<SqliteBackend>(core); }

SqliteBackend::SqliteBackend(StoreCore& core)
    : StoreBackend(core), last_checkpoint_(std::chrono::steady_clock::now()) {
  // Whether this open creates the file (SQLite creates it, empty, when it
  // opens it, before the first write can fail).
  const StoreOptions& options = core_.options;
  std::error_code ec;
  const std::string real = databaseFile(core_.path);
  const bool creating =
      !options.read_only && !options.in_memory && !std::filesystem::exists(std::filesystem::symlink_status(real, ec));
  try {
    open();
  } catch (...) {
    dropCheck();  // no destructor will
    if (creating) discardCreated(real);
    throw;
  }
}

SqliteBackend::~SqliteBackend() { dropCheck(); }

void SqliteBackend::discardCreated(const std::string& real) {
  // Nothing committed: no schema (another process creating the same file
  // at the same time may have committed its own, which stays).
  bool committed = true;
  if (conn_) {
    try {
      committed = checkIdentity(*conn_) != 0;
    } catch (const std::exception&) {
      // unreadable: left as it is
    }
  } else {
    std::error_code ec;
    committed = std::filesystem::file_size(real, ec) != 0 || ec;
  }
  fetch_.reset();
  data_version_.reset();
  conn_.reset();
  if (!committed) removeDatabaseFiles(real);
}

void SqliteBackend::open() {
  const StoreOptions& options = core_.options;
  const std::string& path = core_.path;
  const OpenMode mode = options.in_memory   ? OpenMode::Memory
                        : options.read_only ? OpenMode::ReadOnly
                                            : OpenMode::ReadWrite;
  if (options.read_only) requireDatabaseFile(path);  // else SQLite's "unable to open database file"
  ConnectionSettings settings = options.connection;
  settings.own_application_id = kApplicationId;
  conn_ = std::make_unique<Connection>(path, mode, settings);
  // Identity first: never switch a foreign file to WAL or write to it.
  // Another process creating the same file may make these steps busy.
  core_.version = conn_->retryWhileBusy([&] { return checkIdentity(*conn_); });
  // Then the file's structure, before anything is written to it or read
  // from it: a truncated or damaged file is refused here, naming the first
  // problem, instead of failing some later query mid-plan. A planner may
  // have it checked in the background instead, when opening needs no write
  // (our WAL file at the current version): then every write waits for it.
  // An offline writer checks index contents too (full_check).
  // Not on a machine without a spare core: there the idle-class thread
  // gets no time, and while it waits for some it can hold SQLite's
  // process-wide locks that this connection needs; the check runs here.
  // quick_check reads the whole file (longer than the plan it would hold
  // up); in the background, writes still wait for it, so a damaged file is
  // never written to. Only a current file of ours (nothing to migrate).
  const bool background = options.check_in_background && !options.full_check &&
                          (!options.check_in_open_when_busy || spareCore()) &&
                          core_.version == currentSchemaVersion() &&
                          conn_->retryWhileBusy([&] { return conn_->pragmaText("journal_mode"); }) == "wal";
  if (background) {
    startCheck();
    check_run_ = ExperienceStore::CheckRun::Background;
  } else if (options.full_check) {
    conn_->retryWhileBusy([&] { conn_->requireIntegrityCheck(); });
  } else {
    conn_->retryWhileBusy([&] { conn_->requireQuickCheck(); });
  }
  if (options.read_only) {
    if (core_.version == 0) throw notYetADatabase(path);
  } else if (!background) {
    if (!options.in_memory) conn_->retryWhileBusy([&] { conn_->enableWal(); });
    core_.version = migrate(*conn_);
  }
  core_.session = meta("sessions");
  if (!options.read_only && options.new_session) {
    session_pending_ = true;
    if (!background) awaitCheck();
  }
  fetch_ = std::make_unique<Statement>(conn_->prepare(selectExperiencesSql(core_.version) + " WHERE id = ?1"));
  data_version_ = std::make_unique<Statement>(conn_->prepare("PRAGMA data_version"));
  refresh(true);
}

std::int64_t SqliteBackend::meta(const char* name) {
  if (core_.version < 2) return 0;  // store_meta arrived with migration 2
  Statement s = conn_->prepare("SELECT value FROM store_meta WHERE name = ?1");
  s.bind(1, std::string_view(name));
  std::int64_t v = s.step() ? s.int64At(0) : 0;
  s.reset();
  return v;
}

void SqliteBackend::awaitCheck() {
  joinCheck();
  if (session_pending_) {
    core_.session = conn_->write([&] {
      conn_->exec("UPDATE store_meta SET value = value + 1 WHERE name = 'sessions'");
      return meta("sessions");
    });
    session_pending_ = false;
  }
}

void SqliteBackend::refresh(bool /*force: data_version costs nothing*/) {
  std::int64_t dv = 0;
  {
    ResetStatementOnExit guard{*data_version_};
    dv = data_version_->step() ? data_version_->int64At(0) : 0;
  }
  if (dv == loaded_data_version_) return;  // no other connection committed
  loaded_data_version_ = dv;
  const std::int64_t deletions = meta("deletions");
  if (deletions != core_.loaded_deletions) {
    // Rows were deleted somewhere: the index may point at them; reload all.
    core_.forgetRows();
    core_.loaded_deletions = deletions;
  }
  loadTail();
}

void SqliteBackend::loadTail() {
  // Version 3 has a covering index: the scan never touches the path blobs.
  Statement s = conn_->prepare(std::string("SELECT id, kind, robot_count, signature, base_class, key FROM experiences") +
                               (core_.version >= 3 ? " INDEXED BY experiences_keys" : "") +
                               " WHERE id > ?1 ORDER BY id");
  s.bind(1, core_.max_loaded);
  while (s.step()) core_.indexKeyRow(s.int64At(0), s.textAt(1), s.int64At(2), s.textAt(3), s.textAt(4), s.blobAt(5));
  core_.index.settle();
}

std::vector<Match> SqliteBackend::retrieve(const std::function<std::vector<Match>()>& search) {
  return conn_->read(search);
}

SharedRows SqliteBackend::readRows(const std::vector<std::int64_t>& ids) {
  SharedRows rows;
  for (const std::int64_t id : ids) {
    try {
      if (auto e = fetch(id)) rows.push_back(std::make_shared<const Experience>(std::move(*e)));
    } catch (const CorruptRowError& e) {
      core_.warnSkipped(id, e.reason());
    } catch (const DamagedDatabaseError& e) {
      // A check still running in the background has the verdict on the
      // whole file: a damaged file ends planning with its error.
      // (Only the verdict: this is a read transaction, no place to write.)
      joinCheck();
      // The file was damaged after it was opened (quick_check passed
      // then): this row cannot be read; planning goes on without it.
      core_.warnSkipped(id, e.what());
    }
  }
  return rows;
}

std::optional<Experience> SqliteBackend::fetch(std::int64_t id) {
  ResetStatementOnExit guard{*fetch_};
  fetch_->bind(1, id);
  if (!fetch_->step()) return std::nullopt;
  return readExperience(*fetch_);
}

StoredIds SqliteBackend::insert(const std::vector<Experience>& rows, double eps, SessionStamp stamp) {
  return conn_->write([&] {
    // Inside the write lock: every committed row is loaded, and nobody can
    // insert until we commit, so the duplicate check sees everything.
    refresh(true);
    Statement insert = conn_->prepare(insertExperienceSql());
    StoredIds ids(rows.size());
    std::int64_t stored = 0;
    for (const std::size_t i : core_.novelRows(rows, eps)) {
      bindExperience(insert, rows[i]);
      insert.run();
      insert.reset();
      ids[i] = sqlite3_last_insert_rowid(conn_->handle());
      ++stored;
    }
    // Rows kept with their sessions (an import restoring an export into an
    // empty file): the file has seen at least the latest of them, so that
    // curate --older-than-sessions judges the copy as it judged the
    // original (unless the original's last sessions learned nothing).
    if (stamp == SessionStamp::AsGiven)
      conn_->exec(
          "UPDATE store_meta SET value = max(value, (SELECT coalesce(max(created_session), 0) FROM experiences)) "
          "WHERE name = 'sessions'");
    core_.describeLearning();
    core_.history.record(*conn_, core_.version, stored, 0);
    return ids;
  });
}

void SqliteBackend::writeUses(const std::map<std::int64_t, std::pair<std::int64_t, std::int64_t>>& uses) {
  conn_->write([&] {
    // Saturating at kMaxUseCount: past it SQLite's sum would turn into a
    // real number, which no reader accepts. Both stop there, so succeeded
    // stays at most retrieved.
    Statement update = conn_->prepare(
        "UPDATE experiences SET retrieved_count = min(retrieved_count + ?2, ?4), "
        "succeeded_count = min(succeeded_count + ?3, ?4) WHERE id = ?1");
    for (const auto& [id, counts] : uses) {
      update.bind(1, id).bind(2, counts.first).bind(3, counts.second).bind(4, kMaxUseCount);
      update.run();
      update.reset();
    }
  });
}

void SqliteBackend::afterWrite() {
  const auto now = std::chrono::steady_clock::now();
  if (++writes_since_checkpoint_ >= kCheckpointEveryWrites || now - last_checkpoint_ >= kCheckpointInterval) {
    conn_->checkpointPassive();
    writes_since_checkpoint_ = 0;
    last_checkpoint_ = now;
  }
}

bool SqliteBackend::readyToClose() {
  finishCheck();
  if (!check_error_) return true;
  // A damaged file: nothing is written to it. Its error is thrown here
  // unless a caller has had it already.
  if (check_error_reported_) return false;
  check_error_reported_ = true;
  std::rethrow_exception(check_error_);
}

void SqliteBackend::closeWritable() { conn_->checkpointPassive(); }

HistoryTail SqliteBackend::readHistory(int limit) { return exp::readHistory(*conn_, core_.version, limit); }

}  // namespace earc::exp
