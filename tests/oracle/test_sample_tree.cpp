// The sample tree's queries against nanoflann's own search on the same tree: the same samples in
// the same order with the same distances, ties included (the point-cloud functions sum over them in
// that order, so any other order would change the mesh in its last bits).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nanoflann.hpp>
#include <random>
#include <vector>

#include "coxmesh/oracle/sample_tree.h"
#include "point_samples.h"

namespace coxmesh {
namespace {

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

// The reference: the capacity nearest closer than the radius, each sorted into place as the search
// meets it, after the equal ones met before (what the tree's queries were before they were rewritten).
class SortedResult {
 public:
  using DistanceType = double;
  using IndexType = std::uint32_t;
  SortedResult(double radius2, std::size_t capacity) : radius2_(radius2), capacity_(capacity) {}
  std::size_t size() const { return index.size(); }
  bool full() const { return index.size() == capacity_; }
  double worstDist() const { return full() ? distance2.back() : radius2_; }
  bool addPoint(double dist, std::uint32_t i) {
    if (dist >= worstDist()) return true;
    if (full()) {
      index.pop_back();
      distance2.pop_back();
    }
    std::size_t at = index.size();
    while (at > 0 && distance2[at - 1] > dist) --at;
    index.insert(index.begin() + at, i);
    distance2.insert(distance2.begin() + at, dist);
    return true;
  }
  std::vector<std::uint32_t> index;
  std::vector<double> distance2;

 private:
  double radius2_;
  std::size_t capacity_;
};

using Reference = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Rows, double, std::uint32_t>,
                                                      Rows, -1, std::uint32_t>;

void expect_same_answers(const std::vector<double>& points, int d, const std::vector<double>& queries,
                         const char* what) {
  const SampleTree tree(points, d);
  const Rows rows{points.data(), points.size() / d, d};
  const Reference reference(d, rows, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  int checked = 0;
  for (std::size_t q = 0; q + d <= queries.size(); q += d) {
    const double* x = queries.data() + q;
    for (const double radius2 : {std::numeric_limits<double>::infinity(), 0.01, 0.1})
      for (const int capacity : {1, 2, 13, 32, 65, 200}) {
        SortedResult expected(radius2, capacity);
        reference.findNeighbors(expected, x, nanoflann::SearchParams());
        std::vector<std::uint32_t> index(capacity);
        std::vector<double> distance2(capacity);
        const int count = tree.nearest_within(x, radius2, capacity, index.data(), distance2.data());
        ASSERT_EQ(static_cast<std::size_t>(count), expected.size()) << what << ", query " << q / d;
        index.resize(count);
        distance2.resize(count);
        EXPECT_EQ(index, expected.index) << what << ", query " << q / d << ", capacity " << capacity;
        EXPECT_EQ(distance2, expected.distance2) << what << ", query " << q / d << ", capacity " << capacity;
        std::vector<std::uint32_t> position(capacity);
        ASSERT_EQ(tree.nearest_within_by_position(x, radius2, capacity, position.data(), distance2.data()), count);
        for (int i = 0; i < count; ++i) EXPECT_EQ(tree.sample_at(position[i]), index[i]);
        ++checked;
      }
    SortedResult nearest(std::numeric_limits<double>::infinity(), 1);
    reference.findNeighbors(nearest, x, nanoflann::SearchParams());
    double distance2 = 0;
    EXPECT_EQ(tree.nearest(x, &distance2), nearest.index[0]) << what;
    EXPECT_EQ(distance2, nearest.distance2[0]) << what;
  }
  EXPECT_GT(checked, 0);
}

// Queries at the samples, beside them and between them.
std::vector<double> queries_near(const std::vector<double>& points, int d, double offset) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> shift(-offset, offset);
  std::vector<double> q;
  for (std::size_t i = 0; i < points.size(); i += d * 37) {
    q.insert(q.end(), points.begin() + i, points.begin() + i + d);
    for (int t = 0; t < d; ++t) q.push_back(points[i + t] + shift(rng));
  }
  return q;
}

TEST(SampleTree, SameAnswersAsNanoflannOnRandomSamples) {
  for (const char* name : {"circle", "sphere", "torus", "flat-torus", "s3"}) {
    const test::Samples s = test::sample_manifold(name, 3000, 0.01);
    expect_same_answers(s.points, s.d, queries_near(s.points, s.d, 0.1), name);
  }
}

TEST(SampleTree, SameAnswersAsNanoflannWithTies) {
  // A grid of binary fractions and lattice-like queries: many samples at exactly equal distances,
  // where only the order of the search decides which comes first (or stays within the capacity).
  std::vector<double> grid, queries;
  for (int i = -12; i <= 12; ++i)
    for (int j = -12; j <= 12; ++j) grid.insert(grid.end(), {i / 16.0, j / 16.0, (i * i + j * j) % 3 / 16.0});
  for (int i = -24; i <= 24; i += 3)
    for (int j = -24; j <= 24; j += 5) queries.insert(queries.end(), {i / 32.0, j / 32.0, 1 / 32.0});
  expect_same_answers(grid, 3, queries, "grid");
  // Repeated samples: equal distances from every point.
  std::vector<double> repeated = grid;
  repeated.insert(repeated.end(), grid.begin(), grid.begin() + 3 * 50);
  expect_same_answers(repeated, 3, queries, "grid with repeated samples");
}

TEST(SampleTree, SameAnswersAsNanoflannOnAVeryDeepTree) {
  // Samples at 2^-i split off one at a time: a tree hundreds of levels deep (past the queries'
  // stack of 64 pending nodes).
  std::vector<double> chain;
  for (int i = 0; i < 700; ++i) chain.insert(chain.end(), {std::ldexp(1.0, -i), std::ldexp(0.5, -i), 0.0});
  for (int i = 0; i < 200; ++i) chain.insert(chain.end(), {i / 100.0, 1.0, 2.0});
  expect_same_answers(chain, 3, queries_near(chain, 3, 0.01), "chain");
}

}  // namespace
}  // namespace coxmesh
