// A bounded in-memory cache of decoded experience rows by id, for
// retrieval: a row once read need not be read and decoded again (nor, on
// PostgreSQL, fetched over the network). Least recently used rows go first.
#pragma once

#include <cstdint>
#include <list>
#include <memory>
#include <unordered_map>

#include "earc/experience/experience.hpp"

namespace earc::exp {

// The memory one cached row takes (its vectors and strings and the
// cache's own bookkeeping), approximately, in bytes.
std::size_t cachedRowBytes(const Experience& e);

// Decoded rows by id, least recently used dropped first; usage counters as
// read. The owner clears it after deletions in the store. Not thread-safe:
// the store serializes its use.
class RowCache {
 public:
  // Holds rows while their cachedRowBytes add up to at most max_bytes
  // (0: keeps nothing).
  explicit RowCache(std::size_t max_bytes) : max_bytes_(max_bytes) {}

  // The row with this id, or null; counts a hit or a miss and makes a
  // found row the most recently used.
  std::shared_ptr<const Experience> find(std::int64_t id);
  // Keeps the row (replacing one with its id), then drops the least
  // recently used until within the bound. A row alone over it is not kept.
  void put(std::shared_ptr<const Experience> row);
  void clear();
  // A new bound; the least recently used rows go until within it.
  void setMaxBytes(std::size_t max_bytes);

  std::size_t size() const { return by_id_.size(); }
  std::size_t bytes() const { return bytes_; }
  std::size_t maxBytes() const { return max_bytes_; }
  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }

 private:
  struct Entry {
    std::shared_ptr<const Experience> row;
    std::size_t bytes = 0;
  };
  void eraseEntry(std::list<Entry>::iterator it);

  std::size_t max_bytes_;
  std::size_t bytes_ = 0;
  std::list<Entry> lru_;  // most recently used first
  std::unordered_map<std::int64_t, std::list<Entry>::iterator> by_id_;
  std::uint64_t hits_ = 0;
  std::uint64_t misses_ = 0;
};

}  // namespace earc::exp
