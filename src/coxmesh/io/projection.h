// Points of R^d as points of R³ for the formats that only hold 3D points (VTU, OFF, PLY, OBJ,
// medit): an affine map x ↦ P·(x − c) chosen by `--project`.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace coxmesh {

/// x ↦ P·(x − center), P a 3 × d matrix (row-major), center a point of R^d.
struct Projection {
  int d = 0;
  std::vector<double> matrix;  ///< 3 × d, row-major
  std::vector<double> center;  ///< d
  /// False when the map is the identity of R³ (d = 3, default or "1,2,3"): the points are unchanged.
  bool changes_points = true;
};

/// Builds the projection named by `spec` for points of R^d:
///   ""          the first three coordinates (d > 3); the identity (d = 3); zeros appended (d < 3);
///   "i,j,k"     the coordinates i, j, k (1-based, 1 to 3 indices, missing ones are 0);
///   "pca"       the three principal axes of `points` (n × d), centred at their mean; each axis
///               signed so that its largest component is positive (deterministic);
///   otherwise   the path of a text file with 3 rows of d numbers ('#' comments), the matrix P.
/// Throws InputError when the spec does not fit d (an index outside 1..d, a matrix of the wrong
/// shape, NaN/Inf, an unreadable file).
Projection make_projection(const std::string& spec, int d, std::span<const double> points);

/// The projected points: n × 3, row after row, for `points` of n × d.
std::vector<double> project_points(const Projection& projection, std::span<const double> points);

}  // namespace coxmesh
