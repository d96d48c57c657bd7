// ExperienceStore's retrieval results, either engine: the k nearest rows
// from the row cache or read by the engine, and the counts of both.
#include <map>

#include "earc/experience/store.hpp"

namespace earc::exp {

std::vector<Match> ExperienceStore::matchesLocked(const std::vector<Neighbor>& near, std::size_t skip,
                                                  const RowReader& read) {
  ++retrievals_;
  std::vector<std::shared_ptr<const Experience>> rows(near.size());
  std::vector<std::int64_t> missing;
  for (std::size_t i = skip; i < near.size(); ++i)
    if (!(rows[i] = row_cache_.find(near[i].id))) missing.push_back(near[i].id);
  if (!missing.empty()) {
    // Committed rows never change but for their counters, and a deleted
    // one leaves the cache with the index (forgetRowsLocked).
    std::map<std::int64_t, std::shared_ptr<const Experience>> got;
    for (std::shared_ptr<const Experience>& row : read(missing)) {
      row_cache_.put(row);
      got[row->id] = std::move(row);
    }
    for (std::size_t i = skip; i < near.size(); ++i)
      if (!rows[i])
        if (auto it = got.find(near[i].id); it != got.end()) rows[i] = it->second;
  }
  std::vector<Match> out;
  for (std::size_t i = skip; i < near.size(); ++i)
    if (rows[i]) out.push_back({*rows[i], near[i].distance});
  rows_returned_ += out.size();
  return out;
}

ExperienceStore::RetrievalStats ExperienceStore::retrievalStats() const {
  std::lock_guard lock(mutex_);
  return {retrievals_, rows_returned_, row_cache_.hits(), row_cache_.misses()};
}

std::pair<std::size_t, std::size_t> ExperienceStore::rowCacheSize() const {
  std::lock_guard lock(mutex_);
  return {row_cache_.size(), row_cache_.bytes()};
}

}  // namespace earc::exp
