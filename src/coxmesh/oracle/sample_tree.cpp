// The kd-tree of a point cloud: nanoflann's single-index kd-tree instantiated for each d up to
// SampleTree::kFixedMaxDimension, so that a query's per-dimension distances live on the stack.
#include "coxmesh/oracle/sample_tree.h"

#include <limits>
#include <nanoflann.hpp>
#include <utility>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

namespace {

// nanoflann's view of the n × d row-major samples.
struct Rows {
  const double* data;
  std::size_t n;
  int d;
  std::size_t kdtree_get_point_count() const { return n; }
  double kdtree_get_pt(std::size_t i, std::size_t j) const { return data[i * d + j]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

// Keeps the `capacity` nearest samples closer than a radius, sorted, in caller-owned arrays (no
// allocation; nanoflann's own radius result set grows a std::vector).
class NearestWithin {
 public:
  using DistanceType = double;
  using IndexType = std::uint32_t;
  NearestWithin(double radius2, int capacity, std::uint32_t* index, double* distance2)
      : radius2_(radius2), capacity_(capacity), index_(index), distance2_(distance2) {}
  std::size_t size() const { return count_; }
  bool full() const { return count_ == capacity_; }
  double worstDist() const { return count_ == capacity_ ? distance2_[capacity_ - 1] : radius2_; }
  bool addPoint(double dist, std::uint32_t i) {
    if (dist >= worstDist()) return true;
    int pos = count_ < capacity_ ? count_++ : capacity_ - 1;
    for (; pos > 0 && distance2_[pos - 1] > dist; --pos) {
      distance2_[pos] = distance2_[pos - 1];
      index_[pos] = index_[pos - 1];
    }
    distance2_[pos] = dist;
    index_[pos] = i;
    return true;
  }

 private:
  double radius2_;
  int capacity_, count_ = 0;
  std::uint32_t* index_;
  double* distance2_;
};

}  // namespace

struct SampleTree::Index {
  virtual ~Index() = default;
  virtual int search(const double* x, NearestWithin& result) const = 0;
};

namespace {

template <int Dim>
class TreeIndex final : public SampleTree::Index {
 public:
  TreeIndex(const Rows& rows) : rows_(rows), tree_(rows.d, rows_, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
  int search(const double* x, NearestWithin& result) const override {
    tree_.findNeighbors(result, x, nanoflann::SearchParams());
    return static_cast<int>(result.size());
  }

 private:
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Rows, double, std::uint32_t>,
                                                   Rows, Dim, std::uint32_t>;
  Rows rows_;
  Tree tree_;
};

template <int Dim>
std::unique_ptr<const SampleTree::Index> make_index(const Rows& rows) {
  if constexpr (Dim > SampleTree::kFixedMaxDimension) {
    return std::make_unique<TreeIndex<-1>>(rows);
  } else {
    if (rows.d == Dim) return std::make_unique<TreeIndex<Dim>>(rows);
    return make_index<Dim + 1>(rows);
  }
}

}  // namespace

SampleTree::SampleTree(std::vector<double> points, int d) : points_(std::move(points)), d_(d) {
  check_dimension(d);
  if (points_.empty() || points_.size() % d != 0)
    throw InputError("a point cloud needs at least one point of R^" + std::to_string(d));
  if (points_.size() / d >= 0xFFFFFFFFu) throw InputError("too many samples (at most 2^32 − 1)");
  index_ = make_index<1>(Rows{points_.data(), points_.size() / d, d});
}

SampleTree::~SampleTree() = default;

std::uint32_t SampleTree::nearest(const double* x, double* distance2) const {
  std::uint32_t i = 0;
  *distance2 = std::numeric_limits<double>::infinity();
  NearestWithin result(std::numeric_limits<double>::infinity(), 1, &i, distance2);
  index_->search(x, result);
  return i;
}

int SampleTree::nearest_within(const double* x, double radius2, int capacity, std::uint32_t* index,
                               double* distance2) const {
  if (capacity <= 0) return 0;
  NearestWithin result(radius2, capacity, index, distance2);
  return index_->search(x, result);
}

void local_scatter(const SampleTree& tree, const std::uint32_t* ids, int count, LocalVector& mean,
                   LocalSquare& scatter) {
  const int d = tree.dimension();
  mean.setZero(d);
  for (int j = 0; j < count; ++j)
    for (int t = 0; t < d; ++t) mean[t] += tree.point(ids[j])[t];
  mean /= count;
  scatter.setZero(d, d);
  for (int j = 0; j < count; ++j) {
    const double* q = tree.point(ids[j]);
    for (int r = 0; r < d; ++r)
      for (int c = 0; c <= r; ++c) scatter(r, c) += (q[r] - mean[r]) * (q[c] - mean[c]);
  }
}

}  // namespace coxmesh
