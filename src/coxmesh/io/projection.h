// Points of R^d as points of R³ for the formats that only hold 3D points (VTU, OFF, PLY, OBJ,
// medit, STL, Gmsh): an affine map x ↦ P·(x − c) chosen by `--project`, or a stereographic
// projection R^d → R^(d−1), which maps a manifold lying on a sphere without squashing it.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "coxmesh/arrays.h"
#include "coxmesh/cell_complex/cell_complex.h"

namespace coxmesh {

/// x ↦ P·(x − center), P a 3 × d matrix (row-major), center a point of R^d; stereographic:
/// x ↦ radius / ⟨center − x, normal⟩ · P·(x − center), with center the pole.
struct Projection {
  int d = 0;
  std::vector<double> matrix;  ///< 3 × d, row-major
  std::vector<double> center;  ///< d
  /// False when the map is the identity of R³ (d = 3, default or "1,2,3"): the points are unchanged.
  bool changes_points = true;
  /// Stereographic: from the pole (`center`), a point of the sphere of `radius` around `sphere_center`,
  /// onto the hyperplane through sphere_center orthogonal to normal = (pole − sphere_center)/radius;
  /// P's rows are the first three of an orthonormal basis of that hyperplane (zero rows when d < 4).
  bool stereographic = false;
  std::vector<double> normal, sphere_center;
  double radius = 0;
};

/// Builds the projection named by `spec` for points of R^d:
///   ""          the first three coordinates (d > 3); the identity (d = 3); zeros appended (d < 3);
///   "i,j,k"     the coordinates i, j, k (1-based, 1 to 3 indices, missing ones are 0);
///   "pca"       the three principal axes of `points` (n × d), centred at their mean; each axis
///               signed so that its largest component is positive (deterministic);
///   "stereographic"  from a pole on the sphere S around the centroid of `points` with their mean
///               distance to it as radius, to R^(d−1) (its first three coordinates; zeros appended
///               when d < 4): a point on S maps to the point where the line from the pole through it
///               meets the hyperplane through the centre orthogonal to the pole's direction, any
///               other point by the same central projection. The pole: `pole` if given (S then has
///               the radius |pole − centroid|), otherwise of the 2d points centre ± radius·e_i the
///               one farthest from all the points (the largest distance to the nearest point).
///   otherwise   the path of a text file with 3 rows of d numbers ('#' comments), the matrix P.
/// Throws InputError when the spec does not fit d (an index outside 1..d, a matrix of the wrong
/// shape, NaN/Inf, an unreadable file; a pole of the wrong size, a pole given without
/// "stereographic", a pole at the centroid).
Projection make_projection(const std::string& spec, int d, std::span<const double> points,
                           std::span<const double> pole = {});

/// The projected points: n × 3, row after row, for `points` of n × d.
///   Throws InputError (stereographic) when a point is not strictly on the far side of the pole's
///   tangent hyperplane (it has no image; give another pole).
std::vector<double> project_points(const Projection& projection, std::span<const double> points);

/// The complex's vertices in R³ in the global numbering (polygons.h: interior, then boundary), 3
/// numbers each: the complex's own array where it is its own projection (the identity of R³, no
/// boundary vertices, no coordinate −0, which the projection writes as +0), else project_points of
/// them into a copy. (A copy is n × 3 doubles written for the first time: pages to fault in.)
class ProjectedVertices {
 public:
  ProjectedVertices(const Projection& projection, const CellComplex& cc);
  std::span<const double> points() const { return own_.data() ? own_ : std::span<const double>(copy_); }

 private:
  std::span<const double> own_;  // (the complex's vertices, or empty)
  PointArray copy_;
};

}  // namespace coxmesh
