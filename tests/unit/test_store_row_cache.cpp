// The store's cache of retrieved rows: its bound and order on its own, and
// on an SQLite file (row_cache_checks.hpp; test_pg_store.cpp runs the same
// checks on PostgreSQL).
#include <doctest/doctest.h>

#include "earc/experience/scratch.hpp"
#include "row_cache_checks.hpp"

using namespace earc;
using namespace earc::exp;

namespace {

std::shared_ptr<const Experience> rowCacheRow(std::int64_t id, std::mt19937_64& rng) {
  const std::vector<RobotTraits> two(2, test::discTraits(0.3));
  Experience e = straightLineExperience(two, sampleMobileQuery(2, rng), 8);
  e.id = id;
  return std::make_shared<const Experience>(std::move(e));
}

}  // namespace

TEST_CASE("RowCache keeps the most recently used rows within its bound") {
  std::mt19937_64 rng(3);
  const std::size_t one = cachedRowBytes(*rowCacheRow(1, rng));
  RowCache cache(3 * one + one / 2);  // three rows of this size
  for (std::int64_t id = 1; id <= 3; ++id) cache.put(rowCacheRow(id, rng));
  CHECK(cache.size() == 3);
  CHECK(cache.bytes() <= cache.maxBytes());
  REQUIRE(cache.find(1));  // 1 is now the most recently used; 2 the least
  cache.put(rowCacheRow(4, rng));
  CHECK(cache.size() == 3);
  CHECK_FALSE(cache.find(2));
  CHECK(cache.find(1));
  CHECK(cache.find(3));
  CHECK(cache.find(4)->id == 4);
  CHECK(cache.hits() == 4);
  CHECK(cache.misses() == 1);

  // The same id again replaces the row, not adds one.
  auto again = rowCacheRow(3, rng);
  cache.put(again);
  CHECK(cache.size() == 3);
  CHECK(cache.find(3) == again);

  cache.clear();
  CHECK(cache.size() == 0);
  CHECK(cache.bytes() == 0);
  CHECK_FALSE(cache.find(1));
}

TEST_CASE("RowCache keeps nothing with a bound of 0 or a row larger than its bound") {
  std::mt19937_64 rng(4);
  RowCache off(0);
  off.put(rowCacheRow(1, rng));
  CHECK(off.size() == 0);
  const auto row = rowCacheRow(2, rng);
  RowCache small(cachedRowBytes(*row) - 1);
  small.put(row);
  CHECK(small.size() == 0);
  CHECK(small.bytes() == 0);
}

TEST_CASE("An SQLite store's row cache follows rows committed and deleted by others, within its bound") {
  ScratchDirectory dir("row-cache");
  test::checkRowCacheFollowsStore(dir.file("cache.db"));
}

TEST_CASE("A store without a row cache reads every row every time") {
  ScratchDirectory dir("row-cache");
  std::mt19937_64 rng(5);
  const std::vector<RobotTraits> two(2, test::discTraits(0.3));
  const Experience e = straightLineExperience(two, sampleMobileQuery(2, rng), 8);
  StoreOptions off;
  off.row_cache_bytes = 0;
  ExperienceStore store(dir.file("off.db"), off);
  store.insert(e, -1);
  for (int i = 0; i < 3; ++i) CHECK(store.nearest(e.cls, e.key, 1).size() == 1);
  CHECK(store.retrievalStats().retrievals == 3);
  CHECK(store.retrievalStats().rows == 3);
  CHECK(store.retrievalStats().cache_hits == 0);
  CHECK(store.retrievalStats().cache_misses == 3);
  CHECK(store.rowCacheSize().first == 0);
}
