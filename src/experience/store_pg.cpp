// ExperienceStore's PostgreSQL engine: the same index, duplicate check and
// row checks as the SQLite file's (store.cpp), over a libpq connection.
//
// Rows other planners commit are found by polling the highest id loaded
// (at most every kPgPollInterval before a retrieval, always inside an
// insert's transaction). That is exact because every insert holds one
// advisory lock from before it takes ids until it commits: ids are
// committed in increasing order, so no row can appear later below an id
// already seen. LISTEN/NOTIFY would save the polls but needs a connection
// kept listening and still a scan after a lost connection; the poll is
// one indexed range query that returns nothing when nothing changed.
#include <algorithm>
#include <cstdio>

#include "earc/experience/pg_connection.hpp"
#include "earc/experience/pg_schema.hpp"
#include "earc/experience/store.hpp"

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

}  // namespace

// Whether a store is small enough to hold in the row cache: its table's
// size on the server (with indexes and dead rows: more than the rows hold)
// within half the bound.
static bool pgStoreFitsRowCache(PgConnection& pg, std::size_t bound) {
  if (bound == 0) return false;
  const std::int64_t bytes =
      pg.retryLost([&] { return pg.query("SELECT pg_total_relation_size('earc.experiences')"); }).int64At(0, 0);
  return bytes >= 0 && static_cast<std::size_t>(bytes) <= bound / 2;
}

void ExperienceStore::pgOpenLocked() {
  pg_ = std::make_unique<PgConnection>(path_);
  version_ = pgCheckIdentity(*pg_);
  if (options_.read_only) {
    if (version_ == 0)
      throw InputError(pg_->location(), "", "empty database (no earc schema), not an earc database yet");
  } else {
    version_ = pgMigrate(*pg_);
  }
  if (!options_.read_only && options_.new_session) {
    pg_->write([&] {
      session_ = pg_->query("UPDATE earc.store_meta SET value = value + 1 WHERE name = 'sessions' RETURNING value")
                     .int64At(0, 0);
    });
  } else {
    session_ = pg_->query("SELECT value FROM earc.store_meta WHERE name = 'sessions'").int64At(0, 0);
  }
  // A small store comes whole with its keys, and retrievals never wait for
  // the server; a large one fetches the k rows a retrieval misses.
  pg_preload_ = version_ > 0 && pgStoreFitsRowCache(*pg_, options_.row_cache_bytes);
  pgRefreshLocked(true);
}

void ExperienceStore::pgRefreshLocked(bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && (now - pg_polled_ < kPgPollInterval || now < pg_down_until_)) return;
  for (;;) {
    const bool whole = pg_preload_;
    PgResult r = pg_->retryLost(
        [&] { return pg_->query(whole ? pgSelectTailWithDeletionsSql() : kTailSql, PgParams().add(max_loaded_)); });
    pg_polled_ = now;
    const int id_col = whole ? 0 : 1;  // then kind, robot_count, signature, base_class, key
    const std::int64_t deletions = r.int64At(0, whole ? kPgRowColumns : 0);
    if (deletions != loaded_deletions_ && (max_loaded_ > 0 || index_.size() > 0)) {
      // Rows were deleted somewhere: the index may point at them; reload all.
      forgetRowsLocked();
      loaded_deletions_ = deletions;
      continue;
    }
    loaded_deletions_ = deletions;
    for (int i = 0; i < r.rows(); ++i) {
      if (r.isNull(i, id_col)) continue;
      const int c = id_col;
      indexKeyRowLocked(r.int64At(i, c), r.textAt(i, c + 1), r.int64At(i, c + 2), r.textAt(i, c + 3),
                        r.textAt(i, c + 4), r.bytesAt(i, c + 5));
      if (whole && pg_preload_) pgPreloadRowLocked(r, i);
    }
    index_.settle();
    return;
  }
}

void ExperienceStore::pgPreloadRowLocked(const PgResult& r, int row) {
  std::shared_ptr<const Experience> e;
  try {
    e = std::make_shared<const Experience>(readPgExperience(r, row));
  } catch (const CorruptRowError&) {
    return;  // the index skipped it too, or a retrieval reports it
  }
  // The store outgrew the cache: retrievals fetch what they miss from now on.
  if (row_cache_.bytes() + cachedRowBytes(*e) > row_cache_.maxBytes()) {
    pg_preload_ = false;
    return;
  }
  row_cache_.put(std::move(e));
}

std::vector<Match> ExperienceStore::pgNearestLocked(const ExperienceClass& cls, std::span<const double> key,
                                                    std::size_t k, std::size_t skip) {
  std::vector<Match> out;
  try {
    pgRefreshLocked(false);
    const ClassIndex* index = index_.find(cls);
    if (!index || index->dim() != key.size()) return out;
    out = matchesLocked(index->nearest(key, k), skip,
                        [&](const std::vector<std::int64_t>& ids) { return pgReadRowsLocked(ids); });
  } catch (const PgConnectionLostError& e) {
    // The server went away through every reconnection: planning goes on
    // without experience and tries the server again a while later.
    pg_down_until_ = std::chrono::steady_clock::now() + kPgRetryUnreachableAfter;
    std::fprintf(stderr, "earc: experience store: retrieval skipped: %s\n", e.what());
    out.clear();
  }
  return out;
}

