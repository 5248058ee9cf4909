// The kd-tree of a point cloud. nanoflann builds it; its nodes are then copied into one flat array
// and the samples into coordinate-major arrays in the tree's order, and the queries run on that copy:
// they visit the same nodes in the same order and compute the same distances as nanoflann's search,
// so they find exactly what it finds (ties included), only faster (see "Point clouds" in
// docs/benchmarks.md).
#include "coxmesh/oracle/sample_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>
#include <utility>
#include <vector>

#include "coxmesh/lattice/simplex.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace coxmesh {

namespace {

constexpr int kLeafSize = 16;  // nanoflann's largest leaf

// nanoflann's view of the n × d row-major samples (only to build the tree).
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
using BuildTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Rows, double, std::uint32_t>,
                                                      Rows, -1, std::uint32_t>;

// The answer of one query, the `capacity` nearest closer than a radius, built so that the search
// prunes exactly as nanoflann's sorted result set makes it prune (its pruning test is not exact in
// floating point: with another bound it would visit other leaves and could find other samples).
// Until `capacity` samples are found the bound is the radius: the samples are appended in the order
// the search meets them, without a branch per sample (sorting each into place as it came cost a
// third of a query in mispredicted branches), and ranked at the end. When a leaf brings the count to
// `capacity` or more, the nearest `capacity` are ranked into place and the rest of the search sorts
// each newcomer in, as nanoflann does: from then on the bound is the capacity-th distance. Either
// way the answer is the `capacity` smallest by (distance, order met).
class Candidates {
 public:
  Candidates(double radius2, int capacity, std::uint32_t* index, double* distance2)
      : bound_(radius2), capacity_(capacity), index_(index), distance2_(distance2) {
    slot_ = on_stack_.data();
    if (capacity_ + kLeafSize > kOnStack) {  // (only neighbourhoods larger than the defaults: grown once a thread)
      if (static_cast<int>(scratch().size()) < capacity_ + kLeafSize) scratch().resize(capacity_ + kLeafSize);
      slot_ = scratch().data();
    }
  }
  double bound() const { return bound_; }
  /// Positions first, first + 1, … at squared distances d2[0..count) (count ≤ kLeafSize).
  void add_leaf(const double* d2, int count, std::uint32_t first) {
    if (sorted_) {
      for (int i = 0; i < count; ++i)
        if (d2[i] < bound_) insert(d2[i], first + static_cast<std::uint32_t>(i));
      return;
    }
    const double bound = bound_;
    for (int i = 0; i < count; ++i) {
      slot_[count_] = {d2[i], first + static_cast<std::uint32_t>(i)};
      count_ += d2[i] < bound;
    }
    if (count_ >= capacity_) {
      rank_into_answer();
      count_ = capacity_;
      sorted_ = true;
      bound_ = distance2_[capacity_ - 1];
    }
  }
  /// The answer, nearest first, in index[0..r) (positions in the tree) and distance2[0..r); returns r.
  int finish() {
    if (!sorted_) rank_into_answer();
    return count_;
  }

 private:
  struct Slot {
    double d2;
    std::uint32_t position;
  };
  static constexpr int kOnStack = 160;  // the PCA's 65 nearest and a leaf, with room to spare

  static std::vector<Slot>& scratch() {
    thread_local std::vector<Slot> buffer;
    return buffer;
  }

  // A newcomer nearer than the capacity-th: after the equal ones, the last one out.
  void insert(double d2, std::uint32_t position) {
    int at = capacity_ - 1;
    for (; at > 0 && distance2_[at - 1] > d2; --at) {
      distance2_[at] = distance2_[at - 1];
      index_[at] = index_[at - 1];
    }
    distance2_[at] = d2;
    index_[at] = position;
    bound_ = distance2_[capacity_ - 1];
  }

