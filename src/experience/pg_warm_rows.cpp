#include "pg_warm_rows.hpp"

#include <stdexcept>

namespace earc::exp {

namespace {

// Rows per FETCH: few round trips, and a stop waits for at most one batch.
constexpr int kPgWarmBatch = 1000;

}  // namespace

PgWarmRows::PgWarmRows(std::string location, std::size_t max_bytes)
    : location_(std::move(location)), max_bytes_(max_bytes), thread_([this] { read(); }) {}

PgWarmRows::~PgWarmRows() {
  stop_ = true;
  thread_.join();
}

void PgWarmRows::read() {
  // Rows are immutable once committed but for their usage counters, so a
  // snapshot's rows stay right; rows committed later are fetched when a
  // retrieval misses them, and a deletion anywhere clears the copy.
  try {
    PgConnection pg(location_);
    pg.exec("BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY");
    pg.exec("DECLARE earc_warm BINARY NO SCROLL CURSOR FOR " + pgSelectExperiencesSql());
    std::size_t bytes = 0;
    for (bool full = false; !full && !stop_;) {
      PgResult r = pg.exec("FETCH " + std::to_string(kPgWarmBatch) + " FROM earc_warm");
      std::vector<PgPackedRow> batch;
      for (int i = 0; i < r.rows() && !full; ++i) {
        PgPackedRow p = packPgRow(r, i);
        bytes += packedPgRowBytes(p);
        full = bytes > max_bytes_;
        if (!full) batch.push_back(std::move(p));
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stop_) break;
        for (PgPackedRow& p : batch) staged_.push_back(std::move(p));
        if (full) {  // part of a store would serve few retrievals whole
          overflowed_ = true;
          staged_.clear();
        }
      }
      if (r.rows() < kPgWarmBatch) break;
    }
  } catch (const std::exception&) {
    // An unreachable server or a lost connection: retrievals ask the
    // server for what was not read, as without the copy.
  }
  std::lock_guard<std::mutex> lock(mutex_);
  done_ = true;
  done_cv_.notify_all();
}

void PgWarmRows::takeStaged() {
  std::vector<PgPackedRow> got;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    got.swap(staged_);
    if (overflowed_) held_.clear();
  }
  for (PgPackedRow& p : got) {
    const std::int64_t id = p.id;
    held_.insert_or_assign(id, std::move(p));
  }
}

bool PgWarmRows::has(std::int64_t id) {
  takeStaged();
  return held_.count(id) > 0;
}

Experience PgWarmRows::decode(std::int64_t id) { return readPgExperience(held_.at(id)); }

void PgWarmRows::clear() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    staged_.clear();
  }
  held_.clear();
}

bool PgWarmRows::overflowed() {
  takeStaged();
  std::lock_guard<std::mutex> lock(mutex_);
  return overflowed_;
}

std::size_t PgWarmRows::awaitRead() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_cv_.wait(lock, [this] { return done_; });
  }
  takeStaged();
  return held_.size();
}

}  // namespace earc::exp