std::vector<std::shared_ptr<const Experience>> ExperienceStore::pgReadRowsLocked(const std::vector<std::int64_t>& ids) {
  // The rows the cache lacks in one round trip; one deleted since the
  // index was loaded is not there.
  PgResult r = pg_->retryLost(
      [&] { return pg_->query(pgSelectExperiencesSql() + " WHERE id = ANY($1)", PgParams().addIds(ids)); });
  std::vector<std::shared_ptr<const Experience>> rows;
  for (int i = 0; i < r.rows(); ++i) {
    try {
      rows.push_back(std::make_shared<const Experience>(readPgExperience(r, i)));
    } catch (const CorruptRowError& e) {
      warnSkipped(r.int64At(i, 0), e.reason());
    }
  }
  return rows;
}

std::optional<Experience> ExperienceStore::pgFetchLocked(std::int64_t id) {
  PgResult r = pg_->retryLost(
      [&] { return pg_->query(pgSelectExperiencesSql() + " WHERE id = $1", PgParams().add(id)); });
  if (r.rows() == 0) return std::nullopt;
  return readPgExperience(r, 0);
}

std::vector<std::optional<std::int64_t>> ExperienceStore::pgInsertLocked(const std::vector<Experience>& batch,
                                                                         double eps, SessionStamp stamp) {
  const std::vector<Experience> rows = prepareRowsLocked(batch, stamp);
  std::vector<std::optional<std::int64_t>> ids;
  std::int64_t stored = 0;
  if (!history_described_) history_.describe("learn", "planning session " + std::to_string(session_));
  // A connection lost during COMMIT: this open's history line counts every
  // row it committed, so it tells whether the COMMIT went through.
  auto committed = [&] { return pgHistoryRowsAdded(*pg_, history_) == pg_rows_added_ + stored; };
  pg_->write(
      [&] {
        ids.clear();
        stored = 0;
        // Writers one at a time: every committed row is loaded, and nobody
        // can insert until we commit, so the duplicate check sees everything.
        pg_->exec("SELECT pg_advisory_xact_lock(" + std::to_string(kPgWriteLock) + ")");
        pgRefreshLocked(true);
        KeyIndex batch_index;  // rows of this transaction, for the in-batch check
        ids.assign(rows.size(), std::nullopt);
        // Rows to store, sent kPgInsertRows to a statement. Their ids come
        // from the sequence in VALUES order under the lock: ascending.
        std::vector<std::size_t> pending;
        auto send = [&] {
          if (pending.empty()) return;
          PgParams params;
          for (std::size_t i : pending) params.append(pgExperienceParams(rows[i]));
          PgResult r = pg_->query(pgInsertExperiencesSql(pending.size()), params);
          std::vector<std::int64_t> got;
          for (int j = 0; j < r.rows(); ++j) got.push_back(r.int64At(j, 0));
          std::sort(got.begin(), got.end());
          for (std::size_t j = 0; j < pending.size(); ++j) ids[pending[j]] = got.at(j);
          stored += static_cast<std::int64_t>(pending.size());
          pending.clear();
        };
        for (std::size_t i = 0; i < rows.size(); ++i) {
          const Experience& e = rows[i];
          if (nearDuplicate(batch_index, e, eps)) continue;
          if (eps >= 0) {
            batch_index.add(e.cls, static_cast<std::int64_t>(i), e.key);  // an id of this batch only
            if (i % ClassIndex::kBulkSettleEvery == 0) batch_index.settle();
          }
          pending.push_back(i);
          if (pending.size() == kPgInsertRows) send();
        }
        send();
        // As store.cpp's: a restored export's sessions.
        if (stamp == SessionStamp::AsGiven)
          pg_->exec(
              "UPDATE earc.store_meta SET value = GREATEST(value, (SELECT coalesce(max(created_session), 0) "
              "FROM earc.experiences)) WHERE name = 'sessions'");
        pgRecordHistory(*pg_, history_, stored, 0);
      },
      committed);
  pg_rows_added_ += stored;
  indexInsertedLocked(rows, ids);
  if (pg_preload_)
    for (std::size_t i = 0; i < rows.size() && pg_preload_; ++i)
      if (ids[i]) {
        auto e = std::make_shared<Experience>(rows[i]);
        e->id = *ids[i];
        if (row_cache_.bytes() + cachedRowBytes(*e) > row_cache_.maxBytes())
          pg_preload_ = false;
        else
          row_cache_.put(std::move(e));
      }
  return ids;
}

void ExperienceStore::pgFlushLocked() {
  pg_->write([&] {
    for (const auto& [id, counts] : pending_uses_)
      pg_->query(
          "UPDATE earc.experiences SET retrieved_count = LEAST(retrieved_count + $2, $4), "
          "succeeded_count = LEAST(succeeded_count + $3, $4) WHERE id = $1",
          PgParams().add(id).add(counts.first).add(counts.second).add(kMaxUseCount));
  });
  pending_uses_.clear();
}

PgConnection& ExperienceStore::pgConnection() {
  requireOpen();
  if (!pg_) throw std::logic_error("ExperienceStore::pgConnection: " + path_ + " is an SQLite file");
  return *pg_;
}

}  // namespace earc::exp
