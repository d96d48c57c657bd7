// ExperienceStore's PostgreSQL engine: the same index, duplicate check and
// row checks as the SQLite file's (StoreCore), over a libpq connection.
//
// Rows other planners commit are found by polling the highest id loaded
// (at most every kPgPollInterval before a retrieval, always inside an
// insert's transaction). That is exact because every insert holds one
// advisory lock from before it takes ids until it commits: ids are
// committed in increasing order, so no row can appear later below an id
// already seen. LISTEN/NOTIFY would save the polls but needs a connection
// kept listening and still a scan after a lost connection; the poll is
// one indexed range query that returns nothing when nothing changed.
//
// Rows a retrieval lacks: from the row cache; for a store read whole at
// open, there; otherwise from the packed copy a background read fills
// (PgWarmRows), and the rest from the server, in one round trip.
#include <algorithm>
#include <cstdio>

#include "earc/experience/pg_connection.hpp"
#include "earc/experience/pg_schema.hpp"
#include "pg_warm_pack.hpp"
#include "pg_warm_rows.hpp"
#include "store_backend.hpp"

namespace earc::exp {

namespace {

// How long retrievals skip a server that could not be reached through
// every reconnection attempt, before trying again.
constexpr std::chrono::seconds kPgRetryUnreachableAfter{5};

// Rows per INSERT statement (14 parameters each; a statement takes 65,535).
constexpr std::size_t kPgInsertRows = 256;

constexpr const char* kTailSql =
    "SELECT d.value, e.id, e.kind, e.robot_count, e.signature, e.base_class, e.key "
    "FROM (SELECT value FROM earc.store_meta WHERE name = 'deletions') d "
    "LEFT JOIN earc.experiences e ON e.id > $1 ORDER BY e.id";

// Whether a store is small enough to hold in the row cache: its table's
// size on the server (with indexes and dead rows: more than the rows hold)
// within half the bound.
bool pgStoreFitsRowCache(PgConnection& pg, std::size_t bound) {
  if (bound == 0) return false;
  const std::int64_t bytes =
      pg.retryLost([&] { return pg.query("SELECT pg_total_relation_size('earc.experiences')"); }).int64At(0, 0);
  return bytes >= 0 && static_cast<std::size_t>(bytes) <= bound / 2;
}

class PgBackend final : public StoreBackend {
 public:
  // Connects, checks identity, migrates, counts the session, loads.
  explicit PgBackend(StoreCore& core);

  void refresh(bool force) override;
  std::vector<Match> retrieve(const std::function<std::vector<Match>()>& search) override;
  SharedRows readRows(const std::vector<std::int64_t>& ids) override;
  std::optional<Experience> fetch(std::int64_t id) override;
  StoredIds insert(const std::vector<Experience>& rows, double eps, SessionStamp stamp) override;
  void writeUses(const std::map<std::int64_t, std::pair<std::int64_t, std::int64_t>>& uses) override;
  HistoryTail readHistory(int limit) override { return pgReadHistory(pg_, limit); }
  std::size_t awaitWarmRows() override;
  PgConnection* pgConnection() override { return &pg_; }

 private:
  // Row `row` of a tail read whole (pgSelectTailWithDeletionsSql) into the
  // row cache; preloading stops when the cache is full.
  void preloadRow(const PgResult& r, int row);
  // A row this open stored, into the row cache while preloading.
  void cacheStored(std::shared_ptr<const Experience> e);
  // Ends the background copy (stopped, or too large).
  void dropWarmRows();

