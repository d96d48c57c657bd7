// ExperienceStore: the public methods, written once for both engines over
// StoreCore (the index, the row cache, the duplicate check) and a
// StoreBackend (sqlite_backend.cpp, pg_backend.cpp).
#include "earc/experience/store.hpp"

#include <cstdio>
#include <set>
#include <stdexcept>

#include "earc/experience/keys.hpp"
#include "earc/experience/pg_connection.hpp"
#include "earc/scene/robot_model.hpp"
#include "store_backend.hpp"

namespace earc::exp {

ExperienceStore::ExperienceStore(const std::string& path, const StoreOptions& options)
    : core_(std::make_unique<StoreCore>(path, options)) {
  std::lock_guard lock(mutex_);
  backend_ = isPostgresLocation(path) ? openPgBackend(*core_) : openSqliteBackend(*core_);
}

ExperienceStore::~ExperienceStore() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "earc: experience store %s: closing: %s\n", core_->path.c_str(), e.what());
  }
}

const std::string& ExperienceStore::path() const { return core_->path; }
int ExperienceStore::schemaVersion() const { return core_->version; }
bool ExperienceStore::readOnly() const { return core_->options.read_only; }
const HistoryWriter& ExperienceStore::history() const { return core_->history; }

void ExperienceStore::awaitCheck() {
  std::lock_guard lock(mutex_);
  requireOpen();
  backend_->awaitCheck();
}

ExperienceStore::CheckRun ExperienceStore::checkRun() const {
  std::lock_guard lock(mutex_);
  return backend_ ? backend_->checkRun() : CheckRun::InOpen;
}

std::int64_t ExperienceStore::session() {
  std::lock_guard lock(mutex_);
  if (backend_) backend_->awaitCheck();
  return core_->session;
}

void ExperienceStore::refresh() {
  std::lock_guard lock(mutex_);
  requireOpen();
  backend_->refresh(true);
}

std::vector<Match> ExperienceStore::nearest(const ExperienceClass& cls, std::span<const double> key, std::size_t k,
                                            std::size_t skip) {
  std::lock_guard lock(mutex_);
  requireOpen();
  return backend_->retrieve([&] {
    backend_->refresh(false);
    const ClassIndex* index = core_->index.find(cls);
    if (!index || index->dim() != key.size()) return std::vector<Match>{};
    return core_->matches(index->nearest(key, k), skip,
                          [&](const std::vector<std::int64_t>& ids) { return backend_->readRows(ids); });
  });
}

std::vector<Neighbor> ExperienceStore::nearestIds(const ExperienceClass& cls, std::span<const double> key,
                                                  std::size_t k) {
  std::lock_guard lock(mutex_);
  requireOpen();
  backend_->refresh(false);
  const ClassIndex* index = core_->index.find(cls);
  if (!index || index->dim() != key.size()) return {};
  return index->nearest(key, k);
}

std::optional<Experience> ExperienceStore::get(std::int64_t id) {
  std::lock_guard lock(mutex_);
  requireOpen();
  return backend_->fetch(id);
}

ExperienceStore::RetrievalStats ExperienceStore::retrievalStats() const {
  std::lock_guard lock(mutex_);
  return {core_->retrievals, core_->rows_returned, core_->row_cache.hits(), core_->row_cache.misses(),
          core_->warm_hits};
}

std::size_t ExperienceStore::awaitWarmRows() {
  std::lock_guard lock(mutex_);
  requireOpen();
  return backend_->awaitWarmRows();
}

std::pair<std::size_t, std::size_t> ExperienceStore::rowCacheSize() const {
  std::lock_guard lock(mutex_);
  return {core_->row_cache.size(), core_->row_cache.bytes()};
}

void ExperienceStore::describeHistory(std::string operation, std::string detail) {
  std::lock_guard lock(mutex_);
  core_->history.describe(std::move(operation), std::move(detail));
  core_->history_described = true;
}

