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
#include <map>

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
  pgRefreshLocked(true);
}

void ExperienceStore::pgRefreshLocked(bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && (now - pg_polled_ < kPgPollInterval || now < pg_down_until_)) return;
  for (;;) {
    PgResult r = pg_->retryLost([&] { return pg_->query(kTailSql, PgParams().add(max_loaded_)); });
    pg_polled_ = now;
    const std::int64_t deletions = r.int64At(0, 0);
    if (deletions != loaded_deletions_ && (max_loaded_ > 0 || index_.size() > 0)) {
      // Rows were deleted somewhere: the index may point at them; reload all.
      index_.clear();
      max_loaded_ = 0;
      loaded_deletions_ = deletions;
      continue;
    }
    loaded_deletions_ = deletions;
    for (int i = 0; i < r.rows(); ++i)
      if (!r.isNull(i, 1))
        indexKeyRowLocked(r.int64At(i, 1), r.textAt(i, 2), r.int64At(i, 3), r.textAt(i, 4), r.textAt(i, 5),
                          r.bytesAt(i, 6));
    index_.settle();
    return;
  }
}

std::vector<Match> ExperienceStore::pgNearestLocked(const ExperienceClass& cls, std::span<const double> key,
                                                    std::size_t k, std::size_t skip) {
  std::vector<Match> out;
  try {
    pgRefreshLocked(false);
    const ClassIndex* index = index_.find(cls);
    if (!index || index->dim() != key.size()) return out;
    const std::vector<Neighbor> near = index->nearest(key, k);
    if (near.size() <= skip) return out;
    std::vector<std::int64_t> ids;
    for (std::size_t i = skip; i < near.size(); ++i) ids.push_back(near[i].id);
    // The k rows in one round trip.
    PgResult r = pg_->retryLost(
        [&] { return pg_->query(pgSelectExperiencesSql() + " WHERE id = ANY($1)", PgParams().addIds(ids)); });
    std::map<std::int64_t, int> at;
    for (int i = 0; i < r.rows(); ++i) at[r.int64At(i, 0)] = i;
    for (std::size_t i = skip; i < near.size(); ++i) {
      auto it = at.find(near[i].id);
      if (it == at.end()) continue;  // deleted since the index was loaded
      try {
        out.push_back({readPgExperience(r, it->second), near[i].distance});
      } catch (const CorruptRowError& e) {
        warnSkipped(near[i].id, e.reason());
      }
    }
  } catch (const PgConnectionLostError& e) {
    // The server went away through every reconnection: planning goes on
    // without experience and tries the server again a while later.
    pg_down_until_ = std::chrono::steady_clock::now() + kPgRetryUnreachableAfter;
    std::fprintf(stderr, "earc: experience store: retrieval skipped: %s\n", e.what());
    out.clear();
  }
  return out;
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