  // The candidates' ranks by (distance, order met); those below `capacity` go to their place.
  void rank_into_answer() {
    if (count_ > kOnStack) {  // (very large neighbourhoods: a stable insertion sort)
      int kept = 0;
      for (int i = 0; i < count_; ++i) {
        if (kept == capacity_ && !(slot_[i].d2 < distance2_[capacity_ - 1])) continue;
        int at = kept < capacity_ ? kept++ : capacity_ - 1;
        for (; at > 0 && distance2_[at - 1] > slot_[i].d2; --at) {
          distance2_[at] = distance2_[at - 1];
          index_[at] = index_[at - 1];
        }
        distance2_[at] = slot_[i].d2;
        index_[at] = slot_[i].position;
      }
      return;
    }
    alignas(16) std::array<double, kOnStack> d;
    alignas(16) std::array<std::int64_t, kOnStack> behind;  // minus the number ranked before
    std::fill_n(behind.begin(), count_, 0);
    for (int i = 0; i < count_; ++i) d[i] = slot_[i].d2;
    count_behind(d.data(), behind.data(), count_);
    for (int i = 0; i < count_; ++i) {
      const auto rank = static_cast<int>(-behind[i]);
      if (rank >= capacity_) continue;
      index_[rank] = slot_[i].position;
      distance2_[rank] = d[i];
    }
  }

  // Each candidate's rank: those before it at most as far, and those after it nearer. Each pair is
  // compared once: the later one is behind exactly when the earlier one is at most as far. (Counts
  // are kept negated: a true comparison is a lane of all ones, −1.)
  static void count_behind(const double* d, std::int64_t* behind, int count) {
    for (int i = 0; i < count; ++i) {
      const double di = d[i];
      std::int64_t before = 0;
      int j = 0;
#if defined(__SSE2__)
      const __m128d vi = _mm_set1_pd(di);
      __m128i sum = _mm_setzero_si128();
      for (; j + 2 <= i; j += 2) {
        const __m128i le = _mm_castpd_si128(_mm_cmple_pd(_mm_load_pd(d + j), vi));
        sum = _mm_add_epi64(sum, le);
        __m128i* b = reinterpret_cast<__m128i*>(behind + j);
        _mm_store_si128(b, _mm_add_epi64(_mm_load_si128(b), _mm_xor_si128(le, _mm_set1_epi64x(-1))));
      }
      alignas(16) std::array<std::int64_t, 2> lanes;
      _mm_store_si128(reinterpret_cast<__m128i*>(lanes.data()), sum);
      before = lanes[0] + lanes[1];
#endif
      for (; j < i; ++j) {
        const std::int64_t le = d[j] <= di ? -1 : 0;
        before += le;
        behind[j] += ~le;
      }
      behind[i] += before;
    }
  }

  double bound_;
  int capacity_, count_ = 0;
  bool sorted_ = false;
  std::uint32_t* index_;
  double* distance2_;
  std::array<Slot, kOnStack> on_stack_;
  Slot* slot_;
};

// A few nearest samples (the spacing's two), or nearest samples at any distance: sorted into place
// as they come, so that the bound tightens at once and prunes most of the tree.
class FewNearest {
 public:
  static constexpr int kAtMost = 4;
  FewNearest(double radius2, int capacity, std::uint32_t* index, double* distance2)
      : radius2_(radius2), capacity_(capacity), index_(index), distance2_(distance2) {}
  double bound() const { return count_ == capacity_ ? distance2_[capacity_ - 1] : radius2_; }
  void add_leaf(const double* d2, int count, std::uint32_t first) {
    for (int i = 0; i < count; ++i) {
      if (d2[i] >= bound()) continue;
      int at = count_ < capacity_ ? count_++ : capacity_ - 1;
      for (; at > 0 && distance2_[at - 1] > d2[i]; --at) {  // after the equal ones met before
        distance2_[at] = distance2_[at - 1];
        index_[at] = index_[at - 1];
      }
      distance2_[at] = d2[i];
      index_[at] = first + static_cast<std::uint32_t>(i);
    }
  }
  int count() const { return count_; }

 private:
  double radius2_;
  int capacity_, count_ = 0;
  std::uint32_t* index_;
  double* distance2_;
};

// The nearest sample only: the first met at the smallest distance.
class Nearest {
 public:
  double bound() const { return best_; }
  void add_leaf(const double* d2, int count, std::uint32_t first) {
    for (int i = 0; i < count; ++i)
      if (d2[i] < best_) {
        best_ = d2[i];
        position_ = first + static_cast<std::uint32_t>(i);
      }
  }
  std::uint32_t position() const { return position_; }

 private:
  double best_ = std::numeric_limits<double>::infinity();
  std::uint32_t position_ = 0;
};

}  // namespace

