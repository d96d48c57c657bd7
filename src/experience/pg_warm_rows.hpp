// A PostgreSQL store's rows read after the open, in the background, and
// kept packed (as the server sent them): a retrieval decodes a row from
// memory instead of asking the server for it. Not a public header.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "earc/experience/experience.hpp"
#include "earc/experience/pg_schema.hpp"

namespace earc::exp {

// Reads every row of a store on a connection and a thread of its own (one
// snapshot, in batches) and keeps them all, or none once their packed bytes
// pass the bound. Methods: one thread at a time (the store's mutex); the
// reading thread hands rows over under its own lock.
class PgWarmRows {
 public:
  // Starts reading the store at `location`, within max_bytes
  // (packedPgRowBytes). A failure only ends the reading early.
  PgWarmRows(std::string location, std::size_t max_bytes);
  // Stops the reading (after the batch under way) and waits for it.
  ~PgWarmRows();
  PgWarmRows(const PgWarmRows&) = delete;
  PgWarmRows& operator=(const PgWarmRows&) = delete;

  // Whether the row with this id is held (read so far).
  bool has(std::int64_t id);
  // The held row with this id, decoded and checked. Throws CorruptRowError,
  // std::out_of_range when it is not held.
  Experience decode(std::int64_t id);
  // Stops the reading and forgets every row (the store deleted some).
  void clear();
  // Waits until the reading has ended; the rows held then.
  std::size_t awaitRead();
  // Whether the store did not fit: nothing is held, nothing will be.
  bool overflowed();

 private:
  void read();
  void takeStaged();

  std::string location_;
  std::size_t max_bytes_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;  // guards staged_ and done_
  std::condition_variable done_cv_;
  std::vector<PgPackedRow> staged_;  // read, not yet taken by find
  bool done_ = false;
  bool overflowed_ = false;  // guarded by mutex_
  std::unordered_map<std::int64_t, PgPackedRow> held_;  // the store's thread only
  std::thread thread_;
};

}  // namespace earc::exp
