// Thesis Ch. 2 (quality of Coxeter triangulations: §2.1, §2.3–§2.5), Def. 1.1.48 (Delaunay).
// Quality measures of a d-simplex, the Delaunay property and protection of a Coxeter triangulation.
//
// Conventions (thesis §2.1): L longest edge, l shortest edge, h_i the height from v_i (distance to the
// hyperplane of the opposite facet), R circumradius, r inradius. thickness = h_min/L (thesis intro),
// thickness_normalized = h_min/(d·L) (Boissonnat–Dyer–Ghosh), radius ratio r/R, fatness vol/L^d,
// aspect ratio h_min/R. A Coxeter triangulation is monohedral, so its quality is that of its
// fundamental alcove. Protection δ = min over vertices q not in σ of |q − c(σ)| − R(σ), reported as δ/L.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "coxmesh/quality/alcove.h"

namespace coxmesh::quality {

/// Measures of one d-simplex.
struct SimplexMeasures {
  int dimension = 0;  ///< d
  double longest_edge = 0, shortest_edge = 0;
  double edge_ratio = 0;    ///< L / l
  Eigen::VectorXd heights;  ///< d+1: h_i
  double min_height = 0;
  Eigen::VectorXd circumcentre;              ///< d
  Eigen::VectorXd circumcentre_barycentric;  ///< d+1, summing to 1
  double circumradius = 0, inradius = 0, volume = 0;
  double thickness = 0;             ///< h_min / L
  double thickness_normalized = 0;  ///< h_min / (d·L)
  double radius_ratio = 0;          ///< r / R
  double fatness = 0;               ///< vol / L^d
  double aspect_ratio = 0;          ///< h_min / R
};

/// Measures of the simplex whose vertices are the rows of `vertices` ((d+1) × d, d ≥ 1). O(d³).
/// Throws InputError if the shape is wrong, a coordinate is not finite, or the simplex is degenerate.
SimplexMeasures measure_simplex(const Eigen::MatrixXd& vertices);

/// Closed forms for the regular d-simplex with unit edges: h = √((d+1)/(2d)), R = √(d/(2(d+1))),
/// r = 1/√(2d(d+1)), vol = √(d+1)/(d!·2^{d/2}). Throws InputError unless d ≥ 1.
SimplexMeasures regular_simplex_measures(int d);

/// Scale-invariant measures divided by those of the regular simplex of the same dimension (1 for
/// the regular simplex, < 1 otherwise).
struct RelativeMeasures {
  double thickness = 0;     ///< also the ratio for thickness_normalized
  double radius_ratio = 0;  ///< = d·r/R
  double fatness = 0;
  double aspect_ratio = 0;
};
RelativeMeasures relative_to_regular(const SimplexMeasures& m);

/// Delaunay status of a Coxeter triangulation.
enum class DelaunayStatus { yes, degenerate, no };
/// "yes", "degenerate" or "no".
std::string to_string(DelaunayStatus s);

/// Relative tolerance of both Delaunay decisions (on barycentric coordinates, resp. distances / L).
inline constexpr double kDelaunayTolerance = 1e-9;

struct DelaunayResult {
  DelaunayStatus status = DelaunayStatus::no;
  std::optional<double> protection;  ///< δ/L; 0 when degenerate, none when not Delaunay
};

/// The criterion of thesis §2.3 for the Coxeter triangulation with fundamental simplex m: Delaunay iff the
/// circumcentre lies in the closed simplex, non-degenerate iff in its interior (min barycentric
/// coordinate > tol). The neighbour across facet j being the mirror image, its opposite vertex v_j'
/// satisfies |c − v_j'|² = R² + 4·h_j²·λ_j(c); when the triangulation is Delaunay the vertex nearest
/// to c outside σ is one of these (see docs/quality.md), so δ = min_j √(R² + 4h_j²λ_j) − R.
DelaunayResult delaunay_by_circumcentre(const SimplexMeasures& m, double tol = kDelaunayTolerance);

/// Direct check on a generated neighbourhood: for every alcove of depth < max depth of `complex`
/// (normally generate_by_depth(alcove, 2)), no point of the complex strictly inside its circumball
/// (distance < R − tol·L) → "yes" or, when a point other than its vertices is on the sphere
/// (within tol·L), "degenerate"; protection = min over those alcoves and the points not on them of
/// (|q − c| − R)/L. Throws InputError if the complex has only depth 0. O(#alcoves·#points·d + d³·#alcoves).
DelaunayResult delaunay_direct(const AlcoveComplex& complex, double tol = kDelaunayTolerance);

/// Everything tabulated for one Coxeter triangulation, in the normalisation of Thm 1.2.15.
struct CoxeterQuality {
  Family family = Family::A;
  int dimension = 0;
  SimplexMeasures measures;  ///< of the fundamental alcove
  RelativeMeasures relative;
  DelaunayResult delaunay;                        ///< by the criterion of thesis §2.3, §2.5
  std::optional<DelaunayResult> delaunay_direct;  ///< on a generated neighbourhood, when computed
};

/// Quality of the Coxeter triangulation of affine type (f, d). direct_depth ≥ 1 also runs
/// delaunay_direct on generate_by_depth(alcove, direct_depth) (depth 1 checks the fundamental alcove
/// against its d+1 mirror images; depth 2 also checks those); 0 skips it. Throws InputError for an
/// unsupported (f, d) or a negative direct_depth.
///
///   CoxeterQuality q = coxeter_quality(Family::A, 3);
///   // q.measures.thickness == 1/√2; q.delaunay.status == DelaunayStatus::yes
CoxeterQuality coxeter_quality(Family f, int d, int direct_depth = 2);

}  // namespace coxmesh::quality
