#include "earc/experience/row_cache.hpp"

namespace earc::exp {

std::size_t cachedRowBytes(const Experience& e) {
  // The shared row, its paths' states and the strings' heap buffers, plus
  // a list node and a hash map entry (about 100 bytes on 64-bit targets).
  std::size_t n = sizeof(Experience) + 100 + e.key.capacity() * sizeof(double);
  n += e.cls.signature.capacity() + e.cls.base_class.capacity() + e.made_by.capacity();
  for (const Path& p : e.paths) n += sizeof(Path) + p.size() * static_cast<std::size_t>(p.dim()) * sizeof(double);
  return n;
}

// Rows are immutable once committed except for their usage counters, so a
// cached row stays right but for those; a deleted one is the owner's to drop.
std::shared_ptr<const Experience> RowCache::find(std::int64_t id) {
  auto it = by_id_.find(id);
  if (it == by_id_.end()) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  lru_.splice(lru_.begin(), lru_, it->second);
  return it->second->row;
}

void RowCache::put(std::shared_ptr<const Experience> row) {
  if (!row) return;
  if (auto it = by_id_.find(row->id); it != by_id_.end()) eraseEntry(it->second);
  const std::size_t bytes = cachedRowBytes(*row);
  if (bytes > max_bytes_) return;
  while (bytes_ + bytes > max_bytes_) eraseEntry(std::prev(lru_.end()));
  const std::int64_t id = row->id;
  lru_.push_front({std::move(row), bytes});
  by_id_[id] = lru_.begin();
  bytes_ += bytes;
}

void RowCache::eraseEntry(std::list<Entry>::iterator it) {
  bytes_ -= it->bytes;
  by_id_.erase(it->row->id);
  lru_.erase(it);
}

void RowCache::setMaxBytes(std::size_t max_bytes) {
  max_bytes_ = max_bytes;
  while (bytes_ > max_bytes_) eraseEntry(std::prev(lru_.end()));
}

void RowCache::clear() {
  lru_.clear();
  by_id_.clear();
  bytes_ = 0;
}

}  // namespace earc::exp