std::optional<std::int64_t> ExperienceStore::insert(const Experience& e, double near_duplicate_eps) {
  return insertAll({e}, near_duplicate_eps).front();
}

std::vector<std::optional<std::int64_t>> ExperienceStore::insertAll(const std::vector<Experience>& batch,
                                                                    double near_duplicate_eps, SessionStamp stamp) {
  std::lock_guard lock(mutex_);
  requireWritable();
  backend_->awaitCheck();  // before the rows take this session's number
  const std::vector<Experience> rows = core_->prepareRows(batch, stamp);
  StoredIds ids = backend_->insert(rows, near_duplicate_eps, stamp);
  // Committed: now the rows may enter the in-memory index.
  core_->indexInserted(rows, ids);
  backend_->afterWrite();
  return ids;
}

void ExperienceStore::recordUse(std::int64_t id, bool success) {
  std::lock_guard lock(mutex_);
  requireWritable();
  auto& [retrieved, succeeded] = core_->pending_uses[id];
  ++retrieved;
  if (success) ++succeeded;
  // Not while a background check runs: the write would wait for it, mid-plan.
  if (core_->pending_uses.size() >= kMaxPendingUses && !backend_->checkRunning()) flushLocked();
}

void ExperienceStore::flush() {
  std::lock_guard lock(mutex_);
  requireOpen();
  flushLocked();
}

void ExperienceStore::flushLocked() {
  if (core_->pending_uses.empty()) return;
  backend_->awaitCheck();
  backend_->writeUses(core_->pending_uses);
  core_->pending_uses.clear();
  backend_->afterWrite();
}

void ExperienceStore::close() {
  std::lock_guard lock(mutex_);
  if (!backend_) return;
  // The engine goes however this ends: closed, or an error thrown.
  struct DropOnExit {
    std::unique_ptr<StoreBackend>& backend;
    ~DropOnExit() { backend.reset(); }
  } drop{backend_};
  if (!backend_->readyToClose()) {
    core_->pending_uses.clear();  // nothing is written to a damaged file
    return;
  }
  if (!core_->options.read_only) {
    flushLocked();
    backend_->closeWritable();
  }
}

std::size_t ExperienceStore::size() const {
  std::lock_guard lock(mutex_);
  return core_->index.size();
}

std::vector<ExperienceStore::ClassInfo> ExperienceStore::classes() const {
  std::lock_guard lock(mutex_);
  std::vector<ClassInfo> out;
  for (const auto& [cls, index] : core_->index.classes()) out.push_back({cls, index->size(), index->dim()});
  return out;
}

const ClassIndex* ExperienceStore::classIndex(const ExperienceClass& cls) const {
  std::lock_guard lock(mutex_);
  return core_->index.find(cls);
}

Connection& ExperienceStore::connection() {
  requireOpen();
  Connection* c = backend_->sqliteConnection();
  if (!c)
    throw std::logic_error("ExperienceStore::connection: " + maskedLocation(core_->path) + " is a PostgreSQL store");
  return *c;
}

bool ExperienceStore::isPostgres() const { return backend_ && backend_->pgConnection(); }

PgConnection& ExperienceStore::pgConnection() {
  requireOpen();
  PgConnection* c = backend_->pgConnection();
  if (!c) throw std::logic_error("ExperienceStore::pgConnection: " + core_->path + " is an SQLite file");
  return *c;
}

HistoryTail ExperienceStore::readHistoryLines(int limit) {
  std::lock_guard lock(mutex_);
  requireOpen();
  return backend_->readHistory(limit);
}

void ExperienceStore::requireOpen() const {
  if (!backend_) throw std::logic_error("ExperienceStore: used after close()");
}

void ExperienceStore::requireWritable() const {
  requireOpen();
  if (core_->options.read_only) throw std::logic_error("ExperienceStore: write on a store opened read-only");
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
