#include "earc/experience/key_index.hpp"

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace earc::exp {

namespace {

// Leaf size: nanoflann's default (docs/performance-log.md: others no better).
constexpr std::size_t kLeafSize = 10;

double squaredDistance(const double* a, const double* b, std::size_t dim) {
  double s = 0;
  for (std::size_t d = 0; d < dim; ++d) {
    double t = a[d] - b[d];
    s += t * t;
  }
  return s;
}

void keepNearest(std::vector<Neighbor>& v, std::size_t k) {
  auto less = [](const Neighbor& a, const Neighbor& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.id < b.id);
  };
  if (v.size() > k) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end(), less);
    v.resize(k);
  }
  std::sort(v.begin(), v.end(), less);
  for (Neighbor& n : v) n.distance = std::sqrt(n.distance);
}

}  // namespace

// The adaptor and tree types are Tree's own: the class holds them, so they
// cannot have internal linkage (GCC's -Wsubobject-linkage, in a unity build).
struct ClassIndex::Tree {
  // nanoflann's three-method adaptor over the first `count` keys.
  struct KeyCloud {
    const std::vector<double>* keys = nullptr;
    std::size_t dim = 0;
    std::size_t count = 0;
    std::size_t kdtree_get_point_count() const { return count; }
    double kdtree_get_pt(std::uint32_t idx, std::size_t d) const { return (*keys)[idx * dim + d]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };

  using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, KeyCloud>, KeyCloud, -1,
                                                     std::uint32_t>;

  KeyCloud cloud;
  KdTree tree;
  Tree(const std::vector<double>& keys, std::size_t dim, std::size_t count)
      : cloud{&keys, dim, count},
        tree(static_cast<KdTree::Dimension>(dim), cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize)) {}
};

ClassIndex::ClassIndex(std::size_t dim) : dim_(dim) {
  if (dim == 0) throw std::invalid_argument("ClassIndex: zero-dimensional keys");
}

ClassIndex::~ClassIndex() = default;

void ClassIndex::add(std::int64_t id, std::span<const double> key) {
  if (key.size() != dim_)
    throw std::invalid_argument("ClassIndex: key of dimension " + std::to_string(key.size()) + ", class has " +
                                std::to_string(dim_));
  keys_.insert(keys_.end(), key.begin(), key.end());
  ids_.push_back(id);
}

// A scan of a tail that small costs little next to a rebuild, which then
// comes seldom (figures in docs/performance-log.md).
void ClassIndex::settle() {
  const double limit = std::max<double>(static_cast<double>(kMinTailBeforeRebuild),
                                        kTailRebuildFraction * static_cast<double>(indexed_));
  if (static_cast<double>(tailSize()) > limit) rebuild();
}

void ClassIndex::rebuild() {
  if (tailSize() == 0 && tree_) return;
  if (ids_.size() > 0xffffffffu) throw std::length_error("ClassIndex: more than 2^32 keys in one class");
  tree_.reset();  // the old tree refers to its own cloud; build a fresh one
  indexed_ = ids_.size();
  if (indexed_ == 0) return;
  tree_ = std::make_unique<Tree>(keys_, dim_, indexed_);
  // The tree reaches its keys through a permutation (vAcc), a run of it per
  // leaf. Stored in that order, a leaf's keys lie side by side in memory
  // instead of a cache line each anywhere in the class, and the permutation
  // becomes the identity; the tree itself does not change
  // (docs/performance-log.md, "figures moved out of code comments").
  auto& order = tree_->tree.vAcc;
  std::vector<double> keys(keys_.size());
  std::vector<std::int64_t> ids(ids_.size());
  for (std::size_t i = 0; i < indexed_; ++i) {
    std::copy_n(keys_.begin() + static_cast<std::ptrdiff_t>(order[i] * dim_), dim_,
                keys.begin() + static_cast<std::ptrdiff_t>(i * dim_));
    ids[i] = ids_[order[i]];
    order[i] = static_cast<std::uint32_t>(i);
  }
  keys_.swap(keys);
  ids_.swap(ids);
}

std::vector<Neighbor> ClassIndex::nearest(std::span<const double> key, std::size_t k) const {
  if (key.size() != dim_) throw std::invalid_argument("ClassIndex::nearest: key dimension mismatch");
  std::vector<Neighbor> out;
  if (k == 0) return out;
  if (tree_ && indexed_ > 0) {
    const std::size_t want = std::min(k, indexed_);
    std::vector<std::uint32_t> idx(want);
    std::vector<double> d2(want);
    const std::size_t found = tree_->tree.knnSearch(key.data(), want, idx.data(), d2.data());
    for (std::size_t i = 0; i < found; ++i) out.push_back({ids_[idx[i]], d2[i]});
  }
  for (std::size_t i = indexed_; i < ids_.size(); ++i)
    out.push_back({ids_[i], squaredDistance(key.data(), keys_.data() + i * dim_, dim_)});
  keepNearest(out, k);
  return out;
}

std::vector<Neighbor> ClassIndex::bruteForce(std::span<const double> key, std::size_t k) const {
  if (key.size() != dim_) throw std::invalid_argument("ClassIndex::bruteForce: key dimension mismatch");
  // A bounded sorted list of the k best: what a careful linear scan costs.
  std::vector<Neighbor> best;
  best.reserve(k + 1);
  for (std::size_t i = 0; i < ids_.size() && k > 0; ++i) {
    const double d = squaredDistance(key.data(), keys_.data() + i * dim_, dim_);
    if (best.size() == k && d >= best.back().distance) continue;
    auto at = std::upper_bound(best.begin(), best.end(), d,
                               [](double v, const Neighbor& n) { return v < n.distance; });
    best.insert(at, {ids_[i], d});
    if (best.size() > k) best.pop_back();
  }
  keepNearest(best, k);
  return best;
}

const ClassIndex* KeyIndex::find(const ExperienceClass& cls) const {
  auto it = classes_.find(cls);
  return it == classes_.end() ? nullptr : it->second.get();
}

void KeyIndex::add(const ExperienceClass& cls, std::int64_t id, std::span<const double> key) {
  auto it = classes_.find(cls);
  if (it == classes_.end()) it = classes_.emplace(cls, std::make_unique<ClassIndex>(key.size())).first;
  it->second->add(id, key);
}

void KeyIndex::settle() {
  for (auto& [cls, index] : classes_) index->settle();
}

std::size_t KeyIndex::size() const {
  std::size_t n = 0;
  for (const auto& [cls, index] : classes_) n += index->size();
  return n;
}

}  // namespace earc::exp
