// A PostgreSQL store's rows read after the open, in the background, and
// kept packed (pg_warm_pack.hpp): a retrieval decodes a row from memory
// instead of asking the server for it. Not a public header.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "earc/experience/experience.hpp"
#include "earc/experience/pg_connection.hpp"

namespace earc::exp {

// Reads every row of a store on its own connection and thread, keeping all
// of them packed, or none once they pass the bound. Methods: one thread at
// a time (the store's mutex); the reader hands rows over under its own lock.
class PgWarmRows {
 public:
  // Starts reading the store at `location`, within max_bytes. A failure
  // only ends the reading early.
  PgWarmRows(std::string location, std::size_t max_bytes);
  // Stops the reading (cancelling the statement under way) and waits for it.
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
  // The memory the rows held take, bookkeeping included, approximately.
  std::size_t bytes();

 private:
  // Rows read in one batch: their packed bytes, each row's id and offset,
  // and the strings numbered first in it.
  struct Batch {
    std::vector<unsigned char> bytes;
    std::vector<std::pair<std::int64_t, std::uint32_t>> rows;
    std::vector<std::string> strings;
  };
  // Where a held row is: batch, offset.
  struct Slot {
    std::int64_t id;
    std::uint32_t batch;
    std::uint32_t offset;
  };
  void read();
  void takeStaged();
  void stop();
  const Slot* find(std::int64_t id) const;

  std::string location_;
  std::size_t max_bytes_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;  // guards staged_, done_, overflowed_, canceller_, bytes_
  std::condition_variable done_cv_;
  std::vector<Batch> staged_;  // read, not yet taken
  bool done_ = false;
  bool overflowed_ = false;
  std::size_t bytes_ = 0;
  std::unique_ptr<PgCanceller> canceller_;  // the reading connection's, while it reads
  // The store's thread only: rows by id, their batches' bytes, the strings.
  std::vector<Slot> slots_;
  std::vector<std::vector<unsigned char>> batches_;
  std::vector<std::string> strings_;
  std::thread thread_;
};

}  // namespace earc::exp