struct SampleTree::Index {
  // Interior: split on `feature`, child one at the next node, child two at `second`; the children's
  // extents along the feature end at `low` and begin at `high` (nanoflann's divlow, divhigh).
  // Leaf (feature < 0): the samples at positions [begin, end).
  struct Node {
    int feature;
    std::uint32_t second_or_end;
    std::uint32_t begin;
    double low, high;
  };
  static constexpr int kStackDepth = 64;
  int d;
  std::size_t n;
  int depth = 0;  // splits on the longest path from the root to a leaf
  std::vector<Node> nodes;
  std::vector<double> coordinates;      // coordinate t of the sample at position p: [t * n + p]
  std::vector<std::uint32_t> original;  // position in the tree → index of the sample
  std::vector<double> box_low, box_high;

  Index(const double* points, std::size_t count, int dimension) : d(dimension), n(count) {
    const Rows rows{points, n, d};
    BuildTree tree(d, rows, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
    original.assign(tree.vAcc.begin(), tree.vAcc.end());
    coordinates.resize(n * d);
    for (std::size_t p = 0; p < n; ++p)
      for (int t = 0; t < d; ++t) coordinates[t * n + p] = points[static_cast<std::size_t>(original[p]) * d + t];
    for (int t = 0; t < d; ++t) {
      box_low.push_back(tree.root_bbox[t].low);
      box_high.push_back(tree.root_bbox[t].high);
    }
    copy(tree.root_node, 0);
  }

  std::uint32_t copy(const BuildTree::Node* node, int level) {
    const auto at = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    depth = std::max(depth, level);
    if (node->child1 == nullptr && node->child2 == nullptr) {
      nodes[at] = {-1, static_cast<std::uint32_t>(node->node_type.lr.right),
                   static_cast<std::uint32_t>(node->node_type.lr.left), 0, 0};
      return at;
    }
    copy(node->child1, level + 1);
    const std::uint32_t second = copy(node->child2, level + 1);
    nodes[at] = {static_cast<int>(node->node_type.sub.divfeat), second, 0, node->node_type.sub.divlow,
                 node->node_type.sub.divhigh};
    return at;
  }

  // nanoflann's search (searchLevel) without recursion: at each split the nearer child first; the
  // other one, with its box distance grown along the split coordinate, waits on a stack and is
  // searched after the nearer one if still within the bound: the same nodes in the same order.
  template <int Dim, class Result>
  void search(const double* x, Result& result) const {
    constexpr int kDims = Dim > 0 ? Dim : kMaxDimension;
    struct Pending {
      std::uint32_t at;
      double box_distance2;
      std::array<double, kDims> dists;  // per coordinate: the box distance's share
    };
    // One pending node per level at most: on the stack for the usual depth (about log2(n / 8)),
    // else (very uneven samples) in a buffer grown once per thread.
    std::array<Pending, kStackDepth> on_stack;
    Pending* stack = on_stack.data();
    if (depth >= kStackDepth) {
      thread_local std::vector<Pending> deep;
      if (static_cast<int>(deep.size()) <= depth) deep.resize(depth + 1);
      stack = deep.data();
    }
    int top = 0;
    Pending& first = stack[top++];
    first.at = 0;
    first.box_distance2 = 0;
    const int dim = Dim > 0 ? Dim : d;
    first.dists.fill(0);
    for (int t = 0; t < dim; ++t) {
      if (x[t] < box_low[t]) {
        first.dists[t] = (x[t] - box_low[t]) * (x[t] - box_low[t]);
        first.box_distance2 += first.dists[t];
      }
      if (x[t] > box_high[t]) {
        first.dists[t] = (x[t] - box_high[t]) * (x[t] - box_high[t]);
        first.box_distance2 += first.dists[t];
      }
    }
    for (bool root = true; top > 0; root = false) {
      const Pending& p = stack[--top];
      if (!root && !(p.box_distance2 <= result.bound())) continue;
      std::uint32_t at = p.at;
      const double box_distance2 = p.box_distance2;
      std::array<double, kDims> dists = p.dists;  // (p's slot is reused by the first push)
      for (;;) {
        const Node& node = nodes[at];
        if (node.feature < 0) {
          const int count = static_cast<int>(node.second_or_end - node.begin);
          std::array<double, kLeafSize> d2;
          const double* c = coordinates.data() + node.begin;
          for (int i = 0; i < count; ++i) {
            double s = 0;  // (as nanoflann sums: from 0, coordinate by coordinate)
            for (int t = 0; t < dim; ++t) {
              const double diff = x[t] - c[t * n + i];
              s += diff * diff;
            }
            d2[i] = s;
          }
          result.add_leaf(d2.data(), count, node.begin);
          break;
        }
        const int f = node.feature;
        const double v = x[f];
        const bool first_is_near = (v - node.low) + (v - node.high) < 0;
        const double edge = first_is_near ? node.high : node.low;
        const double cut = (v - edge) * (v - edge);
        Pending& far = stack[top++];
        far.at = first_is_near ? node.second_or_end : at + 1;
        far.box_distance2 = box_distance2 + cut - dists[f];
        far.dists = dists;
        far.dists[f] = cut;
        at = first_is_near ? at + 1 : node.second_or_end;
      }
    }
  }

  template <class Result>
  void run(const double* x, Result& result) const {
    switch (d) {  // the common dimensions with the coordinate loop unrolled
      case 2:
        return search<2>(x, result);
      case 3:
        return search<3>(x, result);
      case 4:
        return search<4>(x, result);
      default:
        return search<-1>(x, result);
    }
  }
};

SampleTree::SampleTree(std::vector<double> points, int d) : points_(std::move(points)), d_(d) {
  check_dimension(d);
  if (points_.empty() || points_.size() % d != 0)
    throw InputError("a point cloud needs at least one point of R^" + std::to_string(d));
  if (points_.size() / d >= 0xFFFFFFFFu) throw InputError("too many samples (at most 2^32 − 1)");
  index_ = std::make_unique<const Index>(points_.data(), points_.size() / d, d);
}

SampleTree::~SampleTree() = default;

std::uint32_t SampleTree::nearest(const double* x, double* distance2) const {
  Nearest result;
  index_->run(x, result);
  *distance2 = result.bound();
  return index_->original[result.position()];
}

int SampleTree::nearest_within_by_position(const double* x, double radius2, int capacity, std::uint32_t* position,
                                           double* distance2) const {
  if (capacity <= 0) return 0;
  int count;
  if (capacity <= FewNearest::kAtMost || !std::isfinite(radius2)) {
    FewNearest result(radius2, capacity, position, distance2);
    index_->run(x, result);
    count = result.count();
  } else {
    Candidates result(radius2, capacity, position, distance2);
    index_->run(x, result);
    count = result.finish();
  }
  return count;
}

std::uint32_t SampleTree::sample_at(std::uint32_t position) const { return index_->original[position]; }

int SampleTree::nearest_within(const double* x, double radius2, int capacity, std::uint32_t* index,
                               double* distance2) const {
  const int count = nearest_within_by_position(x, radius2, capacity, index, distance2);
  for (int i = 0; i < count; ++i) index[i] = index_->original[index[i]];
  return count;
}

namespace {

// local_scatter for d known at compile time (Dim > 0) or not: the same sums in the same order.
template <int Dim>
void scatter_of(const SampleTree& tree, const std::uint32_t* ids, int count, LocalVector& mean, LocalSquare& scatter) {
  const int d = Dim > 0 ? Dim : tree.dimension();
  constexpr int kAtMost = Dim > 0 ? Dim : kMaxDimension;
  std::array<double, kAtMost> m;
  std::array<double, kAtMost * kAtMost> s;  // row-major lower triangle
  std::fill_n(m.begin(), d, 0.0);
  std::fill_n(s.begin(), d * d, 0.0);
  for (int j = 0; j < count; ++j) {
    const double* p = tree.point(ids[j]);
    for (int t = 0; t < d; ++t) m[t] += p[t];
  }
  for (int t = 0; t < d; ++t) m[t] /= count;
  for (int j = 0; j < count; ++j) {
    const double* q = tree.point(ids[j]);
    for (int r = 0; r < d; ++r)
      for (int c = 0; c <= r; ++c) s[r * d + c] += (q[r] - m[r]) * (q[c] - m[c]);
  }
  mean.resize(d);
  scatter.setZero(d, d);
  for (int r = 0; r < d; ++r) {
    mean[r] = m[r];
    for (int c = 0; c <= r; ++c) scatter(r, c) = s[r * d + c];
  }
}

}  // namespace

void local_scatter(const SampleTree& tree, const std::uint32_t* ids, int count, LocalVector& mean,
                   LocalSquare& scatter) {
  switch (tree.dimension()) {
    case 3:
      return scatter_of<3>(tree, ids, count, mean, scatter);
    case 4:
      return scatter_of<4>(tree, ids, count, mean, scatter);
    default:
      return scatter_of<-1>(tree, ids, count, mean, scatter);
  }
}

}  // namespace coxmesh
