// A k-d tree (nanoflann) over points stored flat in this object: build
// once, query many times. Points are in an embedding chosen by the caller
// (Euclidean distance there should approximate the caller's metric).
#pragma once

#include <nanoflann.hpp>

#include <cstddef>
#include <memory>
#include <vector>

namespace earc {

class PointIndex {
 public:
  explicit PointIndex(int dim) : cloud_{dim, {}} {}
  // A copy holds the same points; its tree is built again on its first
  // query (the tree refers to its own index's points).
  PointIndex(const PointIndex& other) : cloud_(other.cloud_) {}
  PointIndex& operator=(const PointIndex& other) {
    cloud_ = other.cloud_;
    tree_.reset();
    return *this;
  }

  int dim() const { return cloud_.dim; }
  std::size_t size() const { return cloud_.count(); }
  void add(const double* p) {
    cloud_.pts.insert(cloud_.pts.end(), p, p + cloud_.dim);
    tree_.reset();  // rebuilt lazily on the next query
  }
  void clear() {
    cloud_.pts.clear();
    tree_.reset();
  }
  const double* point(std::size_t i) const { return cloud_.pts.data() + i * static_cast<std::size_t>(cloud_.dim); }

  // Up to k nearest points (indices in insertion order), nearest first.
  std::vector<std::size_t> nearest(const double* q, std::size_t k) const {
    std::vector<std::size_t> idx;
    std::vector<double> d2;
    nearest(q, k, idx, d2);
    return idx;
  }
  // The same into idx, with d2 as scratch: a caller asking for many points
  // in a row keeps both and allocates nothing per query.
  void nearest(const double* q, std::size_t k, std::vector<std::size_t>& idx, std::vector<double>& d2) const {
    idx.clear();
    if (size() == 0 || k == 0) return;
    build();
    k = std::min(k, size());
    idx.resize(k);
    d2.resize(k);
    nanoflann::KNNResultSet<double, std::size_t> rs(k);
    rs.init(idx.data(), d2.data());
    tree_->findNeighbors(rs, q, nanoflann::SearchParams());
    idx.resize(rs.size());
  }

 private:
  struct Cloud {
    int dim;
    std::vector<double> pts;
    std::size_t count() const { return dim == 0 ? 0 : pts.size() / static_cast<std::size_t>(dim); }
    std::size_t kdtree_get_point_count() const { return count(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const { return pts[i * static_cast<std::size_t>(dim) + d]; }
    template <class B>
    bool kdtree_get_bbox(B&) const { return false; }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, -1, std::size_t>;
  void build() const {
    if (tree_) return;
    tree_ = std::make_unique<Tree>(cloud_.dim, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree_->buildIndex();
  }
  Cloud cloud_;
  mutable std::unique_ptr<Tree> tree_;
};

}  // namespace earc
