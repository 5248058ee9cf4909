// A kd-tree over the samples of a point cloud (nanoflann), for the point-cloud oracle: the nearest
// sample of a point, and the nearest samples within a radius. Queries allocate nothing (for
// neighbourhoods of up to 72 samples and trees up to 64 levels deep; beyond, a buffer grows once per thread).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

/// Samples of R^d (n × d, row-major) and their kd-tree. Immutable after construction; queries are
/// const and may run concurrently from any number of threads.
class SampleTree {
 public:
  /// Largest d for which the point-cloud functions keep the last query in a fixed-size memo.
  static constexpr int kFixedMaxDimension = 10;

  SampleTree(std::vector<double> points, int d);
  ~SampleTree();
  SampleTree(const SampleTree&) = delete;
  SampleTree& operator=(const SampleTree&) = delete;

  int dimension() const { return d_; }
  std::size_t size() const { return points_.size() / d_; }
  const double* point(std::size_t i) const { return points_.data() + i * d_; }
  const std::vector<double>& points() const { return points_; }

  /// The nearest sample to x: its index, and the squared distance in *distance2.
  std::uint32_t nearest(const double* x, double* distance2) const;
  /// The (at most `capacity`) nearest samples at squared distance < radius2, nearest first:
  /// index[0..r), distance2[0..r); returns r. The arrays hold `capacity` entries.
  int nearest_within(const double* x, double radius2, int capacity, std::uint32_t* index, double* distance2) const;

  /// The tree keeps the samples in an order of its own (neighbours in space are mostly neighbours
  /// there). nearest_within answering with positions in that order (the same samples, the same
  /// distances); sample_at(position) is the sample's index. A caller that stores its per-sample
  /// data by position reads it from nearby memory.
  int nearest_within_by_position(const double* x, double radius2, int capacity, std::uint32_t* position,
                                 double* distance2) const;
  std::uint32_t sample_at(std::uint32_t position) const;

  struct Index;  // the kd-tree: nanoflann's, copied into a flat array

 private:
  std::vector<double> points_;
  int d_;
  std::unique_ptr<const Index> index_;
};

/// Fixed-capacity vectors and matrices for local statistics (no heap for d ≤ 31).
using LocalVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDimension, 1>;
using LocalSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxDimension, kMaxDimension>;

/// The centroid of the samples ids[0..count) (count ≥ 1) and the lower triangle of their scatter
/// matrix Σ (p − mean)(p − mean)ᵀ, for local PCA (SelfAdjointEigenSolver reads the lower triangle).
void local_scatter(const SampleTree& tree, const std::uint32_t* ids, int count, LocalVector& mean,
                   LocalSquare& scatter);

}  // namespace coxmesh
