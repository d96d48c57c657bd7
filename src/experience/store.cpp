#include "earc/experience/store.hpp"

#include <pthread.h>
#include <sched.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <thread>

#include "earc/experience/keys.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/pg_connection.hpp"
#include "earc/experience/pg_schema.hpp"
#include "earc/experience/rows.hpp"
#include "earc/experience/schema.hpp"
#include "earc/scene/robot_model.hpp"

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

std::int64_t nowUnixSeconds() {
  return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Whether a key length can belong to the class without reading the paths
// (the per-robot dimension lives in the path blob): exact for mobile
// robots, one of the possible lengths for arms. verify checks it exactly.
bool plausibleKeyDimension(const ExperienceClass& cls, std::size_t n) {
  if (cls.robot_count < 1) return false;
  if (cls.kind == RobotKind::Mobile) return n == static_cast<std::size_t>(keyDimension(cls.kind, cls.robot_count, 3));
  const std::size_t per_joint = static_cast<std::size_t>(2 * cls.robot_count);
  return n > 0 && n % per_joint == 0 && n / per_joint <= static_cast<std::size_t>(kArmKeyJoints);
}

// Resets a cached statement however the scope is left.
struct ResetOnExit {
  Statement& s;
  ~ResetOnExit() { s.reset(); }
};

}  // namespace

ExperienceStore::ExperienceStore(const std::string& path, const StoreOptions& options)
    : path_(path),
      options_(options),
      row_cache_(options.row_cache_bytes),
      last_checkpoint_(std::chrono::steady_clock::now()) {
  std::lock_guard lock(mutex_);
  if (isPostgresLocation(path)) {
    pgOpenLocked();
    return;
  }
  // Whether this open creates the file (SQLite creates it, empty, when it
  // opens it, before the first write can fail).
  std::error_code ec;
  const std::string real = databaseFile(path);
  const bool creating =
      !options.read_only && !options.in_memory && !std::filesystem::exists(std::filesystem::symlink_status(real, ec));
  try {
    openLocked();
  } catch (...) {
    dropCheckLocked();  // no destructor will
    if (creating) discardCreatedLocked(real);
    throw;
  }
}

void ExperienceStore::discardCreatedLocked(const std::string& real) {
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

ExperienceStore::~ExperienceStore() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "earc: experience store %s: closing: %s\n", path_.c_str(), e.what());
  }
}

void ExperienceStore::openLocked() {
  const OpenMode mode = options_.in_memory   ? OpenMode::Memory
                        : options_.read_only ? OpenMode::ReadOnly
                                             : OpenMode::ReadWrite;
  if (options_.read_only) requireDatabaseFile(path_);  // else SQLite's "unable to open database file"
  ConnectionSettings settings = options_.connection;
  settings.own_application_id = kApplicationId;
  conn_ = std::make_unique<Connection>(path_, mode, settings);
  // Identity first: never switch a foreign file to WAL or write to it.
  // Another process creating the same file may make these steps busy.
  version_ = conn_->retryWhileBusy([&] { return checkIdentity(*conn_); });
  // Then the file's structure, before anything is written to it or read
  // from it: a truncated or damaged file is refused here, naming the first
  // problem, instead of failing some later query mid-plan. A planner may
  // have it checked in the background instead, when opening needs no write
  // (our WAL file at the current version): then every write waits for it.
  // An offline writer checks index contents too (full_check).
  // Not on a machine without a spare core: there the idle-class thread
  // gets no time, and while it waits for some it can hold SQLite's
  // process-wide locks that this connection needs (on 2 cores beside 4
  // busy loops, opening stalled up to 2 s); the check runs here instead.
  const bool background = options_.check_in_background && !options_.full_check &&
                          (!options_.check_in_open_when_busy || spareCore()) &&
                          version_ == currentSchemaVersion() &&
                          conn_->retryWhileBusy([&] { return conn_->pragmaText("journal_mode"); }) == "wal";
  if (background) {
    startCheckLocked();
    check_run_ = CheckRun::Background;
  } else if (options_.full_check) {
    conn_->retryWhileBusy([&] { conn_->requireIntegrityCheck(); });
  } else {
    conn_->retryWhileBusy([&] { conn_->requireQuickCheck(); });
  }
  if (options_.read_only) {
    if (version_ == 0) throw notYetADatabase(path_);
  } else if (!background) {
    if (!options_.in_memory) conn_->retryWhileBusy([&] { conn_->enableWal(); });
    version_ = migrate(*conn_);
  }
  session_ = metaLocked("sessions");
  if (!options_.read_only && options_.new_session) {
    session_pending_ = true;
    if (!background) awaitCheckLocked();
  }
  fetch_ = std::make_unique<Statement>(conn_->prepare(selectExperiencesSql(version_) + " WHERE id = ?1"));
  data_version_ = std::make_unique<Statement>(conn_->prepare("PRAGMA data_version"));
  refreshLocked();
}

