// The per-class k-d tree with its linear tail answers exactly what a
// linear scan answers.
#include <doctest/doctest.h>

#include <random>

#include "earc/experience/key_index.hpp"
#include "earc/util/random.hpp"

using namespace earc;
using namespace earc::exp;

namespace {

std::vector<double> randomKey(std::mt19937_64& rng, std::size_t dim) {
  std::vector<double> k(dim);
  for (double& v : k) v = uniform(rng, -2, 2);
  return k;
}

}  // namespace

TEST_CASE("k-d tree retrieval with an unindexed tail equals brute force at every size") {
  std::mt19937_64 rng(11);
  ClassIndex index(8);
  std::int64_t id = 0;
  for (std::size_t target : {1u, 5u, 63u, 64u, 65u, 300u, 2100u, 5000u}) {
    while (index.size() < target) {
      index.add(++id, randomKey(rng, 8));
      if (id % 7 == 0) index.settle();
    }
    for (int q = 0; q < 20; ++q) {
      auto key = randomKey(rng, 8);
      auto a = index.nearest(key, 10);
      auto b = index.bruteForce(key, 10);
      REQUIRE(a.size() == std::min<std::size_t>(10, target));
      REQUIRE(a.size() == b.size());
      for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].id == b[i].id);
        CHECK(a[i].distance == doctest::Approx(b[i].distance));
      }
    }
  }
}

TEST_CASE("every key, rebuilt into the tree's order or in the tail, still answers with its own id") {
  // Rebuilding stores the keys in the order of the tree's leaves: an id
  // left behind there would answer a query with another key's row. A
  // linear scan over the same arrays cannot tell, so ask for each key.
  std::mt19937_64 rng(5);
  ClassIndex index(8);
  std::vector<std::vector<double>> keys;
  for (std::int64_t id = 1; id <= 3000; ++id) {
    keys.push_back(randomKey(rng, 8));
    index.add(id, keys.back());
    if (id % 500 == 0) index.rebuild();
  }
  index.add(3001, keys.front());  // a twin of id 1, in the tail
  keys.push_back(keys.front());
  REQUIRE(index.tailSize() == 1);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    auto n = index.nearest(keys[i], 1);
    REQUIRE(n.size() == 1);
    CHECK(n[0].distance == 0.0);
    // Ties go to the smaller id: the twin answers with id 1.
    CHECK(n[0].id == (i + 1 == keys.size() ? 1 : static_cast<std::int64_t>(i + 1)));
  }
}

TEST_CASE("the unindexed tail is folded into the tree once it outgrows its share") {
  std::mt19937_64 rng(3);
  ClassIndex index(4);
  for (int i = 0; i < 10000; ++i) {
    index.add(i + 1, randomKey(rng, 4));
    index.settle();
    const double limit = std::max<double>(kMinTailBeforeRebuild,
                                          kTailRebuildFraction * static_cast<double>(index.size() - index.tailSize()));
    REQUIRE(static_cast<double>(index.tailSize()) <= limit);
  }
  CHECK(index.tailSize() < index.size() / 16);
}

TEST_CASE("nearest answers ids in order of distance, ties by id") {
  ClassIndex index(2);
  index.add(5, std::vector<double>{1, 0});
  index.add(3, std::vector<double>{0, 1});
  index.add(9, std::vector<double>{3, 0});
  auto n = index.nearest(std::vector<double>{0, 0}, 3);
  REQUIRE(n.size() == 3);
  CHECK(n[0].id == 3);
  CHECK(n[1].id == 5);
  CHECK(n[2].id == 9);
  CHECK(n[2].distance == doctest::Approx(3.0));
}

TEST_CASE("a key of the wrong dimension is refused by its class") {
  KeyIndex keys;
  ExperienceClass cls{RobotKind::Mobile, 2, "a|a", ""};
  keys.add(cls, 1, std::vector<double>(8, 0.0));
  CHECK_THROWS_AS(keys.add(cls, 2, std::vector<double>(4, 0.0)), std::invalid_argument);
  CHECK(keys.size() == 1);
}
