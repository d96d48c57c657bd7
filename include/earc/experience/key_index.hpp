// In-memory k-nearest-neighbour index over experience keys: one nanoflann
// k-d tree per class (all keys of a class share one dimension) plus an
// un-indexed tail of keys added since the tree was built, searched
// linearly until it outgrows kTailRebuildFraction of the tree.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "earc/experience/experience.hpp"

namespace earc::exp {

struct Neighbor {
  std::int64_t id = 0;
  double distance = 0.0;  // Euclidean, in key space
};

// The tail is folded into the tree when it holds more than this fraction of
// the indexed keys and more than kMinTailBeforeRebuild.
inline constexpr double kTailRebuildFraction = 1.0 / 32.0;
inline constexpr std::size_t kMinTailBeforeRebuild = 64;

class ClassIndex {
 public:
  explicit ClassIndex(std::size_t dim);
  ~ClassIndex();
  ClassIndex(const ClassIndex&) = delete;
  ClassIndex& operator=(const ClassIndex&) = delete;

  std::size_t dim() const { return dim_; }
  std::size_t size() const { return ids_.size(); }
  std::size_t tailSize() const { return ids_.size() - indexed_; }

  // Appends a key to the tail (dimension must match).
  void add(std::int64_t id, std::span<const double> key);
  // Folds the tail into the tree when it outgrew its share. Call after a
  // batch of add(): rebuilding per key would cost a tree per few keys.
  void settle();
  // Keys to add between two settle() calls in bulk work (deduplicating a
  // batch): bounds the linear tail without rebuilding a tree per key.
  static constexpr std::size_t kBulkSettleEvery = 1024;
  // Folds the tail into the tree now.
  void rebuild();

  // Up to k nearest keys, nearest first (ties by id).
  std::vector<Neighbor> nearest(std::span<const double> key, std::size_t k) const;
  // The same answer by a linear scan of every key (benchmarks and tests).
  std::vector<Neighbor> bruteForce(std::span<const double> key, std::size_t k) const;

 private:
  struct Tree;
  std::size_t dim_;
  std::vector<double> keys_;  // size() * dim_
  std::vector<std::int64_t> ids_;
  std::size_t indexed_ = 0;   // keys [0, indexed_) are in the tree
  std::unique_ptr<Tree> tree_;
};

// One ClassIndex per class.
class KeyIndex {
 public:
  // nullptr when the class has no keys yet.
  const ClassIndex* find(const ExperienceClass& cls) const;
  // Adds a key to its class's index, creating the index on first use.
  // Throws std::invalid_argument when the key's dimension differs from the
  // class's earlier keys.
  void add(const ExperienceClass& cls, std::int64_t id, std::span<const double> key);
  // ClassIndex::settle for every class.
  void settle();
  void clear() { classes_.clear(); }
  std::size_t size() const;
  const std::map<ExperienceClass, std::unique_ptr<ClassIndex>>& classes() const { return classes_; }

 private:
  std::map<ExperienceClass, std::unique_ptr<ClassIndex>> classes_;
};

}  // namespace earc::exp