std::int64_t ExperienceStore::metaLocked(const char* name) {
  if (version_ < 2) return 0;  // store_meta arrived with migration 2
  Statement s = conn_->prepare("SELECT value FROM store_meta WHERE name = ?1");
  s.bind(1, std::string_view(name));
  std::int64_t v = s.step() ? s.int64At(0) : 0;
  s.reset();
  return v;
}

void ExperienceStore::awaitCheckLocked() {
  joinCheckLocked();
  if (session_pending_) {
    session_ = conn_->write([&] {
      conn_->exec("UPDATE store_meta SET value = value + 1 WHERE name = 'sessions'");
      return metaLocked("sessions");
    });
    session_pending_ = false;
  }
}

void ExperienceStore::awaitCheck() {
  std::lock_guard lock(mutex_);
  requireOpen();
  awaitCheckLocked();
}

std::int64_t ExperienceStore::session() {
  std::lock_guard lock(mutex_);
  if (conn_) awaitCheckLocked();
  return session_;
}

void ExperienceStore::refresh() {
  std::lock_guard lock(mutex_);
  requireOpen();
  if (pg_) return pgRefreshLocked(true);
  refreshLocked();
}

void ExperienceStore::refreshLocked() {
  if (pg_) return pgRefreshLocked(false);
  std::int64_t dv = 0;
  {
    ResetOnExit guard{*data_version_};
    dv = data_version_->step() ? data_version_->int64At(0) : 0;
  }
  if (dv == loaded_data_version_) return;  // no other connection committed
  loaded_data_version_ = dv;
  const std::int64_t deletions = metaLocked("deletions");
  if (deletions != loaded_deletions_) {
    // Rows were deleted somewhere: the index may point at them; reload all.
    forgetRowsLocked();
    loaded_deletions_ = deletions;
  }
  loadTailLocked();
}

void ExperienceStore::forgetRowsLocked() {
  index_.clear();
  row_cache_.clear();
  max_loaded_ = 0;
}

void ExperienceStore::loadTailLocked() {
  // Version 3 has a covering index: the scan never touches the path blobs.
  Statement s = conn_->prepare(std::string("SELECT id, kind, robot_count, signature, base_class, key FROM experiences") +
                               (version_ >= 3 ? " INDEXED BY experiences_keys" : "") + " WHERE id > ?1 ORDER BY id");
  s.bind(1, max_loaded_);
  while (s.step()) indexKeyRowLocked(s.int64At(0), s.textAt(1), s.int64At(2), s.textAt(3), s.textAt(4), s.blobAt(5));
  index_.settle();
}

void ExperienceStore::indexKeyRowLocked(std::int64_t id, const std::string& kind_name, std::int64_t robot_count,
                                        std::string signature, std::string base_class,
                                        std::span<const unsigned char> key_blob) {
  max_loaded_ = std::max(max_loaded_, id);
  try {
    auto kind = kindFromName(kind_name);
    if (!kind) throw CorruptRowError(id, "unknown kind \"" + kind_name + "\"");
    ExperienceClass cls{*kind, static_cast<int>(robot_count), std::move(signature), std::move(base_class)};
    std::vector<double> key = decodeKey(key_blob, id);
    if (!plausibleKeyDimension(cls, key.size()))
      throw CorruptRowError(id, "key dimension " + std::to_string(key.size()) + " does not fit the class");
    const ClassIndex* existing = index_.find(cls);
    if (existing && existing->dim() != key.size())
      throw CorruptRowError(id, "key dimension differs from the class's other rows");
    index_.add(cls, id, key);
  } catch (const CorruptRowError& e) {
    warnSkipped(id, e.reason());
  }
}

