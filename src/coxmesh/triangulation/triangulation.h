// Thesis §3.1 (FK triangulation; Coxeter Ã_d as a linear image of it), §3.4 (point location).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

/// The Freudenthal–Kuhn triangulation of R^d under the affine map x = Λ·y + b (y: lattice / FK
/// coordinates, x: Cartesian). Stores Λ, Λ^{-1} and b: O(d²) memory. Immutable and thread-safe.
///
///   auto T = Triangulation::coxeter(3).scaled(0.2);
///   Simplex s = T.locate(std::vector<double>{0.1, 0.2, 0.3});
///   std::vector<double> xs(4 * 3);  T.vertex_coordinates(s, xs.data());
class Triangulation {
 public:
  /// Λ must be square, finite and well conditioned (reciprocal condition number > 1e-12), b of size
  /// d; throws InputError otherwise.
  Triangulation(const Eigen::MatrixXd& matrix, const Eigen::VectorXd& offset);

  /// FK itself (Λ = I, b = 0).
  static Triangulation freudenthal(int d);
  /// Ã_d with unit heights, by the closed form of thesis §3.1: Λ = diag(μ_q^{-1/2})·Qᵀ·L^{-1},
  /// Q_{jq} = √(2/(d+1))·sin(jqπ/(d+1)), μ_q = 1 − cos(qπ/(d+1)).
  static Triangulation coxeter(int d);

  /// Λ ← s·Λ (the offset is kept). Throws unless s is finite and positive.
  Triangulation scaled(double s) const;
  /// Λ ← (h / longest_edge())·Λ, so that the longest edge of every d-simplex is h.
  Triangulation with_longest_edge(double h) const;
  /// b ← offset.
  Triangulation with_offset(const Eigen::VectorXd& offset) const;
  /// Λ ← O·Λ, b ← O·b, with O a Haar-random orthogonal matrix drawn from the seed (deterministic).
  Triangulation rotated(std::uint64_t seed) const;

  int dimension() const { return d_; }
  const Eigen::MatrixXd& matrix() const { return matrix_; }
  const Eigen::MatrixXd& inverse() const { return inverse_; }
  const Eigen::VectorXd& offset() const { return offset_; }
  bool is_freudenthal() const { return identity_; }

  /// Lattice (FK) coordinates Λ^{-1}(x − b) of a Cartesian point. O(d²).
  void lattice_coordinates(const double* x, double* y) const;
  /// Cartesian coordinates Λ·v + b of a lattice point. O(d²).
  void cartesian(const std::int32_t* v, double* x) const;
  /// Cartesian coordinates of all vertices of σ, (dim σ + 1) rows of d, incrementally (O(d²) in
  /// total: each step adds the columns of one block, thesis §3.3).
  void vertex_coordinates(const Simplex& sigma, double* out) const;

  /// The minimal simplex containing x (thesis §3.4). FK coordinates within 1e-9 of an integer are
  /// snapped to it and coordinates whose fractional parts differ by at most 1e-9 share a block,
  /// so points on lower-dimensional faces locate those faces. Throws InputError on a wrong size,
  /// NaN/Inf or a lattice coordinate beyond ±2^30. No allocation.
  Simplex locate(std::span<const double> x) const;
  /// locate() on a raw pointer to d coordinates, without the size check.
  Simplex locate(const double* x) const;

  /// Barycentric coordinates of x with respect to the vertices of σ (dim σ + 1 values). Exact for
  /// x in the affine hull of σ; otherwise those of the least-squares projection in FK coordinates.
  void barycentric(const Simplex& sigma, const double* x, double* lambda) const;

  /// Length of the longest edge of the d-simplices: max over non-empty A ⊆ {0..d−1} of |Λ·e_A|.
  /// Closed form for FK and Ã_d (and their scaled or rotated images); otherwise an exhaustive Gray
  /// code walk over the 2^d − 1 subsets, O(2^d·d), for d ≤ 24 (throws InputError beyond).
  double longest_edge() const;

 private:
  Triangulation() = default;
  void factorize();

  int d_ = 0;
  Eigen::MatrixXd matrix_, inverse_;
  // Λ^{-1} with zero rows appended up to padded_rows(d) = a multiple of 4 above d: the lattice
  // coordinate kernel computes whole 4-row groups, and rows d.. come out as 0.
  Eigen::MatrixXd padded_inverse_;
  Eigen::VectorXd offset_;
  bool identity_ = false;
  double known_longest_edge_ = 0;  // > 0 when the closed form applies
};

}  // namespace coxmesh
