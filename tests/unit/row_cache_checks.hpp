// The row cache against a real store of either engine: shared by
// test_store_row_cache.cpp (an SQLite file) and test_pg_store.cpp (a
// PostgreSQL database on the test server).
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <thread>

#include "earc/experience/maintenance.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/store.hpp"
#include "support.hpp"

namespace earc::test {

// The ids nearest() returns, nearest first.
inline std::vector<std::int64_t> rowCacheMatchIds(exp::ExperienceStore& store, const exp::Experience& probe,
                                                  std::size_t k) {
  std::vector<std::int64_t> ids;
  for (const exp::Match& m : store.nearest(probe.cls, probe.key, k)) ids.push_back(m.experience.id);
  return ids;
}

// A reader whose cache holds four rows retrieves rows written by another
// connection; served again from its cache; sees a row the writer commits
// later; no longer sees one curate deleted; stays within its bound.
inline void checkRowCacheFollowsStore(const std::string& location) {
  std::mt19937_64 rng(21);
  const std::vector<exp::RobotTraits> two(2, discTraits(0.3));
  const exp::Experience e = exp::straightLineExperience(two, exp::sampleMobileQuery(2, rng), 8);
  exp::StoreOptions four;
  four.row_cache_bytes = 4 * exp::cachedRowBytes(e) + exp::cachedRowBytes(e) / 2;
  four.warm_rows = false;  // the decoded rows alone (PostgreSQL's copy: test_pg_store.cpp)
  exp::ExperienceStore writer(location);
  const std::int64_t first = *writer.insert(e, -1);
  const std::int64_t second = *writer.insert(e, -1);
  writer.recordUse(second, true);
  writer.flush();
  exp::ExperienceStore reader(location, four);

  // Read, then read again from the cache: the same rows.
  const std::vector<exp::Match> cold = reader.nearest(e.cls, e.key, 2);
  REQUIRE(cold.size() == 2);
  const auto before = reader.retrievalStats();
  const std::vector<exp::Match> warm = reader.nearest(e.cls, e.key, 2);
  const auto after = reader.retrievalStats();
  CHECK(after.cache_hits - before.cache_hits == 2);
  CHECK(after.cache_misses == before.cache_misses);
  REQUIRE(warm.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(warm[i].experience.id == cold[i].experience.id);
    CHECK(warm[i].experience.paths == e.paths);
    CHECK(warm[i].experience.key == e.key);
  }

  // A row committed through the other connection is found (PostgreSQL
  // polls for it at most kPgPollInterval apart; SQLite at once).
  const auto poll = exp::kPgPollInterval + std::chrono::milliseconds(20);
  const std::int64_t third = *writer.insert(e, -1);
  std::this_thread::sleep_for(poll);
  std::vector<std::int64_t> ids = rowCacheMatchIds(reader, e, 3);
  std::sort(ids.begin(), ids.end());
  CHECK(ids == std::vector<std::int64_t>{first, second, third});

  // curate keeps the used duplicate and deletes the others, which were
  // cached: after the next poll never returned again.
  exp::CurateSettings dedupe;
  dedupe.dedupe_eps = 1e-9;
  CHECK(exp::curateDatabase(location, dedupe).duplicates_removed == 2);
  std::this_thread::sleep_for(poll);
  CHECK(rowCacheMatchIds(reader, e, 3) == std::vector<std::int64_t>{second});
  CHECK(rowCacheMatchIds(reader, e, 3) == std::vector<std::int64_t>{second});

  // Twelve other rows through the four-row cache: it never holds more, and
  // a row it let go comes back from the store, whole.
  std::vector<exp::Experience> more;
  for (int i = 0; i < 12; ++i) more.push_back(exp::straightLineExperience(two, exp::sampleMobileQuery(2, rng), 8));
  const auto more_ids = writer.insertAll(more, -1);
  reader.refresh();
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < more.size(); ++i) {
      const std::vector<exp::Match> got = reader.nearest(more[i].cls, more[i].key, 1);
      REQUIRE(got.size() == 1);
      CHECK(got[0].experience.id == *more_ids[i]);
      CHECK(got[0].experience.paths == more[i].paths);
      CHECK(reader.rowCacheSize().first <= 4);
      CHECK(reader.rowCacheSize().second <= four.row_cache_bytes);
    }
  CHECK(reader.rowCacheSize().first == 4);
}

}  // namespace earc::test