void ExperienceStore::warnSkipped(std::int64_t id, const std::string& why) {
  if (!options_.warn_skipped) return;
  static std::mutex warn_mutex;
  static std::set<std::pair<std::string, std::int64_t>> warned;
  std::lock_guard lock(warn_mutex);
  if (!warned.insert({path_, id}).second) return;
  std::fprintf(stderr, "earc: experience store %s: skipping row %lld: %s (run earc-db verify)\n", path_.c_str(),
               static_cast<long long>(id), why.c_str());
}

std::optional<Experience> ExperienceStore::fetchLocked(std::int64_t id) {
  if (pg_) return pgFetchLocked(id);
  ResetOnExit guard{*fetch_};
  fetch_->bind(1, id);
  if (!fetch_->step()) return std::nullopt;
  return readExperience(*fetch_);
}

std::vector<Match> ExperienceStore::nearest(const ExperienceClass& cls, std::span<const double> key, std::size_t k,
                                            std::size_t skip) {
  std::lock_guard lock(mutex_);
  requireOpen();
  if (pg_) return pgNearestLocked(cls, key, k, skip);
  return conn_->read([&] {
    refreshLocked();
    std::vector<Match> out;
    const ClassIndex* index = index_.find(cls);
    if (!index || index->dim() != key.size()) return out;
    return matchesLocked(index->nearest(key, k), skip, [&](const std::vector<std::int64_t>& ids) {
      std::vector<std::shared_ptr<const Experience>> rows;
      for (const std::int64_t id : ids) {
        try {
          if (auto e = fetchLocked(id)) rows.push_back(std::make_shared<const Experience>(std::move(*e)));
        } catch (const CorruptRowError& e) {
          warnSkipped(id, e.reason());
        } catch (const DamagedDatabaseError& e) {
          // A check still running in the background has the verdict on the
          // whole file: a damaged file ends planning with its error.
          // (Only the verdict: this is a read transaction, no place to write.)
          joinCheckLocked();
          // The file was damaged after it was opened (quick_check passed
          // then): this row cannot be read; planning goes on without it.
          warnSkipped(id, e.what());
        }
      }
      return rows;
    });
  });
}

std::vector<Neighbor> ExperienceStore::nearestIds(const ExperienceClass& cls, std::span<const double> key,
                                                  std::size_t k) {
  std::lock_guard lock(mutex_);
  requireOpen();
  refreshLocked();
  const ClassIndex* index = index_.find(cls);
  if (!index || index->dim() != key.size()) return {};
  return index->nearest(key, k);
}

void ExperienceStore::describeHistory(std::string operation, std::string detail) {
  std::lock_guard lock(mutex_);
  history_.describe(std::move(operation), std::move(detail));
  history_described_ = true;
}

std::optional<Experience> ExperienceStore::get(std::int64_t id) {
  std::lock_guard lock(mutex_);
  requireOpen();
  return fetchLocked(id);
}

std::optional<std::int64_t> ExperienceStore::insert(const Experience& e, double near_duplicate_eps) {
  std::lock_guard lock(mutex_);
  return insertLocked({e}, near_duplicate_eps).front();
}

std::vector<std::optional<std::int64_t>> ExperienceStore::insertAll(const std::vector<Experience>& batch,
                                                                    double near_duplicate_eps, SessionStamp stamp) {
  std::lock_guard lock(mutex_);
  return insertLocked(batch, near_duplicate_eps, stamp);
}