  PgConnection pg_;
  std::chrono::steady_clock::time_point polled_{};
  std::chrono::steady_clock::time_point down_until_{};  // retrievals skip the server till then
  std::int64_t rows_added_ = 0;  // on this open's history line
  bool preload_ = false;         // every row read into the row cache
  std::unique_ptr<PgWarmRows> warm_;  // the background copy, if any
};

}  // namespace

std::unique_ptr<StoreBackend> openPgBackend(StoreCore& core) { return std::make_unique<PgBackend>(core); }

PgBackend::PgBackend(StoreCore& core) : StoreBackend(core), pg_(core.path) {
  core_.version = pgCheckIdentity(pg_);
  if (core_.options.read_only) {
    if (core_.version == 0)
      throw InputError(pg_.location(), "", "empty database (no earc schema), not an earc database yet");
  } else {
    core_.version = pgMigrate(pg_);
  }
  if (!core_.options.read_only && core_.options.new_session) {
    pg_.write([&] {
      core_.session =
          pg_.query("UPDATE earc.store_meta SET value = value + 1 WHERE name = 'sessions' RETURNING value")
              .int64At(0, 0);
    });
  } else {
    core_.session = pg_.query("SELECT value FROM earc.store_meta WHERE name = 'sessions'").int64At(0, 0);
  }
  // A small store comes whole with its keys, and retrievals never wait for
  // the server; a large one fetches the k rows a retrieval misses.
  preload_ = core_.version > 0 && pgStoreFitsRowCache(pg_, core_.options.row_cache_bytes);
  refresh(true);
  // A larger one is read packed in the background while planning starts.
  const std::size_t bound = core_.options.row_cache_bytes;
  if (!preload_ && core_.version > 0 && core_.options.warm_rows && bound > 0) {
    // The copy has a bound of its own, the row cache's: it stands where
    // the file's engine has the operating system's cache of the file, and
    // the decoded rows keep their whole bound (a quarter of it made
    // retrievals slower: docs/performance-log.md). Estimated
    // first from a sample of its pages: a store that cannot fit costs the
    // server no whole-table read.
    // The copy is optional: a failed estimate only leaves it out.
    try {
      if (estimatePgWarmBytes(pg_, core_.index.size()) <= bound) warm_ = std::make_unique<PgWarmRows>(core_.path, bound);
    } catch (const StoreError&) {
    }
  }
}

void PgBackend::refresh(bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && (now - polled_ < kPgPollInterval || now < down_until_)) return;
  for (;;) {
    const bool whole = preload_;
    PgResult r = pg_.retryLost(
        [&] { return pg_.query(whole ? pgSelectTailWithDeletionsSql() : kTailSql, PgParams().add(core_.max_loaded)); });
    polled_ = now;
    const int id_col = whole ? 0 : 1;  // then kind, robot_count, signature, base_class, key
    const std::int64_t deletions = r.int64At(0, whole ? kPgRowColumns : 0);
    if (deletions != core_.loaded_deletions && (core_.max_loaded > 0 || core_.index.size() > 0)) {
      // Rows were deleted somewhere: the index may point at them; reload all.
      core_.forgetRows();
      if (warm_) dropWarmRows();  // its rows may be gone too
      core_.loaded_deletions = deletions;
      continue;
    }
    core_.loaded_deletions = deletions;
    for (int i = 0; i < r.rows(); ++i) {
      if (r.isNull(i, id_col)) continue;
      const int c = id_col;
      core_.indexKeyRow(r.int64At(i, c), r.textAt(i, c + 1), r.int64At(i, c + 2), r.textAt(i, c + 3),
                        r.textAt(i, c + 4), r.bytesAt(i, c + 5));
      if (whole && preload_) preloadRow(r, i);
    }
    core_.index.settle();
    return;
  }
}

void PgBackend::preloadRow(const PgResult& r, int row) {
  try {
    cacheStored(std::make_shared<const Experience>(readPgExperience(r, row)));
  } catch (const CorruptRowError&) {
    // the index skipped it too, or a retrieval reports it
  }
}

void PgBackend::cacheStored(std::shared_ptr<const Experience> e) {
  // The store outgrew the cache: retrievals fetch what they miss from now on.
  if (core_.row_cache.bytes() + cachedRowBytes(*e) > core_.row_cache.maxBytes()) {
    preload_ = false;
    return;
  }
  core_.row_cache.put(std::move(e));
}

std::vector<Match> PgBackend::retrieve(const std::function<std::vector<Match>()>& search) {
  try {
    return search();
  } catch (const PgConnectionLostError& e) {
    // The server went away through every reconnection: planning goes on
    // without experience and tries the server again a while later.
    down_until_ = std::chrono::steady_clock::now() + kPgRetryUnreachableAfter;
    std::fprintf(stderr, "earc: experience store: retrieval skipped: %s\n", e.what());
    return {};
  }
}

void PgBackend::dropWarmRows() {
  warm_->clear();
  warm_.reset();
}

std::size_t PgBackend::awaitWarmRows() {
  if (!warm_) return 0;
  const std::size_t held = warm_->awaitRead();
  if (warm_->overflowed()) dropWarmRows();
  return held;
}

