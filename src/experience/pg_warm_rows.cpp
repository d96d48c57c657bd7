#include "pg_warm_rows.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "earc/experience/pg_schema.hpp"
#include "pg_warm_pack.hpp"

namespace earc::exp {

namespace {

// Rows per FETCH: few round trips, and a batch of memory at a time.
constexpr int kPgWarmBatch = 1000;
// The bookkeeping of a row's slot and of a distinct string, in bytes.
constexpr std::size_t kPgWarmSlotBytes = 16, kPgWarmStringBytes = 48;
// The copy is optional: a server slow to answer is not waited for long.
constexpr int kPgWarmConnectTimeoutS = 2;

}  // namespace

PgWarmRows::PgWarmRows(std::string location, std::size_t max_bytes)
    : location_(std::move(location)), max_bytes_(max_bytes), thread_([this] { read(); }) {}

PgWarmRows::~PgWarmRows() {
  {
    // A cancel that falls between two statements cancels nothing: again,
    // until the reading has ended.
    std::unique_lock<std::mutex> lock(mutex_);
    stop_ = true;
    while (!done_) {
      if (canceller_) canceller_->cancel();
      done_cv_.wait_for(lock, std::chrono::milliseconds(50));
    }
  }
  thread_.join();
}

void PgWarmRows::stop() {
  // The statement under way is cancelled: closing waits for a round trip,
  // not for a batch of rows read and packed.
  std::lock_guard<std::mutex> lock(mutex_);
  stop_ = true;
  if (canceller_) canceller_->cancel();
}

void PgWarmRows::read() {
  // Rows are immutable once committed but for their usage counters, so a
  // snapshot's rows stay right; rows committed later are fetched when a
  // retrieval misses them, and a deletion anywhere clears the copy.
  try {
    PgSettings settings;
    settings.connect_timeout_s = kPgWarmConnectTimeoutS;
    PgConnection pg(location_, settings);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      canceller_ = pg.canceller();
      if (stop_) throw StoreError("stopped");
    }
    pg.exec("BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY");
    pg.exec("DECLARE earc_warm BINARY NO SCROLL CURSOR FOR " + pgSelectExperiencesSql());
    PgWarmStringNumbers numbers;
    std::size_t bytes = 0;
    while (!stop_) {
      const PgResult r = pg.exec("FETCH " + std::to_string(kPgWarmBatch) + " FROM earc_warm");
      Batch batch;
      for (int i = 0; i < r.rows(); ++i) {
        batch.rows.emplace_back(r.int64At(i, 0), static_cast<std::uint32_t>(batch.bytes.size()));
        packPgWarmRow(r, i, numbers, batch.bytes);
      }
      batch.bytes.shrink_to_fit();
      batch.strings = numbers.takeAdded();
      bytes += batch.bytes.capacity() + batch.rows.size() * kPgWarmSlotBytes;
      for (const std::string& s : batch.strings) bytes += s.size() + kPgWarmStringBytes;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stop_) break;
        if (bytes > max_bytes_) {  // part of a store would serve few retrievals whole
          overflowed_ = true;
          staged_.clear();
          bytes_ = 0;
          break;
        }
        staged_.push_back(std::move(batch));
        bytes_ = bytes;
      }
      if (r.rows() < kPgWarmBatch) break;
    }
  } catch (const std::exception&) {
    // An unreachable server, a lost connection, a cancelled statement:
    // retrievals ask the server for what was not read, as without the copy.
  }
  std::lock_guard<std::mutex> lock(mutex_);
  canceller_.reset();
  done_ = true;
  done_cv_.notify_all();
}

void PgWarmRows::takeStaged() {
  std::vector<Batch> got;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    got.swap(staged_);
    if (overflowed_) {
      slots_.clear();
      batches_.clear();
      strings_.clear();
    }
  }
  const auto by_id = [](const Slot& a, const Slot& b) { return a.id < b.id; };
  for (Batch& b : got) {
    // Strings are numbered in the order they were first read, batch by batch.
    for (std::string& s : b.strings) strings_.push_back(std::move(s));
    const auto batch = static_cast<std::uint32_t>(batches_.size());
    batches_.push_back(std::move(b.bytes));
    const std::size_t old = slots_.size();
    for (const auto& [id, offset] : b.rows) slots_.push_back({id, batch, offset});
    // Table order is mostly id order: usually nothing to merge.
    std::sort(slots_.begin() + static_cast<std::ptrdiff_t>(old), slots_.end(), by_id);
    if (old > 0 && old < slots_.size() && slots_[old].id < slots_[old - 1].id)
      std::inplace_merge(slots_.begin(), slots_.begin() + static_cast<std::ptrdiff_t>(old), slots_.end(), by_id);
  }
}

const PgWarmRows::Slot* PgWarmRows::find(std::int64_t id) const {
  const auto it =
      std::lower_bound(slots_.begin(), slots_.end(), id, [](const Slot& s, std::int64_t v) { return s.id < v; });
  return it != slots_.end() && it->id == id ? &*it : nullptr;
}

bool PgWarmRows::has(std::int64_t id) {
  takeStaged();
  return find(id) != nullptr;
}

Experience PgWarmRows::decode(std::int64_t id) {
  const Slot* slot = find(id);
  if (!slot) throw std::out_of_range("PgWarmRows::decode: row " + std::to_string(id) + " is not held");
  return unpackPgWarmRow(id, batches_[slot->batch].data() + slot->offset, strings_);
}

void PgWarmRows::clear() {
  stop();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    staged_.clear();
    bytes_ = 0;
  }
  slots_.clear();
  batches_.clear();
  strings_.clear();
}

bool PgWarmRows::overflowed() {
  takeStaged();
  std::lock_guard<std::mutex> lock(mutex_);
  return overflowed_;
}

std::size_t PgWarmRows::bytes() {
  std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}

std::size_t PgWarmRows::awaitRead() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_cv_.wait(lock, [this] { return done_; });
  }
  takeStaged();
  return slots_.size();
}

}  // namespace earc::exp