std::vector<std::optional<std::int64_t>> ExperienceStore::insertLocked(const std::vector<Experience>& batch,
                                                                       double eps, SessionStamp stamp) {
  requireWritable();
  if (pg_) return pgInsertLocked(batch, eps, stamp);
  awaitCheckLocked();
  const std::vector<Experience> rows = prepareRowsLocked(batch, stamp);
  auto ids = conn_->write([&] {
    // Inside the write lock: every committed row is loaded, and nobody can
    // insert until we commit, so the duplicate check sees everything.
    refreshLocked();
    KeyIndex batch_index;  // rows of this transaction, for the in-batch check
    Statement insert = conn_->prepare(insertExperienceSql());
    std::vector<std::optional<std::int64_t>> result;
    result.reserve(rows.size());
    std::int64_t stored = 0;
    for (const Experience& e : rows) {
      if (nearDuplicate(batch_index, e, eps)) {
        result.push_back(std::nullopt);
        continue;
      }
      bindExperience(insert, e);
      insert.run();
      insert.reset();
      const std::int64_t id = sqlite3_last_insert_rowid(conn_->handle());
      if (eps >= 0) {
        batch_index.add(e.cls, id, e.key);
        if (result.size() % ClassIndex::kBulkSettleEvery == 0) batch_index.settle();
      }
      result.push_back(id);
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
    if (!history_described_) history_.describe("learn", "planning session " + std::to_string(session_));
    history_.record(*conn_, version_, stored, 0);
    return result;
  });
  indexInsertedLocked(rows, ids);
  afterWriteLocked();
  return ids;
}

std::vector<Experience> ExperienceStore::prepareRowsLocked(const std::vector<Experience>& batch,
                                                           SessionStamp stamp) const {
  std::vector<Experience> rows = batch;
  const std::int64_t now = nowUnixSeconds();
  for (Experience& e : rows) {
    if (auto problem = findProblem(e)) throw std::invalid_argument("ExperienceStore::insert: " + *problem);
    if (e.created_at == 0) e.created_at = now;
    if (stamp == SessionStamp::ThisSession) e.created_session = session_;
  }
  return rows;
}

bool ExperienceStore::nearDuplicate(const KeyIndex& batch_index, const Experience& e, double eps) const {
  if (eps < 0) return false;
  for (const ClassIndex* index : {index_.find(e.cls), batch_index.find(e.cls)}) {
    if (!index) continue;
    if (index->dim() != e.key.size())
      throw std::invalid_argument("ExperienceStore::insert: key dimension " + std::to_string(e.key.size()) +
                                  " differs from the class's " + std::to_string(index->dim()));
    auto n = index->nearest(e.key, 1);
    if (!n.empty() && n.front().distance <= eps) return true;
  }
  return false;
}

void ExperienceStore::indexInsertedLocked(const std::vector<Experience>& rows,
                                          const std::vector<std::optional<std::int64_t>>& ids) {
  // Committed: now the rows may enter the in-memory index.
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (ids[i]) {
      index_.add(rows[i].cls, *ids[i], rows[i].key);
      max_loaded_ = std::max(max_loaded_, *ids[i]);
    }
  index_.settle();
}

void ExperienceStore::recordUse(std::int64_t id, bool success) {
  std::lock_guard lock(mutex_);
  requireWritable();
  auto& [retrieved, succeeded] = pending_uses_[id];
  ++retrieved;
  if (success) ++succeeded;
  // Not while a background check runs: the write would wait for it, mid-plan.
  if (pending_uses_.size() >= kMaxPendingUses && !checkRunning()) flushLocked();
}

void ExperienceStore::flush() {
  std::lock_guard lock(mutex_);
  requireOpen();
  flushLocked();
}

void ExperienceStore::flushLocked() {
  if (pending_uses_.empty()) return;
  if (pg_) return pgFlushLocked();
  awaitCheckLocked();
  conn_->write([&] {
    // Saturating at kMaxUseCount: past it SQLite's sum would turn into a
    // real number, which no reader accepts. Both stop there, so succeeded
    // stays at most retrieved.
    Statement update = conn_->prepare(
        "UPDATE experiences SET retrieved_count = min(retrieved_count + ?2, ?4), "
        "succeeded_count = min(succeeded_count + ?3, ?4) WHERE id = ?1");
    for (const auto& [id, counts] : pending_uses_) {
      update.bind(1, id).bind(2, counts.first).bind(3, counts.second).bind(4, kMaxUseCount);
      update.run();
      update.reset();
    }
  });
  pending_uses_.clear();
  afterWriteLocked();
}

void ExperienceStore::afterWriteLocked() {
  const auto now = std::chrono::steady_clock::now();
  if (++writes_since_checkpoint_ >= kCheckpointEveryWrites || now - last_checkpoint_ >= kCheckpointInterval) {
    conn_->checkpointPassive();
    writes_since_checkpoint_ = 0;
    last_checkpoint_ = now;
  }
}

void ExperienceStore::close() {
  std::lock_guard lock(mutex_);
  if (pg_) {
    // The connection goes however this ends: closed, or an error thrown.
    struct DropPg {
      std::unique_ptr<PgConnection>& pg;
      ~DropPg() { pg.reset(); }
    } drop{pg_};
    if (!options_.read_only) flushLocked();
    return;
  }
  if (!conn_) return;
  // The connection goes however this ends: closed, or an error thrown.
  struct DropOnExit {
    ExperienceStore& s;
    ~DropOnExit() {
      s.fetch_.reset();
      s.data_version_.reset();
      s.conn_.reset();
    }
  } drop{*this};
  finishCheckLocked();
  if (check_error_) {
    // A damaged file: nothing is written to it. Its error is thrown here
    // unless a caller has had it already.
    pending_uses_.clear();
    if (check_error_reported_) return;
    check_error_reported_ = true;
    std::rethrow_exception(check_error_);
  }
  if (!options_.read_only) {
    flushLocked();
    conn_->checkpointPassive();
  }
}

std::size_t ExperienceStore::size() const {
  std::lock_guard lock(mutex_);
  return index_.size();
}

std::vector<ExperienceStore::ClassInfo> ExperienceStore::classes() const {
  std::lock_guard lock(mutex_);
  std::vector<ClassInfo> out;
  for (const auto& [cls, index] : index_.classes()) out.push_back({cls, index->size(), index->dim()});
  return out;
}

const ClassIndex* ExperienceStore::classIndex(const ExperienceClass& cls) const {
  std::lock_guard lock(mutex_);
  return index_.find(cls);
}

Connection& ExperienceStore::connection() {
  requireOpen();
  if (pg_) throw std::logic_error("ExperienceStore::connection: " + maskedLocation(path_) + " is a PostgreSQL store");
  return *conn_;
}

HistoryTail ExperienceStore::readHistoryLines(int limit) {
  std::lock_guard lock(mutex_);
  requireOpen();
  if (pg_) return pgReadHistory(*pg_, limit);
  return readHistory(*conn_, version_, limit);
}

void ExperienceStore::requireOpen() const {
  if (!conn_ && !pg_) throw std::logic_error("ExperienceStore: used after close()");
}

void ExperienceStore::requireWritable() const {
  requireOpen();
  if (options_.read_only) throw std::logic_error("ExperienceStore: write on a store opened read-only");
}

std::string noClassFitsWarning(const ExperienceStore& store, const Scenario& scenario, const std::string& db) {
  if (store.size() == 0) return "";  // a new file: expected to start empty
  std::set<std::string> ours;
  for (const auto& m : makeRobotModels(scenario)) ours.insert(m->geometrySignature());
  for (const auto& c : store.classes()) {
    bool fits = true;
    for (const std::string_view one : signatureParts(c.cls.signature)) fits = fits && ours.count(std::string(one)) > 0;
    if (fits) return "";
  }
  std::string names;
  for (const std::string& s : ours) names += (names.empty() ? "" : ", ") + s;
  return db + " holds " + std::to_string(store.size()) + " experiences, none for these robots (" + names +
         "): E-ARC plans as ARC does (earc-db build --scenario makes a database for them)";
}

}  // namespace earc::exp