SharedRows PgBackend::readRows(const std::vector<std::int64_t>& ids) {
  if (warm_ && warm_->overflowed()) dropWarmRows();
  // The background copy's rows decoded here, the others in one round trip;
  // one deleted since the index was loaded is not there.
  SharedRows rows;
  std::vector<std::int64_t> ask;
  for (const std::int64_t id : ids) {
    if (!warm_ || !warm_->has(id)) {
      ask.push_back(id);
      continue;
    }
    ++core_.warm_hits;
    try {
      rows.push_back(std::make_shared<const Experience>(warm_->decode(id)));
    } catch (const CorruptRowError& e) {
      core_.warnSkipped(id, e.reason());
    }
  }
  if (ask.empty()) return rows;
  PgResult r = pg_.retryLost(
      [&] { return pg_.query(pgSelectExperiencesSql() + " WHERE id = ANY($1)", PgParams().addIds(ask)); });
  for (int i = 0; i < r.rows(); ++i) {
    try {
      rows.push_back(std::make_shared<const Experience>(readPgExperience(r, i)));
    } catch (const CorruptRowError& e) {
      core_.warnSkipped(r.int64At(i, 0), e.reason());
    }
  }
  return rows;
}

std::optional<Experience> PgBackend::fetch(std::int64_t id) {
  PgResult r =
      pg_.retryLost([&] { return pg_.query(pgSelectExperiencesSql() + " WHERE id = $1", PgParams().add(id)); });
  if (r.rows() == 0) return std::nullopt;
  return readPgExperience(r, 0);
}

StoredIds PgBackend::insert(const std::vector<Experience>& rows, double eps, SessionStamp stamp) {
  StoredIds ids;
  std::int64_t stored = 0;
  core_.describeLearning();
  // A connection lost during COMMIT: this open's history line counts every
  // row it committed, so it tells whether the COMMIT went through.
  auto committed = [&] { return pgHistoryRowsAdded(pg_, core_.history) == rows_added_ + stored; };
  pg_.write(
      [&] {
        ids.assign(rows.size(), std::nullopt);
        stored = 0;
        // Writers one at a time: every committed row is loaded, and nobody
        // can insert until we commit, so the duplicate check sees everything.
        pg_.exec("SELECT pg_advisory_xact_lock(" + std::to_string(kPgWriteLock) + ")");
        refresh(true);
        // Rows to store, sent kPgInsertRows to a statement. Their ids come
        // from the sequence in VALUES order under the lock: ascending.
        const std::vector<std::size_t> novel = core_.novelRows(rows, eps);
        for (std::size_t from = 0; from < novel.size(); from += kPgInsertRows) {
          const std::size_t n = std::min(kPgInsertRows, novel.size() - from);
          PgParams params;
          for (std::size_t j = 0; j < n; ++j) params.append(pgExperienceParams(rows[novel[from + j]]));
          PgResult r = pg_.query(pgInsertExperiencesSql(n), params);
          std::vector<std::int64_t> got;
          for (int j = 0; j < r.rows(); ++j) got.push_back(r.int64At(j, 0));
          std::sort(got.begin(), got.end());
          for (std::size_t j = 0; j < n; ++j) ids[novel[from + j]] = got.at(j);
          stored += static_cast<std::int64_t>(n);
        }
        // As the SQLite engine's: a restored export's sessions.
        if (stamp == SessionStamp::AsGiven)
          pg_.exec(
              "UPDATE earc.store_meta SET value = GREATEST(value, (SELECT coalesce(max(created_session), 0) "
              "FROM earc.experiences)) WHERE name = 'sessions'");
        pgRecordHistory(pg_, core_.history, stored, 0);
      },
      committed);
  rows_added_ += stored;
  for (std::size_t i = 0; i < rows.size() && preload_; ++i)
    if (ids[i]) {
      auto e = std::make_shared<Experience>(rows[i]);
      e->id = *ids[i];
      cacheStored(std::move(e));
    }
  return ids;
}

void PgBackend::writeUses(const std::map<std::int64_t, std::pair<std::int64_t, std::int64_t>>& uses) {
  pg_.write([&] {
    for (const auto& [id, counts] : uses)
      pg_.query(
          "UPDATE earc.experiences SET retrieved_count = LEAST(retrieved_count + $2, $4), "
          "succeeded_count = LEAST(succeeded_count + $3, $4) WHERE id = $1",
          PgParams().add(id).add(counts.first).add(counts.second).add(kMaxUseCount));
  });
}

}  // namespace earc::exp
