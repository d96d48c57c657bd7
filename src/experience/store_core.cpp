// ExperienceStore's engine-independent logic (StoreCore): the rows' checks
// on their way into the k-d trees, retrieval results from the row cache or
// read by the engine, and the near-duplicate check of an insert.
#include <chrono>
#include <cstdio>
#include <mutex>
#include <set>
#include <stdexcept>

#include "earc/experience/keys.hpp"
#include "earc/experience/path_blob.hpp"
#include "store_backend.hpp"

namespace earc::exp {

namespace {

std::int64_t nowUnixSeconds() {
  return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Whether a key length can belong to the class without reading the paths
// (the per-robot dimension lives in the path blob): exact for mobile
// robots, one of the possible lengths for arms. verify checks it exactly.
bool plausibleKeyDimension(const ExperienceClass& cls, std::size_t n) {
  if (cls.robot_count < 1) return false;
  if (cls.kind == RobotKind::Mobile) return n == static_cast<std::size_t>(keyDimension(cls.kind, cls.robot_count, 3));
  const std::size_t per_joint = static_cast<std::size_t>(2 * cls.robot_count);
  return n > 0 && n % per_joint == 0 && n / per_joint <= static_cast<std::size_t>(kArmKeyJoints);
}

}  // namespace

StoreCore::StoreCore(std::string location, const StoreOptions& opts)
    : path(std::move(location)), options(opts), row_cache(opts.row_cache_bytes) {}

void StoreCore::indexKeyRow(std::int64_t id, const std::string& kind_name, std::int64_t robot_count,
                            std::string signature, std::string base_class, std::span<const unsigned char> key_blob) {
  max_loaded = std::max(max_loaded, id);
  try {
    auto kind = kindFromName(kind_name);
    if (!kind) throw CorruptRowError(id, "unknown kind \"" + kind_name + "\"");
    ExperienceClass cls{*kind, static_cast<int>(robot_count), std::move(signature), std::move(base_class)};
    std::vector<double> key = decodeKey(key_blob, id);
    if (!plausibleKeyDimension(cls, key.size()))
      throw CorruptRowError(id, "key dimension " + std::to_string(key.size()) + " does not fit the class");
    const ClassIndex* existing = index.find(cls);
    if (existing && existing->dim() != key.size())
      throw CorruptRowError(id, "key dimension differs from the class's other rows");
    index.add(cls, id, key);
  } catch (const CorruptRowError& e) {
    warnSkipped(id, e.reason());
  }
}

void StoreCore::forgetRows() {
  index.clear();
  row_cache.clear();
  max_loaded = 0;
}

void StoreCore::warnSkipped(std::int64_t id, const std::string& why) const {
  if (!options.warn_skipped) return;
  static std::mutex warn_mutex;
  static std::set<std::pair<std::string, std::int64_t>> warned;
  std::lock_guard lock(warn_mutex);
  if (!warned.insert({path, id}).second) return;
  std::fprintf(stderr, "earc: experience store %s: skipping row %lld: %s (run earc-db verify)\n", path.c_str(),
               static_cast<long long>(id), why.c_str());
}

std::vector<Match> StoreCore::matches(const std::vector<Neighbor>& near, std::size_t skip,
                                      const std::function<SharedRows(const std::vector<std::int64_t>&)>& read) {
  ++retrievals;
  SharedRows rows(near.size());
  std::vector<std::int64_t> missing;
  for (std::size_t i = skip; i < near.size(); ++i)
    if (!(rows[i] = row_cache.find(near[i].id))) missing.push_back(near[i].id);
  if (!missing.empty()) {
    // Committed rows never change but for their counters, and a deleted
    // one leaves the cache with the index (forgetRows).
    std::map<std::int64_t, std::shared_ptr<const Experience>> got;
    for (std::shared_ptr<const Experience>& row : read(missing)) {
      row_cache.put(row);
      got[row->id] = std::move(row);
    }
    for (std::size_t i = skip; i < near.size(); ++i)
      if (!rows[i])
        if (auto it = got.find(near[i].id); it != got.end()) rows[i] = it->second;
  }
  std::vector<Match> out;
  for (std::size_t i = skip; i < near.size(); ++i)
    if (rows[i]) out.push_back({*rows[i], near[i].distance});
  rows_returned += out.size();
  return out;
}

std::vector<Experience> StoreCore::prepareRows(const std::vector<Experience>& batch, SessionStamp stamp) const {
  std::vector<Experience> rows = batch;
  const std::int64_t now = nowUnixSeconds();
  for (Experience& e : rows) {
    if (auto problem = findProblem(e)) throw std::invalid_argument("ExperienceStore::insert: " + *problem);
    if (e.created_at == 0) e.created_at = now;
    if (stamp == SessionStamp::ThisSession) e.created_session = session;
  }
  return rows;
}

std::vector<std::size_t> StoreCore::novelRows(const std::vector<Experience>& rows, double eps) const {
  std::vector<std::size_t> novel;
  if (eps < 0) {
    for (std::size_t i = 0; i < rows.size(); ++i) novel.push_back(i);
    return novel;
  }
  KeyIndex batch_index;  // the batch's rows kept so far, by their position
  const auto duplicate = [&](const Experience& e) {
    for (const ClassIndex* in : {index.find(e.cls), batch_index.find(e.cls)}) {
      if (!in) continue;
      if (in->dim() != e.key.size())
        throw std::invalid_argument("ExperienceStore::insert: key dimension " + std::to_string(e.key.size()) +
                                    " differs from the class's " + std::to_string(in->dim()));
      auto n = in->nearest(e.key, 1);
      if (!n.empty() && n.front().distance <= eps) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (duplicate(rows[i])) continue;
    batch_index.add(rows[i].cls, static_cast<std::int64_t>(i), rows[i].key);
    if (novel.size() % ClassIndex::kBulkSettleEvery == 0) batch_index.settle();
    novel.push_back(i);
  }
  return novel;
}

void StoreCore::indexInserted(const std::vector<Experience>& rows, const StoredIds& ids) {
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (ids[i]) {
      index.add(rows[i].cls, *ids[i], rows[i].key);
      max_loaded = std::max(max_loaded, *ids[i]);
    }
  index.settle();
}

void StoreCore::describeLearning() {
  if (!history_described) history.describe("learn", "planning session " + std::to_string(session));
}

}  // namespace earc::exp
